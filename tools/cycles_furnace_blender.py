"""A closed furnace in Blender's Cycles: checks, inside Cycles itself, the Principled v1 model of
tools/principled_v1_albedo.py, which predicts what the camera sees. Run as

    blender -b (factory startup) -P tools/cycles_furnace_blender.py -- MATERIAL [OUT.exr] [SIZE] [SPP] [BOUNCES]

MATERIAL is `principled` (Principled BSDF: base 0.5, roughness 1, metallic 0, specular 0.5, distribution GGX as
the glTF importer sets it) or `lambert` (Diffuse BSDF of roughness 0, colour 0.5); both with emission 0.5 at
strength 1 added. Defaults: out/cycles_furnace_MATERIAL.exr, 64 x 64, 1024 spp, 64 bounces.

The scene: a UV sphere of radius 1 (256 segments, 128 rings, smooth shaded), the camera at its centre, a black
world; Cycles on the CPU with the unbiased settings of tools/compare_cycles_blender.py (no clamping, no glossy
filter, caustics on, no denoising, box filter, Standard view transform, 32-bit linear EXR). The wall emits 0.5
and reflects; with Lambert at base 0.5 the radiance is 0.5 / (1 - 0.5) = 1 everywhere. Prints the image's
mean and its standard error over pixels.
"""
import os
import sys

import bpy
import numpy

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
material_name = args[0] if args else "principled"
if material_name not in ("principled", "lambert"):
    sys.exit("cycles_furnace: MATERIAL is principled or lambert")
out_path = os.path.abspath(args[1] if len(args) > 1 else "out/cycles_furnace_%s.exr" % material_name)
size = int(args[2]) if len(args) > 2 else 64
spp = int(args[3]) if len(args) > 3 else 1024
bounces = int(args[4]) if len(args) > 4 else 64
BASE, EMISSION = 0.5, 0.5

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene

# The sphere, and the camera at its centre (any direction: every ray meets the wall head-on).
bpy.ops.mesh.primitive_uv_sphere_add(segments=256, ring_count=128, radius=1.0, location=(0, 0, 0))
sphere = bpy.context.active_object
bpy.ops.object.shade_smooth()
camera_data = bpy.data.cameras.new("camera")
camera = bpy.data.objects.new("camera", camera_data)
scene.collection.objects.link(camera)
camera.location = (0.0, 0.0, 0.0)
camera.rotation_euler = (1.2, 0.0, 0.4)
scene.camera = camera

# The material: the BSDF plus emission 0.5.
material = bpy.data.materials.new("furnace")
material.use_nodes = True
tree = material.node_tree
tree.nodes.clear()
output = tree.nodes.new("ShaderNodeOutputMaterial")
if material_name == "principled":
    bsdf = tree.nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.distribution = "GGX"
    i = bsdf.inputs
    i["Base Color"].default_value = (BASE, BASE, BASE, 1.0)
    i["Metallic"].default_value = 0.0
    i["Roughness"].default_value = 1.0
    i["Specular"].default_value = 0.5
    i["Emission"].default_value = (EMISSION, EMISSION, EMISSION, 1.0)
    i["Emission Strength"].default_value = 1.0
    tree.links.new(bsdf.outputs[0], output.inputs["Surface"])
else:
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (BASE, BASE, BASE, 1.0)
    diffuse.inputs["Roughness"].default_value = 0.0
    emission = tree.nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (EMISSION, EMISSION, EMISSION, 1.0)
    emission.inputs["Strength"].default_value = 1.0
    add = tree.nodes.new("ShaderNodeAddShader")
    tree.links.new(diffuse.outputs[0], add.inputs[0])
    tree.links.new(emission.outputs[0], add.inputs[1])
    tree.links.new(add.outputs[0], output.inputs["Surface"])
sphere.data.materials.append(material)

world = bpy.data.worlds.new("black")
world.use_nodes = False
world.color = (0.0, 0.0, 0.0)
scene.world = world

scene.render.engine = "CYCLES"
cycles = scene.cycles
cycles.device = "CPU"
cycles.seed = 1
cycles.samples = spp
cycles.use_adaptive_sampling = False
cycles.use_denoising = False
cycles.max_bounces = cycles.diffuse_bounces = cycles.glossy_bounces = bounces
cycles.transmission_bounces = bounces
cycles.volume_bounces = 0
cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0.0
cycles.blur_glossy = 0.0
cycles.caustics_reflective = cycles.caustics_refractive = True
cycles.light_sampling_threshold = 0.0
cycles.pixel_filter_type = "BOX"
cycles.filter_width = 1.0
scene.render.resolution_x = scene.render.resolution_y = size
scene.render.resolution_percentage = 100
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.view_settings.exposure = 0.0
scene.view_settings.gamma = 1.0
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.filepath = out_path
os.makedirs(os.path.dirname(out_path), exist_ok=True)
bpy.ops.render.render(write_still=True)

image = bpy.data.images.load(out_path)
pixels = numpy.array(image.pixels[:], dtype=numpy.float64).reshape(-1, 4)[:, :3]
value = pixels.mean(axis=1)
print("cycles_furnace: %s, %d x %d, %d spp, %d bounces: mean %.4f, standard error %.4f (RGB %.4f %.4f %.4f)" % (
    material_name, size, size, spp, bounces, value.mean(), value.std() / numpy.sqrt(value.size),
    *pixels.mean(axis=0)))
