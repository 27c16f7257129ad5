# A room built in Blender 3.4, exported by Blender's own glTF exporter and rendered by Cycles:
# the yardstick for kdray's rendering of Blender glTF exports (issue 24; bench/gltf_cycles.sh
# drives it and runs kdray on the .glb).
#
# The scene: a floor, a back wall, two side walls and a ceiling with an opening (rough coloured
# Principled BSDFs, roughness 1, metallic 0), a gold sphere (metallic 1, roughness 0.3), a cube
# turned about two axes (roughness 0.5), a cylinder under a turned, non-uniformly scaled empty
# (roughness 1), and either an emissive quad in the ceiling's opening (Principled emission,
# strength 6, facing down) or, with --light point, a 100 W point light (radius 0) in its place.
# The room is open at the front, where the camera stands: 28 mm lens, sensor fit auto, tilted
# down. World black. Everything is made here from nothing (--factory-startup), so the same
# options give the same scene.
#
# --layout-seed 0 is the hand-made layout; any other seed draws the colours, the sizes, the
# places and the turns of the objects, the room's size and the lamp's place from that seed
# (nothing is tuned to one layout). The camera and the image shape are options of their own.
#
# Writes OUT_DIR/NAME.blend and OUT_DIR/NAME.glb (export_format GLB, export_cameras and
# export_lights; every other exporter setting its default), and with --exr renders with
# Cycles on the CPU (settings as ../shared/yardsticks/cycles_render.py: --spp samples, 8
# bounces of every kind, no denoising, 1-pixel box filter, no adaptive sampling, no clamping,
# film not transparent, view transform Standard, float RGB OpenEXR of linear radiance).
#
# usage:
#   blender -b --factory-startup --python bench/gltf_cycles/room.py -- --out-dir D --name room \
#       [--light quad|point] [--layout-seed N] [--width 320 --height 240 --lens 28] \
#       [--cam-pos X,Y,Z --cam-target X,Y,Z] [--exr OUT.exr --spp 1024 --seed 1 --threads 2]
#   e.g. bench/gltf_cycles.sh's third scene, "wide": --layout-seed 7 --width 384 --height 216
#        --lens 24 --cam-pos=-1.2,-2.8,1.5 --cam-target 0.4,0.8,0.9
# Coordinates are Blender's (Z up); the exporter turns them to glTF's Y up.
import argparse
import math
import os
import random
import sys
import time

import bpy
from mathutils import Vector

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
ap = argparse.ArgumentParser(prog="room.py")
ap.add_argument("--out-dir", required=True)
ap.add_argument("--name", default="room")
ap.add_argument("--light", choices=["quad", "point"], default="quad")
ap.add_argument("--layout-seed", type=int, default=0)
ap.add_argument("--width", type=int, default=320)
ap.add_argument("--height", type=int, default=240)
ap.add_argument("--lens", type=float, default=28.0, help="focal length in mm (36 mm sensor, fit auto)")
ap.add_argument("--cam-pos", default="0,-2.6,1.3")
ap.add_argument("--cam-target", default="0,1.5,0.8")
ap.add_argument("--emission-strength", type=float, default=6.0)
ap.add_argument("--point-watts", type=float, default=100.0)
ap.add_argument("--exr", help="render with Cycles to this OpenEXR file")
ap.add_argument("--spp", type=int, default=1024)
ap.add_argument("--seed", type=int, default=1)
ap.add_argument("--max-bounces", type=int, default=8)
ap.add_argument("--threads", type=int, default=2)
args = ap.parse_args(argv)


def vec3(text):
    return Vector([float(t) for t in text.split(",")])


# ------------------------------------------------------------------------------ layout
rng = random.Random(args.layout_seed)
if args.layout_seed == 0:
    L = dict(
        room=(4.0, 4.0, 2.4),  # width (x), depth (y), height (z); x in [-w/2, w/2], y in [-d/2, d/2]
        floor=(0.70, 0.68, 0.62), back=(0.60, 0.62, 0.66), left=(0.65, 0.12, 0.10), right=(0.12, 0.35, 0.60),
        ceiling=(0.75, 0.75, 0.75),
        lamp=(0.0, 1.0, 0.9, 0.7),  # x, y, size x, size y
        gold=(1.0, 0.766, 0.336), sphere=(-0.75, 0.55, 0.5),  # (x, y, radius)
        cube_color=(0.25, 0.55, 0.20), cube=(0.85, 1.1, 0.35, 20.0, 30.0),  # x, y, half size, turn about x, about z (deg)
        cyl_color=(0.80, 0.78, 0.70), cyl=(0.3, 0.0, 0.22, 0.4, 35.0, (1.3, 0.8, 1.1)),  # x, y, radius, half height, turn, scale
    )
else:
    def colour():
        return tuple(round(rng.uniform(0.08, 0.85), 3) for _ in range(3))
    w, d, h = rng.uniform(3.2, 5.0), rng.uniform(3.2, 5.0), rng.uniform(2.3, 3.0)
    L = dict(
        room=(w, d, h), floor=colour(), back=colour(), left=colour(), right=colour(), ceiling=colour(),
        lamp=(rng.uniform(-0.3, 0.3) * w, rng.uniform(-0.2, 0.3) * d, rng.uniform(0.5, 1.2), rng.uniform(0.5, 1.2)),
        gold=(1.0, rng.uniform(0.6, 0.85), rng.uniform(0.25, 0.45)),
        sphere=(rng.uniform(-0.35, -0.1) * w, rng.uniform(0.0, 0.3) * d, rng.uniform(0.3, 0.6)),
        cube_color=colour(),
        cube=(rng.uniform(0.1, 0.35) * w, rng.uniform(0.1, 0.35) * d, rng.uniform(0.25, 0.45),
              rng.uniform(10, 45), rng.uniform(10, 60)),
        cyl_color=colour(),
        cyl=(rng.uniform(-0.15, 0.15) * w, rng.uniform(-0.25, -0.05) * d, rng.uniform(0.15, 0.35),
             rng.uniform(0.3, 0.6), rng.uniform(0, 90),
             (rng.uniform(0.7, 1.4), rng.uniform(0.7, 1.4), rng.uniform(0.8, 1.3))),
    )
print("layout %d: %s" % (args.layout_seed, L))

# ------------------------------------------------------------------------------ clean scene
for ob in list(bpy.data.objects):
    bpy.data.objects.remove(ob, do_unlink=True)
for collection in (bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras):
    for block in list(collection):
        collection.remove(block)
scene = bpy.context.scene


def principled(name, base, roughness=1.0, metallic=0.0, emission=None, strength=1.0):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*base, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Metallic"].default_value = metallic
    if emission is not None:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    mat.cycles.sample_as_light = True  # 3.4: MIS light sampling of emissive meshes (the default)
    return mat


def mesh_object(name, verts, faces, mat, parent=None):
    me = bpy.data.meshes.new(name)
    me.from_pydata([tuple(v) for v in verts], [], faces)
    me.update()
    me.materials.append(mat)
    ob = bpy.data.objects.new(name, me)
    scene.collection.objects.link(ob)
    ob.parent = parent
    return ob


def quad(name, corners, mat):  # corners counter-clockwise seen from the side the normal points to
    return mesh_object(name, corners, [(0, 1, 2, 3)], mat)


w, d, h = L["room"]
x0, x1, y0, y1 = -w / 2, w / 2, -d / 2, d / 2
V = Vector
quad("Floor", [V((x0, y0, 0)), V((x1, y0, 0)), V((x1, y1, 0)), V((x0, y1, 0))], principled("Floor", L["floor"]))
quad("BackWall", [V((x0, y1, 0)), V((x1, y1, 0)), V((x1, y1, h)), V((x0, y1, h))], principled("BackWall", L["back"]))
quad("LeftWall", [V((x0, y0, 0)), V((x0, y1, 0)), V((x0, y1, h)), V((x0, y0, h))], principled("LeftWall", L["left"]))
quad("RightWall", [V((x1, y1, 0)), V((x1, y0, 0)), V((x1, y0, h)), V((x1, y1, h))], principled("RightWall", L["right"]))

# The ceiling: four quads around the lamp's opening, normals down.
lx, ly, sx, sy = L["lamp"]
a0, a1, b0, b1 = lx - sx / 2, lx + sx / 2, ly - sy / 2, ly + sy / 2
ceiling_verts = [V((x, y, h)) for x, y in
                 [(x0, y0), (x1, y0), (x1, y1), (x0, y1), (a0, b0), (a1, b0), (a1, b1), (a0, b1)]]
mesh_object("Ceiling", ceiling_verts, [(0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 4, 0)],
            principled("Ceiling", L["ceiling"]))

if args.light == "quad":
    lamp = principled("Lamp", (0.0, 0.0, 0.0), emission=(1.0, 1.0, 1.0), strength=args.emission_strength)
    quad("Lamp", [V((a0, b0, h)), V((a0, b1, h)), V((a1, b1, h)), V((a1, b0, h))], lamp)  # normal down
else:
    light = bpy.data.lights.new("PointLight", 'POINT')
    light.energy = args.point_watts
    light.color = (1.0, 1.0, 1.0)
    light.shadow_soft_size = 0.0  # a point, as glTF's punctual light is
    light_ob = bpy.data.objects.new("PointLight", light)
    light_ob.location = (lx, ly, h - 0.5)
    scene.collection.objects.link(light_ob)

sxy = L["sphere"]
bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=sxy[2], location=(sxy[0], sxy[1], sxy[2]))
sphere = bpy.context.active_object
sphere.name = "GoldSphere"
bpy.ops.object.shade_smooth()
sphere.data.materials.append(principled("Gold", L["gold"], roughness=0.3, metallic=1.0))

cx, cy, half, turn_x, turn_z = L["cube"]
bpy.ops.mesh.primitive_cube_add(size=2 * half)
cube = bpy.context.active_object
cube.name = "TurnedCube"
cube.rotation_euler = (math.radians(turn_x), 0.0, math.radians(turn_z))
# Resting on the floor: the lowest corner at z = 0 after the turn.
bpy.context.view_layer.update()
lowest = min((cube.matrix_world @ v.co).z for v in cube.data.vertices)
cube.location = (cx, cy, -lowest)
cube.data.materials.append(principled("Cube", L["cube_color"], roughness=0.5))

px, py, radius, half_h, turn, scale = L["cyl"]
parent = bpy.data.objects.new("CylinderParent", None)
scene.collection.objects.link(parent)
parent.location = (px, py, 0.0)
parent.rotation_euler = (0.0, 0.0, math.radians(turn))
parent.scale = scale
bpy.ops.mesh.primitive_cylinder_add(vertices=32, radius=radius, depth=2 * half_h, location=(0, 0, half_h))
cylinder = bpy.context.active_object
cylinder.name = "Cylinder"
cylinder.parent = parent  # its location is now in the parent's frame: stands on the floor
cylinder.data.materials.append(principled("Cylinder", L["cyl_color"]))

# ------------------------------------------------------------------------------ camera, world
cam_data = bpy.data.cameras.new("Camera")
cam_data.lens = args.lens
cam_data.sensor_width = 36.0
cam_data.sensor_fit = 'AUTO'
cam_data.dof.use_dof = False
cam = bpy.data.objects.new("Camera", cam_data)
scene.collection.objects.link(cam)
cam.location = vec3(args.cam_pos)
cam.rotation_euler = (vec3(args.cam_target) - vec3(args.cam_pos)).to_track_quat('-Z', 'Y').to_euler()
scene.camera = cam

world = scene.world or bpy.data.worlds.new("World")
world.use_nodes = True
background = world.node_tree.nodes["Background"]
background.inputs["Color"].default_value = (0, 0, 0, 1)
background.inputs["Strength"].default_value = 0.0
scene.world = world

# ------------------------------------------------------------------------------ Cycles settings
r = scene.render
r.engine = 'CYCLES'
r.resolution_x, r.resolution_y, r.resolution_percentage = args.width, args.height, 100
r.pixel_aspect_x = r.pixel_aspect_y = 1.0
r.threads_mode = 'FIXED'
r.threads = args.threads
r.use_motion_blur = False
r.film_transparent = False
r.use_compositing = False
r.use_sequencer = False
r.dither_intensity = 0.0
r.use_persistent_data = False

c = scene.cycles
c.device = 'CPU'
c.feature_set = 'SUPPORTED'
c.samples = args.spp
c.use_adaptive_sampling = False
c.time_limit = 0
c.use_denoising = False
c.use_preview_denoising = False
c.seed = args.seed
c.use_animated_seed = False
c.max_bounces = args.max_bounces
c.diffuse_bounces = args.max_bounces
c.glossy_bounces = args.max_bounces
c.transmission_bounces = args.max_bounces
c.volume_bounces = args.max_bounces
c.transparent_max_bounces = args.max_bounces
c.min_light_bounces = 0
c.min_transparent_bounces = 0
c.sample_clamp_direct = 0.0
c.sample_clamp_indirect = 0.0
c.blur_glossy = 0.0
c.caustics_reflective = True
c.caustics_refractive = True
c.light_sampling_threshold = 0.0
c.use_fast_gi = False
if hasattr(c, "use_light_tree"):  # 3.5 and later
    c.use_light_tree = False
c.pixel_filter_type = 'BOX'
c.filter_width = 1.0
c.film_exposure = 1.0
if hasattr(c, "use_auto_tile"):
    c.use_auto_tile = False
scene.view_layers[0].cycles.use_denoising = False
c.use_guiding = False
c.sampling_pattern = 'PROGRESSIVE_MULTI_JITTER'
c.scrambling_distance = 1.0
c.auto_scrambling_distance = False

vs = scene.view_settings
scene.display_settings.display_device = 'sRGB'
vs.view_transform = 'Standard'
vs.look = 'None'
vs.exposure = 0.0
vs.gamma = 1.0
vs.use_curve_mapping = False

im = r.image_settings
im.file_format = 'OPEN_EXR'
im.color_mode = 'RGB'
im.color_depth = '32'
im.exr_codec = 'ZIP'
r.use_file_extension = False

# ------------------------------------------------------------------------------ save, export
out_dir = os.path.abspath(args.out_dir)
os.makedirs(out_dir, exist_ok=True)
stem = os.path.join(out_dir, args.name)
bpy.context.preferences.filepaths.save_version = 0  # no NAME.blend1 backups of an earlier run
bpy.ops.wm.save_as_mainfile(filepath=stem + ".blend")
bpy.ops.export_scene.gltf(filepath=stem + ".glb", export_format='GLB', export_cameras=True, export_lights=True)
print("wrote %s.blend and %s.glb" % (stem, stem))

# ------------------------------------------------------------------------------ render
if args.exr:
    exr = os.path.abspath(args.exr)
    r.filepath = exr
    t0 = time.time()
    bpy.ops.render.render(write_still=False)
    seconds = time.time() - t0
    bpy.data.images["Render Result"].save_render(exr, scene=scene)
    print("CYCLES_RENDER_TIME_S %.1f  (%s: spp=%d seed=%d %dx%d bounces=%d threads=%d)" % (
        seconds, exr, args.spp, args.seed, args.width, args.height, args.max_bounces, args.threads))
