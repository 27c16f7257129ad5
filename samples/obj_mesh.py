"""The little OBJ handling the sample scripts share (samples/bunny_pair.py, bench/cornell_bunny.py)."""

import os


def read_obj(path):
    """The vertices ([x, y, z] floats) and faces (lists of the vertices' OBJ indices) of an OBJ file;
    texture and normal indices, and every other record, are left out."""
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "v":
                vertices.append([float(c) for c in fields[1:4]])
            elif fields[0] == "f":
                faces.append([int(c.split("/")[0]) for c in fields[1:]])
    return vertices, faces


def write_atomically(path, text):
    """Writes text to path through a temporary file, so that no reader sees half a file."""
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)
