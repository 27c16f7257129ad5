# A diagnostic for bench/gltf_cycles.sh: the same room rendered by Cycles with its rough plastics
# as Lambertian surfaces. Opens a .blend that room.py saved (its Cycles settings included),
# replaces every Principled BSDF with roughness 1 and metallic 0 by a Diffuse BSDF of its base
# colour (roughness 0: Lambert), and renders. By the glTF specification such a plastic reflects
# within 1% of a Lambertian surface of its colour (white furnace, tests/render/
# gltf_brdf_reference.py), while Blender's Principled BSDF reflects up to about 7% more (its
# Disney diffuse, brighter towards grazing angles, is not weighted by 1 - Fresnel): kdray's
# render of the export should match this render more closely than the Principled one.
#
# usage: blender -b --factory-startup ROOM.blend --python bench/gltf_cycles/lambert.py -- OUT.exr SPP
import sys

import bpy

out, spp = sys.argv[sys.argv.index("--") + 1:][:2]
replaced = 0
for material in bpy.data.materials:
    if not material.use_nodes:
        continue
    nodes, links = material.node_tree.nodes, material.node_tree.links
    for node in list(nodes):
        if node.type != 'BSDF_PRINCIPLED':
            continue
        if node.inputs["Roughness"].default_value < 1.0 or node.inputs["Metallic"].default_value > 0.0:
            continue
        if node.inputs["Emission Strength"].default_value > 0.0 and any(node.inputs["Emission"].default_value[:3]):
            continue
        diffuse = nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = node.inputs["Base Color"].default_value
        diffuse.inputs["Roughness"].default_value = 0.0
        for link in list(node.outputs["BSDF"].links):
            links.new(diffuse.outputs["BSDF"], link.to_socket)
        replaced += 1
print(f"lambert.py: {replaced} rough plastic(s) rendered as Lambertian")
bpy.context.scene.cycles.samples = int(spp)
bpy.context.scene.render.filepath = out
bpy.ops.render.render(write_still=True)
