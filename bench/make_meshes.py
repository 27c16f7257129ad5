#!/usr/bin/env python3
"""Large meshes unlike the corpus's, for the build and traversal benchmarks.

The corpus's large meshes are a subdivided scan (bunny_sub2) and copies of one scan
(dragons_4x4). Trees and traversals tuned on those alone may fit them; these three meshes have
other shapes of triangle distribution, made with a fixed seed so every run gets the same bytes:

  terrain  a fractal height field, 800 x 800 cells (1,280,000 triangles): one open sheet,
           triangles of even size, most rays meet it once
  city     a 316 x 316 grid of lots, one box each of log-uniform height, a third of them
           turned about +y (1,198,272 triangles): many triangles in shared axis-aligned planes,
           empty streets between them
  sticks   (only when named) 100,000 thin boxes dropped at random, overlapping about ten deep
           (1,200,000 triangles): a stress case where long thin triangles cross many voxels
           and the tree holds many references per triangle
  blob     a sphere subdivided 8 times (1,310,720 triangles) with its radius displaced by a sum
           of random waves: closed, curved, bumpy

usage: bench/make_meshes.py OUT_DIR [NAME...]   (writes OUT_DIR/NAME.ply, binary little-endian)
"""
import math
import os
import random
import struct
import sys
from array import array


def write_ply(path, positions, faces):
    """positions: array('f') of x, y, z; faces: array('i') of three indices per triangle."""
    vertex_count, face_count = len(positions) // 3, len(faces) // 3
    header = ("ply\nformat binary_little_endian 1.0\n"
              f"element vertex {vertex_count}\nproperty float x\nproperty float y\nproperty float z\n"
              f"element face {face_count}\nproperty list uchar int vertex_indices\nend_header\n")
    if sys.byteorder != "little":
        positions.byteswap()
        faces.byteswap()
    face_bytes = bytearray(13 * face_count)
    raw = faces.tobytes()
    for i in range(face_count):
        face_bytes[13 * i] = 3
        face_bytes[13 * i + 1:13 * i + 13] = raw[12 * i:12 * i + 12]
    temporary = path + ".tmp"
    with open(temporary, "wb") as out:
        out.write(header.encode("ascii"))
        out.write(positions.tobytes())
        out.write(face_bytes)
    os.replace(temporary, path)
    return face_count


def waves(rng, count, frequency, amplitude):
    """count random plane waves (direction, frequency, phase, amplitude), falling off as 1/f."""
    result = []
    for k in range(count):
        theta = rng.uniform(0, 2 * math.pi)
        phi = math.acos(rng.uniform(-1, 1))
        f = frequency * (1.7 ** k)
        result.append((math.sin(phi) * math.cos(theta), math.cos(phi), math.sin(phi) * math.sin(theta), f,
                       rng.uniform(0, 2 * math.pi), amplitude / (1.7 ** k)))
    return result


def wave_sum(table, x, y, z):
    return sum(a * math.sin(f * (dx * x + dy * y + dz * z) + p) for dx, dy, dz, f, p, a in table)


def terrain(rng, cells=800):
    table = waves(rng, 9, 4.0, 0.08)
    positions, faces = array("f"), array("i")
    n = cells + 1
    for j in range(n):
        for i in range(n):
            x, z = i / cells - 0.5, j / cells - 0.5
            positions.extend((x, wave_sum(table, x, 0.0, z), z))
    for j in range(cells):
        for i in range(cells):
            a = j * n + i
            faces.extend((a, a + n, a + 1, a + 1, a + n, a + n + 1))
    return positions, faces


# A unit box's 8 corners and 12 outward-wound triangles.
BOX_CORNERS = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
BOX_TRIANGLES = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
                 (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]


def add_box(positions, faces, cx, cz, sx, sy, sz, turn):
    """A box of size sx, sy, sz standing on y = 0 at (cx, cz), turned by `turn` about +y."""
    c, s = math.cos(turn), math.sin(turn)
    base = len(positions) // 3
    for x, y, z in BOX_CORNERS:
        lx, lz = (x - 0.5) * sx, (z - 0.5) * sz
        positions.extend((cx + c * lx - s * lz, y * sy, cz + s * lx + c * lz))
    for t in BOX_TRIANGLES:
        faces.extend((base + t[0], base + t[1], base + t[2]))


def city(rng, lots=316):
    """One box per lot of a lots x lots grid, filling 50-95% of it, a third turned about +y."""
    positions, faces = array("f"), array("i")
    lot = 1.0 / lots
    for j in range(lots):
        for i in range(lots):
            sx, sz = lot * rng.uniform(0.5, 0.95), lot * rng.uniform(0.5, 0.95)
            sy = math.exp(rng.uniform(math.log(0.002), math.log(0.1)))
            cx, cz = (i + 0.5) * lot - 0.5, (j + 0.5) * lot - 0.5
            turn = rng.uniform(0, math.pi / 2) if rng.random() < 1 / 3 else 0.0
            c, s = math.cos(turn), math.sin(turn)
            if turn:  # a turned box fits its lot
                sx, sz = sx / (c + s), sz / (c + s)
            add_box(positions, faces, cx, cz, sx, sy, sz, turn)
    return positions, faces


def sticks(rng, boxes=100000):
    """100,000 thin boxes dropped anywhere on a square, overlapping about ten deep."""
    positions, faces = array("f"), array("i")
    for _ in range(boxes):
        sx = math.exp(rng.uniform(math.log(0.002), math.log(0.03)))
        sz = math.exp(rng.uniform(math.log(0.002), math.log(0.03)))
        sy = math.exp(rng.uniform(math.log(0.002), math.log(0.1)))
        cx, cz = rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)
        turn = rng.uniform(0, math.pi / 2) if rng.random() < 1 / 3 else 0.0
        add_box(positions, faces, cx, cz, sx, sy, sz, turn)
    return positions, faces


def blob(rng, levels=8):
    t = (1 + math.sqrt(5)) / 2
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
                (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    vertices = [tuple(c / math.sqrt(1 + t * t) for c in v) for v in vertices]
    triangles = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
                 (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
                 (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        midpoints = {}

        def middle(a, b):
            key = (a, b) if a < b else (b, a)
            if key not in midpoints:
                m = [(p + q) / 2 for p, q in zip(vertices[a], vertices[b])]
                length = math.sqrt(sum(c * c for c in m))
                vertices.append(tuple(c / length for c in m))
                midpoints[key] = len(vertices) - 1
            return midpoints[key]

        refined = []
        for a, b, c in triangles:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            refined += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        triangles = refined
    table = waves(rng, 7, 3.0, 0.12)
    positions, faces = array("f"), array("i")
    for x, y, z in vertices:
        r = 1.0 + wave_sum(table, x, y, z)
        positions.extend((r * x, r * y, r * z))
    for triangle in triangles:
        faces.extend(triangle)
    return positions, faces


MESHES = {"terrain": terrain, "city": city, "blob": blob, "sticks": sticks}
DEFAULT = ["terrain", "city", "blob"]


def main():
    if len(sys.argv) < 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(sys.argv) >= 2 else 2
    out = sys.argv[1]
    names = sys.argv[2:] or DEFAULT
    unknown = [name for name in names if name not in MESHES]
    if unknown:
        print(f"make_meshes.py: error: unknown mesh {', '.join(unknown)} (known: {', '.join(MESHES)})", file=sys.stderr)
        return 2
    os.makedirs(out, exist_ok=True)
    for name in names:
        positions, faces = MESHES[name](random.Random(f"kdray-{name}"))
        count = write_ply(os.path.join(out, name + ".ply"), positions, faces)
        print(f"{out}/{name}.ply: {count} triangles")
    return 0


if __name__ == "__main__":
    sys.exit(main())
