#!/usr/bin/env python3
"""Writes the Cornell box with the Stanford bunny on its floor, as OBJ + MTL.

The sample Cornell box (samples/cornell-box.obj, millimetres) with the corpus's Stanford bunny
(bunny/stanford-bunny.obj, 69,451 triangles, no normals, so every renderer shades it flat), its
lowest point on the floor (y = 0), in the walls' white paint. Two layouts (the Cornell camera looks
along +z, so +x is image left):
  floor      (default) beside the blocks: x1000 (154 mm tall), centred at x = 430, z = 130; the
             scene of bench/sampler.sh and the speed-vs-error report;
  turntable  the blocks removed: x1500 (about 230 mm tall), centred at x = 278, z = 280, the middle
             of the floor; the scene of samples/turntable.jobs and bench/batch.sh.
The output is the same bytes for the same inputs.

usage: bench/cornell_bunny.py OUT_DIR [CORPUS_DIR] [--layout floor|turntable]
       writes OUT_DIR/cornell-bunny.obj and OUT_DIR/cornell-box.mtl (CORPUS_DIR defaults to
       ../shared/corpus beside the repository)
"""
import os
import shutil
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "samples"))
from obj_mesh import read_obj, write_atomically  # noqa: E402 (found through the line above)

# Per layout: scale, centre x and z, whether the two blocks stay.
LAYOUTS = {"floor": (1000.0, 430.0, 130.0, True), "turntable": (1500.0, 278.0, 280.0, False)}


def main():
    args = sys.argv[1:]
    layout = "floor"
    if "--layout" in args:
        at = args.index("--layout")
        layout = args[at + 1] if at + 1 < len(args) else ""
        del args[at:at + 2]
    if len(args) not in (1, 2) or layout not in LAYOUTS:
        sys.exit("usage: bench/cornell_bunny.py OUT_DIR [CORPUS_DIR] [--layout floor|turntable]")
    scale, centre_x, centre_z, keep_blocks = LAYOUTS[layout]
    out = args[0]
    corpus = args[1] if len(args) == 2 else os.path.join(REPO, "..", "shared", "corpus")
    bunny_path = os.path.join(corpus, "bunny", "stanford-bunny.obj")
    if not os.path.isfile(bunny_path):
        sys.exit(f"cornell_bunny.py: error: {bunny_path}: not found (the corpus is needed)")
    with open(os.path.join(REPO, "samples", "cornell-box.obj")) as f:
        box = f.read()
    if not keep_blocks:  # the blocks come last in the file
        box = box[:box.index("o short_block")]
    box_vertices = sum(1 for line in box.splitlines() if line.startswith("v "))

    vertices, faces = read_obj(bunny_path)
    vertices = [[x * scale for x in v] for v in vertices]
    lo = [min(v[i] for v in vertices) for i in range(3)]
    hi = [max(v[i] for v in vertices) for i in range(3)]
    shift = [centre_x - 0.5 * (lo[0] + hi[0]), -lo[1], centre_z - 0.5 * (lo[2] + hi[2])]

    os.makedirs(out, exist_ok=True)
    shutil.copyfile(os.path.join(REPO, "samples", "cornell-box.mtl"), os.path.join(out, "cornell-box.mtl"))
    lines = [box.rstrip("\n"), "", "# The Stanford bunny (Stanford 3D Scanning Repository, via the corpus), placed by",
             "# bench/cornell_bunny.py: x%g, lowest point on the floor, centred at x %g, z %g."
             % (scale, centre_x, centre_z), "o bunny",
             "usemtl white"]
    lines += ["v %.4f %.4f %.4f" % tuple(v[i] + shift[i] for i in range(3)) for v in vertices]
    lines += ["f " + " ".join(str(i + box_vertices if i > 0 else i) for i in face) for face in faces]
    path = os.path.join(out, "cornell-bunny.obj")
    write_atomically(path, "\n".join(lines) + "\n")
    print(f"{path}: {len(faces)} bunny triangles, bounds x {lo[0] + shift[0]:.1f}..{hi[0] + shift[0]:.1f}, "
          f"y 0..{hi[1] - lo[1]:.1f}, z {lo[2] + shift[2]:.1f}..{hi[2] + shift[2]:.1f}")


if __name__ == "__main__":
    main()
