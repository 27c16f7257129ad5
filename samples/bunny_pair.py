#!/usr/bin/env python3
"""Two Stanford bunnies on a floor, one glass and one copper, as an OBJ with its MTL:

  bunny_pair.py BUNNY.obj OUT.obj

The corpus bunny (about 0.15 units tall, standing on y = 0.033) is scaled to one unit, set on
y = 0 and placed twice side by side; the floor is a 6 x 6 square. Materials follow kdconvert's
MTL rules (formats/kdscene.md): illum 7 with Ni 1.5 is glass, a Ks above Kd with Ns 400 a rough
conductor of GGX alpha sqrt(2 / 402) = 0.07."""

import os
import sys

from obj_mesh import read_obj, write_atomically

SCALE = 1.0 / 0.155
PLACES = (("glass", -0.62), ("copper", 0.62))
MTL = """newmtl glass
Kd 1 1 1
Ni 1.5
illum 7

newmtl copper
Kd 0.05 0.05 0.05
Ks 0.95 0.64 0.54
Ns 400
illum 2

newmtl floor
Kd 0.55 0.55 0.52
illum 1
"""


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: bunny_pair.py BUNNY.obj OUT.obj")
    source, out = sys.argv[1], sys.argv[2]
    vertices, faces = read_obj(source)
    min_y = min(v[1] for v in vertices)
    centre_x = (min(v[0] for v in vertices) + max(v[0] for v in vertices)) / 2
    centre_z = (min(v[2] for v in vertices) + max(v[2] for v in vertices)) / 2
    mtl_path = os.path.splitext(out)[0] + ".mtl"
    lines = [f"mtllib {os.path.basename(mtl_path)}"]
    for index, (material, offset) in enumerate(PLACES):
        for x, y, z in vertices:
            lines.append(f"v {(x - centre_x) * SCALE + offset:.6f} {(y - min_y) * SCALE:.6f} {(z - centre_z) * SCALE:.6f}")
        lines.append(f"usemtl {material}")
        base = index * len(vertices)
        lines += ["f " + " ".join(str(base + i) for i in face) for face in faces]
    floor_base = len(PLACES) * len(vertices)
    s = 3.0
    lines += [f"v {x} 0 {z}" for x, z in ((-s, s), (s, s), (s, -s), (-s, -s))]
    lines += ["usemtl floor", f"f {floor_base + 1} {floor_base + 2} {floor_base + 3} {floor_base + 4}"]
    write_atomically(mtl_path, MTL)
    write_atomically(out, "\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
