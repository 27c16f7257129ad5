#!/usr/bin/env python3
"""A small glTF 2.0 scene for the gallery and the Mitsuba comparison, written from code so that
the repository holds no binary assets: a checker-textured floor, a red plastic sphere, a gold
metal sphere, a box whose faces carry a normal map of ridges, a point light
(KHR_lights_punctual) and a camera.

  gltf_scene.py OUT_DIR [--metal]   writes OUT_DIR/textured-scene.gltf, checker.png and ridges.png

--metal makes every material a metal (metallic 1): the variant whose materials kdray and Mitsuba 3
model alike (Schlick's Fresnel of the base colour over GGX), for comparing the lights and textures
apart from the plastics (kdray's are the glTF specification's BRDF, which Mitsuba does not have).

bench/gltf_mitsuba.py imports scene() to give Mitsuba 3 the same meshes, materials, light and
camera. Textures: the checker has an odd number of cells per side, so it reads the same whichever
way a renderer orients v."""

import base64
import json
import math
import os
import struct
import sys
import zlib

CHECKER_CELLS, CHECKER_CELL_PIXELS = 9, 8
RIDGES_SIZE, RIDGES_PERIOD = 64, 16

CAMERA = {"position": (0.0, 1.6, 4.2), "target": (0.0, 0.45, 0.0), "yfov_degrees": 40.0}
# Radiant intensity in W/sr; KHR_lights_punctual writes it in candela, 683 lm/W.
POINT_LIGHT = {"position": (1.5, 3.0, 2.0), "watts_per_sr": 12.0, "color": (1.0, 0.95, 0.85)}
LUMENS_PER_WATT = 683.0

# glTF material parameters (perceptual roughness; the renderers square it).
MATERIALS = {
    "floor": {"base": (1, 1, 1), "metallic": 0.0, "roughness": 0.7, "texture": "checker.png"},
    "plastic": {"base": (0.8, 0.1, 0.08), "metallic": 0.0, "roughness": 0.3},
    "gold": {"base": (1.0, 0.76, 0.33), "metallic": 1.0, "roughness": 0.35},
    "ridged": {"base": (0.2, 0.35, 0.8), "metallic": 0.0, "roughness": 0.4, "normal_texture": "ridges.png"},
}


def png_bytes(width, height, rgb_rows):
    """An 8-bit RGB PNG from rows of (r, g, b) tuples."""
    raw = b"".join(b"\x00" + bytes(c for pixel in row for c in pixel) for row in rgb_rows)
    chunk = lambda kind, data: (struct.pack(">I", len(data)) + kind + data +
                                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def checker_png():
    size = CHECKER_CELLS * CHECKER_CELL_PIXELS
    light, dark = (230, 230, 225), (40, 60, 90)
    rows = [[light if (x // CHECKER_CELL_PIXELS + y // CHECKER_CELL_PIXELS) % 2 == 0 else dark for x in range(size)]
            for y in range(size)]
    return png_bytes(size, size, rows)


def ridges_png():
    """Ridges along v: the normal tilts along +-u as sin(2 pi u / period)."""
    rows = []
    for y in range(RIDGES_SIZE):
        row = []
        for x in range(RIDGES_SIZE):
            slope = 0.8 * math.sin(2 * math.pi * (x + 0.5) / RIDGES_PERIOD)
            n = (-slope, 0.0, 1.0)
            length = math.sqrt(sum(c * c for c in n))
            row.append(tuple(int(round((c / length * 0.5 + 0.5) * 255)) for c in n))
        rows.append(row)
    return png_bytes(RIDGES_SIZE, RIDGES_SIZE, rows)


def quad(corners, normal, uv_scale=1.0):
    positions = list(corners)
    uvs = [(0, 0), (uv_scale, 0), (uv_scale, uv_scale), (0, uv_scale)]
    return positions, [normal] * 4, uvs, [0, 1, 2, 0, 2, 3]


def uv_sphere(centre, radius, stacks=32, slices=64):
    positions, normals, uvs, indices = [], [], [], []
    for i in range(stacks + 1):
        theta = math.pi * i / stacks
        for j in range(slices + 1):
            phi = 2 * math.pi * j / slices
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            positions.append(tuple(c + radius * d for c, d in zip(centre, n)))
            normals.append(n)
            uvs.append((j / slices, 1 - i / stacks))
    for i in range(stacks):
        for j in range(slices):
            a, b = i * (slices + 1) + j, (i + 1) * (slices + 1) + j
            indices += [a, b, a + 1, a + 1, b, b + 1]
    return positions, normals, uvs, indices


def box(centre, half):
    cx, cy, cz = centre
    h = half
    faces = []
    for axis in range(3):
        for sign in (-1, 1):
            n = [0.0, 0.0, 0.0]
            n[axis] = float(sign)
            u_axis, v_axis = [(1, 2), (2, 0), (0, 1)][axis]
            if sign < 0:
                u_axis, v_axis = v_axis, u_axis
            corners = []
            for du, dv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = sign * h
                p[u_axis] = du * h
                p[v_axis] = dv * h
                corners.append((cx + p[0], cy + p[1], cz + p[2]))
            faces.append(quad(corners, tuple(n)))
    positions, normals, uvs, indices = [], [], [], []
    for p, n, t, idx in faces:
        base = len(positions)
        positions += p
        normals += n
        uvs += t
        indices += [base + i for i in idx]
    return positions, normals, uvs, indices


def scene():
    """Meshes as (material name, positions, normals, uvs in glTF's convention (v down), indices)."""
    s = 3.0
    floor = quad([(-s, 0, s), (s, 0, s), (s, 0, -s), (-s, 0, -s)], (0, 1, 0), uv_scale=3.0)
    return [
        ("floor",) + floor,
        ("plastic",) + uv_sphere((-0.9, 0.5, 0.2), 0.5),
        ("gold",) + uv_sphere((0.75, 0.45, -0.3), 0.45),
        ("ridged",) + box((0.1, 0.35, 1.1), 0.35),
    ]


def materials(metal=False):
    return {name: dict(m, metallic=1.0) if metal else m for name, m in MATERIALS.items()}


def write_gltf(out_dir, metal=False):
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "checker.png"), "wb") as f:
        f.write(checker_png())
    with open(os.path.join(out_dir, "ridges.png"), "wb") as f:
        f.write(ridges_png())

    buffer, views, accessors, meshes, nodes = bytearray(), [], [], [], []

    def add_accessor(values, kind, component_type, pack):
        offset = len(buffer)
        for v in values:
            buffer.extend(struct.pack(pack, *(v if isinstance(v, tuple) else (v,))))
        while len(buffer) % 4:
            buffer.append(0)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(buffer) - offset})
        accessor = {"bufferView": len(views) - 1, "componentType": component_type, "count": len(values), "type": kind}
        if kind == "VEC3" and component_type == 5126:
            accessor["min"] = [min(v[i] for v in values) for i in range(3)]
            accessor["max"] = [max(v[i] for v in values) for i in range(3)]
        accessors.append(accessor)
        return len(accessors) - 1

    names = list(materials(metal))
    for name, positions, normals, uvs, indices in scene():
        primitive = {
            "attributes": {
                "POSITION": add_accessor([tuple(map(float, p)) for p in positions], "VEC3", 5126, "<3f"),
                "NORMAL": add_accessor([tuple(map(float, n)) for n in normals], "VEC3", 5126, "<3f"),
                "TEXCOORD_0": add_accessor([(float(u), float(v)) for u, v in uvs], "VEC2", 5126, "<2f"),
            },
            "indices": add_accessor(indices, "SCALAR", 5125, "<I"),
            "material": names.index(name),
        }
        meshes.append({"name": name, "primitives": [primitive]})
        nodes.append({"name": name, "mesh": len(meshes) - 1})

    images = ["checker.png", "ridges.png"]
    gltf_materials = []
    for name, m in materials(metal).items():
        pbr = {"baseColorFactor": list(m["base"]) + [1.0], "metallicFactor": m["metallic"], "roughnessFactor": m["roughness"]}
        material = {"name": name, "pbrMetallicRoughness": pbr}
        if "texture" in m:
            pbr["baseColorTexture"] = {"index": images.index(m["texture"])}
        if "normal_texture" in m:
            material["normalTexture"] = {"index": images.index(m["normal_texture"])}
        gltf_materials.append(material)

    # The camera node looks down its -Z: a rotation from (0, 0, -1) to the view direction.
    px, py, pz = CAMERA["position"]
    tx, ty, tz = CAMERA["target"]
    d = (tx - px, ty - py, tz - pz)
    length = math.sqrt(sum(c * c for c in d))
    pitch = math.asin(d[1] / length)  # about +X, the view has no yaw
    camera_rotation = [math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2)]
    nodes.append({"name": "camera", "camera": 0, "translation": list(CAMERA["position"]), "rotation": camera_rotation})
    nodes.append({"name": "lamp", "translation": list(POINT_LIGHT["position"]),
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})

    document = {
        "asset": {"version": "2.0", "generator": "kdray samples/gltf_scene.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "lamp", "type": "point", "color": list(POINT_LIGHT["color"]),
             "intensity": POINT_LIGHT["watts_per_sr"] * LUMENS_PER_WATT}]}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [{"type": "perspective", "perspective": {
            "yfov": math.radians(CAMERA["yfov_degrees"]), "aspectRatio": 1.0, "znear": 0.01}}],
        "meshes": meshes,
        "materials": gltf_materials,
        "textures": [{"source": i, "sampler": 0} for i in range(len(images))],
        "samplers": [{"magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497}],
        "images": [{"uri": image} for image in images],
        "buffers": [{"byteLength": len(buffer),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buffer)).decode()}],
        "bufferViews": views,
        "accessors": accessors,
    }
    path = os.path.join(out_dir, "textured-scene.gltf")
    with open(path + ".tmp", "w") as f:
        json.dump(document, f, indent=1)
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3) or (len(sys.argv) == 3 and sys.argv[2] != "--metal"):
        sys.exit("usage: gltf_scene.py OUT_DIR [--metal]")
    write_gltf(sys.argv[1], metal=len(sys.argv) == 3)
