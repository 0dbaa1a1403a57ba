"""Blender side of tools/compare_cycles.sh: imports a glTF file and renders it with Cycles, set up to match
RTDR's estimator as far as Cycles allows. Run by the script as

    blender -b (factory startup) -P tools/compare_cycles_blender.py -- SCENE.gltf OUT.exr WIDTH HEIGHT SPP BOUNCES [MATERIAL]

MATERIAL `principled` (the default) keeps the importer's Principled BSDF (v1 in Blender 3.4): what a Blender user
sees. MATERIAL `lambert` replaces every Principled BSDF by a Diffuse BSDF of roughness 0 (Lambert, glTF's diffuse
lobe) plus its emission: glTF's BRDF without its specular lobe. trace/README.md, "Differences from Cycles", has
both measured, and why they differ (tools/principled_v1_albedo.py, tools/cycles_furnace_blender.py).

Settings, and why each matches RTDR (trace/README.md, "Differences from Cycles", lists what does not):
- an empty factory scene (no default cube, lamp or grey world) and a black world: RTDR has no environment light;
- the glTF camera's vertical field of view (sensor fit VERTICAL), no shift, the requested resolution;
- CPU, a fixed seed, SPP samples, no adaptive sampling, no denoising;
- bounces: Cycles' max_bounces counts the bounces after the first hit, as RTDR's bounce count does (0 is
  direct light only); diffuse and glossy alike, no transparency or volumes in our scenes;
- no clamping (sample_clamp_direct/indirect 0), no glossy filter (blur_glossy 0), caustics on, light
  threshold 0, no light tree where the Blender version has one: each would bias the estimate;
- the pixel filter a box of width 1 px (RTDR samples the pixel centre only: see trace/README.md);
- the "Standard" view transform, no look, exposure 0, gamma 1 (not Filmic), written as a 32-bit linear EXR.
"""
import json
import sys

import bpy
import numpy

# Blender 3.4's glTF importer uses numpy.bool, which numpy 1.24 (Debian 12's) removed; it meant the builtin.
if "bool" not in numpy.__dict__:
    numpy.bool = bool

args = sys.argv[sys.argv.index("--") + 1:]
scene_path, out_path, width, height, spp, bounces = args[:6]
cycles_material = args[6] if len(args) > 6 else "principled"
if cycles_material not in ("principled", "lambert"):
    sys.exit("compare_cycles: MATERIAL is principled or lambert, not " + cycles_material)
lambert = cycles_material == "lambert"
width, height, spp, bounces = int(width), int(height), int(spp), int(bounces)

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=scene_path)
scene = bpy.context.scene

# The camera: the file's first camera, with its vertical field of view (glTF yfov, spec Sec. 3.10.3).
with open(scene_path, encoding="utf-8") as f:
    yfov = json.load(f)["cameras"][0]["perspective"]["yfov"]
cameras = [o for o in scene.objects if o.type == "CAMERA"]
if not cameras:
    sys.exit("compare_cycles: the glTF file has no camera")
scene.camera = cameras[0]
scene.camera.data.sensor_fit = "VERTICAL"
scene.camera.data.angle_y = yfov
scene.camera.data.shift_x = scene.camera.data.shift_y = 0.0
scene.render.resolution_x, scene.render.resolution_y = width, height
scene.render.resolution_percentage = 100
scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0

# No environment light.
world = bpy.data.worlds.new("black")
world.use_nodes = False
world.color = (0.0, 0.0, 0.0)
scene.world = world

cycles = scene.cycles
scene.render.engine = "CYCLES"
cycles.device = "CPU"
cycles.seed = 1
cycles.samples = spp
cycles.use_adaptive_sampling = False
cycles.use_denoising = False
cycles.max_bounces = cycles.diffuse_bounces = cycles.glossy_bounces = bounces
cycles.transmission_bounces = bounces
cycles.volume_bounces = 0
cycles.transparent_max_bounces = 8
cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0.0
cycles.blur_glossy = 0.0
cycles.caustics_reflective = cycles.caustics_refractive = True
cycles.light_sampling_threshold = 0.0
if hasattr(cycles, "use_light_tree"):  # Blender 3.5 and later
    cycles.use_light_tree = False
cycles.pixel_filter_type = "BOX"
cycles.filter_width = 1.0

scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.view_settings.exposure = 0.0
scene.view_settings.gamma = 1.0
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.image_settings.exr_codec = "ZIP"
scene.render.filepath = out_path

# What the importer made of the materials, for the record.
for material in bpy.data.materials:
    if not material.use_nodes:
        continue
    for node in material.node_tree.nodes:
        if node.type == "BSDF_PRINCIPLED":
            i = node.inputs
            print("compare_cycles: material %-12s principled %s, base %s, metallic %.3g, roughness %.3g, specular %.3g,"
                  " emission %s x %.4g" % (material.name, node.distribution, tuple(round(c, 4) for c in i["Base Color"].default_value[:3]),
                                           i["Metallic"].default_value, i["Roughness"].default_value,
                                           i["Specular"].default_value,
                                           tuple(round(c, 4) for c in i["Emission"].default_value[:3]),
                                           i["Emission Strength"].default_value))
            if lambert:
                # Lambert (Diffuse BSDF, roughness 0, is Cycles' Lambertian) + emission, in place of the Principled.
                tree = material.node_tree
                diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
                diffuse.inputs["Color"].default_value = i["Base Color"].default_value
                diffuse.inputs["Roughness"].default_value = 0.0
                emission = tree.nodes.new("ShaderNodeEmission")
                emission.inputs["Color"].default_value = i["Emission"].default_value
                emission.inputs["Strength"].default_value = i["Emission Strength"].default_value
                add = tree.nodes.new("ShaderNodeAddShader")
                tree.links.new(diffuse.outputs[0], add.inputs[0])
                tree.links.new(emission.outputs[0], add.inputs[1])
                output = next(n for n in tree.nodes if n.type == "OUTPUT_MATERIAL")
                tree.links.new(add.outputs[0], output.inputs["Surface"])
                print("compare_cycles: material %s rendered as Lambert + emission" % material.name)
bpy.ops.render.render(write_still=True)
