#!/usr/bin/env python3
"""Renders samples/gltf_scene.py's glTF scene with Mitsuba 3 (a yardstick, not a dependency):
the same meshes, camera, point light (a Mitsuba `point` emitter of the same intensity in W/sr)
and materials as kdray reads them, as near as Mitsuba has them: glTF non-metals as `roughplastic`
(GGX, alpha = roughness^2, int_ior 1.5, linear mode; a coated diffuse, darker when rough than the
glTF specification's BRDF that kdray renders, so the plastics differ by design) with the base
colour (the floor's checker as a bilinear `bitmap`), the
normal-mapped box through `normalmap`, the metal as `principled` with metallic 1 (Schlick's
Fresnel of the base colour, as glTF and kdray).

  VENV/bin/python bench/gltf_mitsuba.py TEXTURE_DIR OUT.exr --spp N --width W --height H \
      --max-bounces B [--threads 2] [--metal]

TEXTURE_DIR holds checker.png and ridges.png (written by gltf_scene.py). --max-bounces counts
as Cycles and kdray do: Mitsuba's max_depth is B + 2."""

import argparse
import math
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "samples"))
import gltf_scene  # noqa: E402


def newest_llvm():
    """Dr.Jit 1.5 needs libLLVM >= 17 (see ../shared/yardsticks/mitsuba_render.py)."""
    if os.environ.get("DRJIT_LIBLLVM_PATH"):
        return
    for version in range(25, 16, -1):
        candidate = f"/usr/lib/x86_64-linux-gnu/libLLVM-{version}.so"
        if os.path.exists(candidate):
            os.environ["DRJIT_LIBLLVM_PATH"] = candidate
            return


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("textures")
    parser.add_argument("out")
    parser.add_argument("--spp", type=int, default=64)
    parser.add_argument("--width", type=int, default=256)
    parser.add_argument("--height", type=int, default=256)
    parser.add_argument("--max-bounces", type=int, default=8)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--metal", action="store_true", help="gltf_scene.py's all-metal variant")
    args = parser.parse_args()

    newest_llvm()
    import drjit as dr
    import mitsuba as mi
    import numpy as np

    mi.set_variant("llvm_ad_rgb")
    dr.set_thread_count(args.threads)

    def texture(name, raw):
        return {"type": "bitmap", "filename": os.path.join(args.textures, name), "filter_type": "bilinear",
                "wrap_mode": "repeat", "raw": raw}

    def bsdf(name):
        m = gltf_scene.materials(args.metal)[name]
        alpha = m["roughness"] ** 2
        base = texture(m["texture"], False) if "texture" in m else {"type": "rgb", "value": list(m["base"])}
        if m["metallic"] >= 1:
            surface = {"type": "principled", "base_color": base, "metallic": 1.0, "roughness": m["roughness"]}
        else:
            surface = {"type": "roughplastic", "distribution": "ggx", "alpha": alpha, "int_ior": 1.5, "ext_ior": 1.0,
                       "nonlinear": False, "diffuse_reflectance": base}
        if "normal_texture" in m:
            # kdray bends the shading normal only (no Mitsuba heuristics): Mitsuba's defaults flip a
            # mapped normal that faces away from the viewer and multiply by a shadow-terminator
            # term, which moved the normal-mapped box's mean by up to 4% (bench/LOG.md,
            # "The glTF plastic as Mitsuba 3's roughplastic").
            return {"type": "normalmap", "normalmap": texture(m["normal_texture"], True), "bsdf": surface,
                    "flip_invalid_normals": False, "use_shadowing_function": False}
        return surface

    scene = {"type": "scene"}
    for index, (name, positions, normals, uvs, indices) in enumerate(gltf_scene.scene()):
        mesh = mi.Mesh(name, len(positions), len(indices) // 3, has_vertex_normals=True, has_vertex_texcoords=True)
        params = mi.traverse(mesh)
        params["vertex_positions"] = np.ravel(np.array(positions, dtype=np.float32))
        params["vertex_normals"] = np.ravel(np.array(normals, dtype=np.float32))
        params["vertex_texcoords"] = np.ravel(np.array(uvs, dtype=np.float32))
        params["faces"] = np.ravel(np.array(indices, dtype=np.uint32))
        params.update()
        mesh.set_bsdf(mi.load_dict(bsdf(name)))
        scene[f"mesh{index}"] = mesh
    light = gltf_scene.POINT_LIGHT
    scene["lamp"] = {"type": "point", "position": list(light["position"]),
                     "intensity": {"type": "rgb", "value": [c * light["watts_per_sr"] for c in light["color"]]}}
    camera = gltf_scene.CAMERA
    scene["sensor"] = {
        "type": "perspective", "fov_axis": "y", "fov": camera["yfov_degrees"], "near_clip": 1e-3, "far_clip": 1e7,
        "to_world": mi.ScalarTransform4f().look_at(origin=camera["position"], target=camera["target"], up=[0, 1, 0]),
        "film": {"type": "hdrfilm", "width": args.width, "height": args.height, "rfilter": {"type": "box"},
                 "pixel_format": "rgb", "component_format": "float32"},
        "sampler": {"type": "multijitter", "sample_count": args.spp},
    }
    scene["integrator"] = {"type": "path", "max_depth": args.max_bounces + 2}
    loaded = mi.load_dict(scene)
    start = time.perf_counter()
    image = mi.render(loaded, spp=args.spp, seed=args.seed)
    dr.eval(image)
    seconds = time.perf_counter() - start
    mi.Bitmap(image).write(args.out)
    print(f"render {seconds:.3f} s")


if __name__ == "__main__":
    main()
