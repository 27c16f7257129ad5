# The gallery of real-asset materials and lights (included by the Makefile; part of `demo`):
#   textured-scene      a glTF written by gltf_scene.py: a base-colour texture, a normal map,
#                       plastic and metal, lit by its KHR_lights_punctual point light, seen by its camera
#   bunnies-studio      the corpus bunny twice, glass and copper (bunny_pair.py), under the studio map
#   clearcoat-interior  Assimp's ClearCoatTest.gltf (Debian's assimp-testmodels: base-colour,
#                       metallic-roughness and normal textures) under the interior map
# Their speed-vs-error reports: make -C samples report (report.mk, REPORT_SCENES).
ASSIMP_MODELS ?= /usr/share/assimp/models/glTF2
GALLERY_SETTINGS = --width 384 --height 384 --spp 128 --max-bounces 8
GALLERY_IMAGES = textured-scene bunnies-studio clearcoat-interior
DEMO_IMAGES += $(GALLERY_IMAGES)
IMAGES += $(GALLERY_IMAGES)

ASSET_textured-scene = $(OUT)/textured-scene/textured-scene.gltf
RENDER_textured-scene = $(GALLERY_SETTINGS)
$(OUT)/textured-scene/textured-scene.gltf: gltf_scene.py
	/usr/bin/python3 gltf_scene.py $(@D)

ASSET_bunnies = $(OUT)/bunny-pair/bunny-pair.obj
SCENE_bunnies-studio = bunnies
BUNNIES_VIEW = --cam-pos 0,1.1,3.6 --cam-target 0,0.45,0 --fov 35 --env $(CORPUS)/hdri/studio.exr
INPUTS_bunnies-studio = $(CORPUS)/hdri/studio.exr
RENDER_bunnies-studio = $(BUNNIES_VIEW) $(GALLERY_SETTINGS)
$(OUT)/bunny-pair/bunny-pair.obj: bunny_pair.py obj_mesh.py $(CORPUS)/bunny/stanford-bunny.obj
	mkdir -p $(@D)
	/usr/bin/python3 bunny_pair.py $(CORPUS)/bunny/stanford-bunny.obj $@

ASSET_clearcoat = $(ASSIMP_MODELS)/ClearCoat-glTF/ClearCoatTest.gltf
SCENE_clearcoat-interior = clearcoat
CLEARCOAT_VIEW = --env $(CORPUS)/hdri/interior.exr
INPUTS_clearcoat-interior = $(CORPUS)/hdri/interior.exr
RENDER_clearcoat-interior = $(CLEARCOAT_VIEW) $(GALLERY_SETTINGS)
