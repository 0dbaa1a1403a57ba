#!/usr/bin/python3
"""Writes the shipped glTF scenes and the loader's test fixtures. Run from anywhere:

    /usr/bin/python3 scenes/make_scenes.py

Writes the shipped scenes scenes/<name>.gltf (SCENES below: cornell, pillars and seven failure cases) and the
loader's test fixtures tests/data/*.gltf (see make_test_fixtures.py).
The output is deterministic: running it again must leave `git status` clean.

Conventions (scenes/README.md): metres, +Y up, the camera looks down its node's -Z axis, every mesh is
a triangle list with counter-clockwise front faces and per-vertex normals, metallic 0 everywhere except the
glossy scene's floor. The geometry helpers are in scene_geometry.py.
"""

import math
import os
import sys

sys.dont_write_bytecode = True  # keep scenes/ free of __pycache__
import gltf_writer  # noqa: E402  (the script's own folder is on sys.path)
import make_test_fixtures  # noqa: E402
from scene_geometry import (WALLS, add_geometry, add_moving_camera, add_room, axis_angle, box,  # noqa: E402
                            look_at, quad)

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)


# --- Cornell box -----------------------------------------------------------------------------------------
# After the Cornell box data (Cornell University Program of Computer Graphics, "Cornell Box Data"): a 556 mm
# box scaled by 2/556 to 2 m, and turned 180 degrees about Y so that the camera looks down -Z with the red
# wall on its left. The box spans x in [-1, 1], y in [0, 2], z in [-1, 1]; the front (z = +1) is open.

# Diffuse reflectances: RGB averages of the measured Cornell spectra, as in Bitterli's Tungsten and
# Mitsuba Cornell box scenes.
CORNELL_WHITE = (0.725, 0.71, 0.68, 1.0)
CORNELL_RED = (0.63, 0.065, 0.05, 1.0)
CORNELL_GREEN = (0.14, 0.45, 0.091, 1.0)
# The light's radiance (17, 12, 4) (the same scenes' Cornell light) as a normalised colour times a strength.
CORNELL_LIGHT_COLOR = (1.0, 12.0 / 17.0, 4.0 / 17.0)
CORNELL_LIGHT_STRENGTH = 17.0


def cornell():
    gltf = gltf_writer.GltfBuilder("cornell")
    white = gltf.add_material("white", CORNELL_WHITE)
    red = gltf.add_material("red", CORNELL_RED)
    green = gltf.add_material("green", CORNELL_GREEN)
    light = gltf.add_material("light", CORNELL_WHITE, emissive=CORNELL_LIGHT_COLOR,
                              emissive_strength=CORNELL_LIGHT_STRENGTH)

    # The room: five quads facing inwards, in world coordinates (their nodes have identity transforms).
    walls = [
        ("floor", quad((0, 0, 0), (1, 0, 0), (0, 0, -1)), white),       # normal +Y
        ("ceiling", quad((0, 2, 0), (1, 0, 0), (0, 0, 1)), white),      # normal -Y
        ("back_wall", quad((0, 1, -1), (1, 0, 0), (0, 1, 0)), white),   # normal +Z
        ("left_wall", quad((-1, 1, 0), (0, 1, 0), (0, 0, 1)), red),     # normal +X
        ("right_wall", quad((1, 1, 0), (0, 0, 1), (0, 1, 0)), green),   # normal -X
    ]
    for name, geometry, material in walls:
        gltf.add_node(name, mesh=add_geometry(gltf, name, geometry, material))

    # The light: 130 x 105 mm in the data, so 0.47 x 0.38 m here, 1 cm below the ceiling, facing down.
    light_quad = quad((0, 1.99, 0), (0.235, 0, 0), (0, 0, 0.19))  # cross(+x, +z) = -Y
    gltf.add_node("light", mesh=add_geometry(gltf, "light", light_quad, light))

    # Both blocks share one unit cube, placed by their nodes. In the data the short block is 165 mm on a
    # side, centred at (185.5, 169) mm on the floor and turned by 17 degrees; the tall block is 165 x 330 x
    # 165 mm at (368.5, 351) mm, turned the other way. Scaled by 2/556 and turned about Y as above:
    cube = add_geometry(gltf, "cube", box((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5)), white)
    gltf.add_node("short_box", mesh=cube, translation=(0.33, 0.3, 0.4),
                  rotation=axis_angle((0, 1, 0), -17), scale=(0.6, 0.6, 0.6))
    gltf.add_node("tall_box", mesh=cube, translation=(-0.33, 0.6, -0.26),
                  rotation=axis_angle((0, 1, 0), 17), scale=(0.6, 1.2, 0.6))

    # The data's camera: 800 mm in front of the opening at mid-height, a 35 mm lens on 25 x 25 mm film,
    # so yfov = 2 atan(12.5 / 35) = 0.686 rad (39.3 degrees). Here: 2.88 m in front of z = +1.
    camera = gltf.add_camera("camera", yfov=2 * math.atan(12.5 / 35), znear=0.05)
    gltf.add_node("camera", camera=camera, translation=(0, 1, 3.88))
    return gltf


# --- Pillars ---------------------------------------------------------------------------------------------
# The A-SVGF paper's soft-shadow test [ASVGF18 Sec. 5.1]: "eleven pillars moving left to right in front of
# an area light". Our layout (metres): a floor and a back wall at z = -4; eleven 0.2 x 2.5 x 0.2 pillars
# 0.5 m apart at z = -1; a 0.3 x 1.2 light high behind them (centre y = 4, z = -3.5) tilted 45 degrees
# down towards the camera. A pillar's shadow then runs from its foot at z = -1 to z = 3.2 (the line from
# the light's centre over the pillar's top: 4 m of drop over 2.5 m of run per 1.5 m), towards the camera.
# Across a shadow the penumbra is w b / a wide (w = 0.3 m light width, a = light to occluder, b = occluder
# to floor), and along z, b / (a + b) = (z + 1) / (z + 3.5); the umbra lasts while 0.3 b / a < 0.2 m (the
# pillar's width), i.e. b / (a + b) < 0.4, from the pillar's foot to z = 0.67. Beyond it, soft penumbrae.

PILLAR_COUNT = 11
PILLAR_SPACING = 0.5
PILLAR_SIZE = (0.2, 2.5, 0.2)
PILLARS_Z = -1.0
# The parent's x over time: 1 m/s (two pillar spacings per second), left to right.
PILLARS_KEY_TIMES = [0.0, 1.0, 2.0]
PILLARS_KEY_X = [-1.0, 0.0, 1.0]
# Irradiance at the floor under the shadows, E = L A cos_l cos_r / d^2 with A = 0.36 m^2 and, at
# (0, 0, 1): d^2 = 36.25 m^2, cos_l ~ 1, cos_r = 0.66, gives E = 0.0066 L; L = 250 gives E = 1.6, so a 0.7
# white floor reflects 0.7 E / pi = 0.37: a mid-grey lit floor and black umbrae.
PILLARS_LIGHT_STRENGTH = 250.0


def pillars():
    gltf = gltf_writer.GltfBuilder("pillars")
    grey = gltf.add_material("grey", (0.7, 0.7, 0.7, 1.0))
    stone = gltf.add_material("stone", (0.75, 0.6, 0.45, 1.0))
    light = gltf.add_material("light", (0.7, 0.7, 0.7, 1.0), emissive=(1.0, 1.0, 1.0),
                              emissive_strength=PILLARS_LIGHT_STRENGTH)

    # Floor x in [-8, 8], z in [-4, 7] and back wall y in [0, 6]: wide enough to fill the view.
    floor = quad((0, 0, 1.5), (8, 0, 0), (0, 0, -5.5))  # normal +Y
    gltf.add_node("floor", mesh=add_geometry(gltf, "floor", floor, grey))
    wall = quad((0, 3, -4), (8, 0, 0), (0, 3, 0))  # normal +Z
    gltf.add_node("back_wall", mesh=add_geometry(gltf, "back_wall", wall, grey))

    # The light quad is built facing +Z in its node's frame; rotating 45 degrees about +X turns its normal
    # to (0, -sin 45, cos 45): down and towards the camera.
    light_quad = quad((0, 0, 0), (0.15, 0, 0), (0, 0.6, 0))
    gltf.add_node("light", mesh=add_geometry(gltf, "light", light_quad, light), translation=(0, 4, -3.5),
                  rotation=axis_angle((1, 0, 0), 45))

    # One pillar mesh with its foot at y = 0, shared by eleven children of one moving parent.
    sx, sy, sz = PILLAR_SIZE
    pillar = add_geometry(gltf, "pillar", box((-sx / 2, 0, -sz / 2), (sx / 2, sy, sz / 2)), stone)
    parent = gltf.add_node("pillars", translation=(PILLARS_KEY_X[0], 0, PILLARS_Z))
    first_x = -PILLAR_SPACING * (PILLAR_COUNT - 1) / 2
    for i in range(PILLAR_COUNT):
        gltf.add_node("pillar_%02d" % i, parent=parent, mesh=pillar,
                      translation=(first_x + i * PILLAR_SPACING, 0, 0))
    keys = [(x, 0.0, PILLARS_Z) for x in PILLARS_KEY_X]
    gltf.add_animation("pillars_move", [(parent, "translation", PILLARS_KEY_TIMES, keys, "LINEAR")])

    # Camera 1.7 m high, 7 m in front of the pillars, pitched 15 degrees down. With yfov = 45 degrees the
    # view reaches the floor from z = 3.8 (1.7 / tan 37.5 in front of the camera) to the wall; the pillars'
    # tops (2.5 m) and the whole shadows fit, the light (above y = 3.6) stays out of view.
    camera = gltf.add_camera("camera", yfov=math.radians(45), znear=0.05)
    gltf.add_node("camera", camera=camera, translation=(0, 1.7, 6), rotation=axis_angle((1, 0, 0), -15))
    return gltf


# --- The failure cases ----------------------------------------------------------------------------------
# Seven scenes, each modelling only the situation in which a temporal denoiser fails that a paper figure
# shows, with a few boxes and quads. Each is 2-3 s of animation at 30 fps (frame f at t = f / 30 s); the
# event times below are repeated in scenes/README.md and checked by tests/scenes_failure_cases_test.cpp.
# Surfaces are diffuse (metallic 0) except the glossy scene's floor; every light is a one-sided quad or
# box (trace/lights.h) turned towards what the camera sees.

STONE = (0.5, 0.47, 0.43, 1.0)      # a mid-grey stone for the dungeon and the corridor
SANDSTONE = (0.68, 0.6, 0.48, 1.0)  # the corridor's warm walls (a Sponza-like tone)
WHITE = (0.75, 0.75, 0.75, 1.0)


# --- Flicker ---------------------------------------------------------------------------------------------
# The A-SVGF DUNGEON scene [ASVGF18 Sec. 5.1, Fig. 1 and Fig. 3]: "multiple static area light sources ...
# one rapidly moving red area light and a flickering, blue area light", seen from a moving camera. A closed
# stone room x in [-3, 3], y in [0, 3], z in [-5, 3]; two floor-to-ceiling pillars at x = -1.3, 1.3,
# z = -2.5 and a crate; two warm static lights on the side walls; a blue panel on the back wall that
# switches on and off (STEP keys, below); a small red emissive cube that sweeps across the room at
# y = 1, z = -1 (6.4 m/s, turning at x = +-2.4 every 0.75 s), throwing fast shadows of the pillars and
# the crate onto the back wall. The camera dollies 3.4 m across the front of the room in 3 s, turning to
# keep the back of the room in view.
# The blue light is on from t = 0, off at 0.5 s, ON AGAIN AT t = 1.0 s (frame 30: the documented
# off -> on switch; frame 29 is the last dark frame), off at 1.375 s, on at 1.75 s, off at 2.125 s and
# on at 2.5 s. The key times are binary fractions, exact in float32, so each switch lands on the first
# frame at or after its key: frames 15, 30, 42, 53, 64, 75.

FLICKER_BLUE_TIMES = [0.0, 0.5, 1.0, 1.375, 1.75, 2.125, 2.5]
FLICKER_BLUE_STRENGTH = 40.0
FLICKER_RED_TIMES = [0.0, 0.75, 1.5, 2.25, 3.0]
FLICKER_RED_X = [-2.4, 2.4, -2.4, 2.4, -2.4]


def flicker():
    gltf = gltf_writer.GltfBuilder("flicker")
    stone = gltf.add_material("stone", STONE)
    wood = gltf.add_material("wood", (0.45, 0.3, 0.18, 1.0))
    warm = gltf.add_material("warm_light", STONE, emissive=(1.0, 0.62, 0.3), emissive_strength=40.0)
    values = [FLICKER_BLUE_STRENGTH * (1 - k % 2) for k in range(len(FLICKER_BLUE_TIMES))]  # on, off, on, ...
    track = {"times": FLICKER_BLUE_TIMES, "values": values, "interpolation": "STEP"}
    blue = gltf.add_material("blue_light", STONE, emissive=(0.1, 0.3, 1.0), emissive_strength=FLICKER_BLUE_STRENGTH,
                             extras={"rtdr_emissive_strength": track})
    red = gltf.add_material("red_light", (0.8, 0.1, 0.05, 1.0), emissive=(1.0, 0.08, 0.04), emissive_strength=40.0)

    add_room(gltf, "room", (-3, 0, -5), (3, 3, 3), {wall: stone for wall in WALLS})
    pillar = add_geometry(gltf, "pillar", box((-0.25, 0, -0.25), (0.25, 3, 0.25)), stone)
    for name, x in (("pillar_left", -1.3), ("pillar_right", 1.3)):
        gltf.add_node(name, mesh=pillar, translation=(x, 0, -2.5))
    crate = add_geometry(gltf, "crate", box((-0.4, 0, -0.4), (0.4, 0.8, 0.4)), wood)
    gltf.add_node("crate", mesh=crate, translation=(0.3, 0, -3.9), rotation=axis_angle((0, 1, 0), 20))

    # The static lights: 0.5 x 0.7 m panels 2 cm off the side walls (no depth ties with the walls), facing in.
    left_panel = quad((-2.98, 1.9, -1.0), (0, 0.35, 0), (0, 0, 0.25))   # cross(y, z) = +X
    right_panel = quad((2.98, 1.9, -3.0), (0, 0, 0.25), (0, 0.35, 0))   # cross(z, y) = -X
    gltf.add_node("warm_light_left", mesh=add_geometry(gltf, "warm_light_left", left_panel, warm))
    gltf.add_node("warm_light_right", mesh=add_geometry(gltf, "warm_light_right", right_panel, warm))
    # The blue panel: 1.2 x 0.5 m, 2 cm in front of the back wall, facing the room (+Z).
    blue_panel = quad((0, 2.0, -4.98), (0.6, 0, 0), (0, 0.25, 0))
    gltf.add_node("blue_light", mesh=add_geometry(gltf, "blue_light", blue_panel, blue))
    # The red light: a 0.24 m cube, emitting from all six faces, swept along x by its node.
    cube = add_geometry(gltf, "red_light", box((-0.12, -0.12, -0.12), (0.12, 0.12, 0.12)), red)
    keys = [(x, 1.0, -1.0) for x in FLICKER_RED_X]
    node = gltf.add_node("red_light", mesh=cube, translation=keys[0])
    gltf.add_animation("red_light_sweep", [(node, "translation", FLICKER_RED_TIMES, keys, "LINEAR")])

    # The camera slides from (-1.6, 1.7, 2.4) to (1.6, 1.5, 1.4), keys every 0.5 s, looking at the back wall.
    times = [0.5 * k for k in range(7)]
    eyes = [(-1.6 + 3.2 * t / 3, 1.7 - 0.2 * t / 3, 2.4 - t / 3) for t in times]
    add_moving_camera(gltf, 55, times, eyes, (0, 1.1, -3))
    return gltf


# --- Falling light ---------------------------------------------------------------------------------------
# The A-SVGF SPONZA scene [ASVGF18 Sec. 5.1, Fig. 3]: "The camera flies through the corridor while an area
# light drops to the ground quickly". A closed corridor x in [-2, 2], y in [0, 4], z in [-12, 3] with warm
# walls and two rows of four 0.4 m square columns (x = +-1.3, z = -1, -3.5, -6, -8.5). Its only light is a
# 0.6 x 0.6 m quad facing down at x = 0, z = -5: it hangs at y = 3 m, DROPS TO y = 0.5 m BETWEEN t = 1.0 s
# AND t = 1.5 s (frames 30 to 45, 5 m/s) and stays there, so the lit area shrinks from the whole corridor
# to a bright pool around z = -5 and the ceiling and far walls fall dark. The camera flies 4 m down the
# corridor in 3 s at eye height.

FALLING_LIGHT_TIMES = [0.0, 1.0, 1.5, 3.0]
FALLING_LIGHT_Y = [3.0, 3.0, 0.5, 0.5]
FALLING_LIGHT_STRENGTH = 120.0


def falling_light():
    gltf = gltf_writer.GltfBuilder("falling-light")
    walls = gltf.add_material("sandstone", SANDSTONE)
    floor = gltf.add_material("floor", STONE)
    light = gltf.add_material("light", WHITE, emissive=(1.0, 0.95, 0.85), emissive_strength=FALLING_LIGHT_STRENGTH)

    materials = {wall: walls for wall in WALLS}
    materials["floor"] = floor
    add_room(gltf, "corridor", (-2, 0, -12), (2, 4, 3), materials)
    column = add_geometry(gltf, "column", box((-0.2, 0, -0.2), (0.2, 4, 0.2)), walls)
    for i, z in enumerate((-1.0, -3.5, -6.0, -8.5)):
        for side, x in (("left", -1.3), ("right", 1.3)):
            gltf.add_node("column_%s_%d" % (side, i), mesh=column, translation=(x, 0, z))

    # The lamp: the emitting quad at its node's origin, facing down, under an opaque 8 cm housing 1 cm above
    # it, so that seen from above (after the drop) it is a dark box and not the back of an emitter.
    keys = [(0.0, y, -5.0) for y in FALLING_LIGHT_Y]
    lamp = gltf.add_node("lamp", translation=keys[0])
    panel = quad((0, 0, 0), (0.3, 0, 0), (0, 0, 0.3))  # cross(x, z) = -Y: facing down
    gltf.add_node("light", parent=lamp, mesh=add_geometry(gltf, "light", panel, light))
    housing = box((-0.32, 0.01, -0.32), (0.32, 0.09, 0.32))
    gltf.add_node("lamp_housing", parent=lamp, mesh=add_geometry(gltf, "lamp_housing", housing, floor))
    gltf.add_animation("lamp_drop", [(lamp, "translation", FALLING_LIGHT_TIMES, keys, "LINEAR")])

    times = [0.5 * k for k in range(7)]
    eyes = [(0.3 - 0.2 * t, 1.6, 2.5 - 4 * t / 3) for t in times]
    add_moving_camera(gltf, 60, times, eyes, (0, 1.2, -12))
    return gltf


# --- Glossy ----------------------------------------------------------------------------------------------
# The A-SVGF GLOSSYSPONZA scene [ASVGF18 Sec. 5.1, Fig. 3] and the TRMV sun temple [TRMV21 Fig. 11]: glossy
# reflections under a fast camera move, where the reflected image moves unlike the surface it is seen in.
# A closed room x in [-5, 5], y in [0, 4], z in [-4, 7] with white walls and a brushed-metal floor
# (metallic 1, roughness 0.15, so GGX alpha = 0.0225: sharp but blurred reflections); four coloured boxes
# (red, green, blue, yellow) stand on it; a ceiling panel above the camera's side lights their fronts, and
# a strip light on the back wall gives a highlight in the floor. The camera orbits the boxes at 5.5 m
# radius, 1.8 m high, from -40 to +40 degrees in 2 s (about 3.8 m/s), looking at (0, 0.6, -0.5).

GLOSSY_FLOOR_ROUGHNESS = 0.15
GLOSSY_FLOOR_METALLIC = 1.0
GLOSSY_DURATION = 2.0


def glossy():
    gltf = gltf_writer.GltfBuilder("glossy")
    white = gltf.add_material("white", WHITE)
    metal = gltf.add_material("floor_metal", (0.85, 0.85, 0.85, 1.0), roughness=GLOSSY_FLOOR_ROUGHNESS,
                              metallic=GLOSSY_FLOOR_METALLIC)
    light = gltf.add_material("light", WHITE, emissive=(1.0, 1.0, 1.0), emissive_strength=25.0)

    materials = {wall: white for wall in WALLS}
    materials["floor"] = metal
    add_room(gltf, "room", (-5, 0, -4), (5, 4, 7), materials)
    # (colour, size x, y, z, centre x, z, turn about Y in degrees)
    boxes = [
        ("red", (0.8, 0.1, 0.08), (0.6, 1.2, 0.6), -1.3, -0.6, 15),
        ("green", (0.12, 0.6, 0.15), (0.8, 0.8, 0.8), 0.2, 0.7, -20),
        ("blue", (0.1, 0.2, 0.8), (0.5, 1.8, 0.5), 1.4, -1.3, 0),
        ("yellow", (0.85, 0.7, 0.1), (0.5, 0.5, 0.5), -0.1, -2.0, 35),
    ]
    for name, colour, (sx, sy, sz), x, z, turn in boxes:
        material = gltf.add_material(name, colour + (1.0,))
        mesh = add_geometry(gltf, name + "_box", box((-sx / 2, 0, -sz / 2), (sx / 2, sy, sz / 2)), material)
        gltf.add_node(name + "_box", mesh=mesh, translation=(x, 0, z), rotation=axis_angle((0, 1, 0), turn))

    ceiling_panel = quad((0, 3.98, 2.5), (0.75, 0, 0), (0, 0, 0.5))  # cross(x, z) = -Y
    strip = quad((0, 2.8, -3.98), (1.25, 0, 0), (0, 0.2, 0))          # cross(x, y) = +Z
    gltf.add_node("ceiling_light", mesh=add_geometry(gltf, "ceiling_light", ceiling_panel, light))
    gltf.add_node("strip_light", mesh=add_geometry(gltf, "strip_light", strip, light))

    target = (0.0, 0.6, -0.5)
    times = [0.25 * k for k in range(9)]
    angles = [math.radians(-40 + 80 * t / GLOSSY_DURATION) for t in times]
    eyes = [(target[0] + 5.5 * math.sin(a), 1.8, target[2] + 5.5 * math.cos(a)) for a in angles]
    add_moving_camera(gltf, 50, times, eyes, target)
    return gltf


# --- Fence -----------------------------------------------------------------------------------------------
# The TRMV fence scene [TRMV21 Sec. 6, Fig. 8]: "a rapidly moving fence in front and an area light behind
# it". A floor and a back wall (z = -6); a 14.4 m fence of 48 slats (0.08 x 1.4 x 0.04 m, 0.3 m apart, all
# sharing one mesh) on two rails, under one parent node at z = 0 that moves along x at 3 m/s, reversing at
# t = 1 s and t = 2 s (x = -1.5, 1.5, -1.5, 1.5 at t = 0, 1, 2, 3 s). A narrow 0.4 x 1 m light behind and
# above the fence (y = 3.5, z = -3), tilted 45 degrees towards the camera, casts the slats' shadows onto
# the floor in front of them (from z = 0 to z = 2, where the line from the light over a slat's top lands).
# The camera is static at (0, 1.6, 5), pitched 12 degrees down, yfov 45 degrees: the fence is about 5.1 m
# deep in the view, where at 640x360 a metre is 360 / (2 * 5.1 tan 22.5) = 85 px, so it moves about 8.5 px
# per frame (0.1 m), its shadows on the floor as much or more. The light stays above the view.

FENCE_SLATS = 48
FENCE_SPACING = 0.3
FENCE_SLAT = (0.08, 1.4, 0.04)
FENCE_TIMES = [0.0, 1.0, 2.0, 3.0]
FENCE_X = [-1.5, 1.5, -1.5, 1.5]


def fence():
    gltf = gltf_writer.GltfBuilder("fence")
    grey = gltf.add_material("grey", (0.7, 0.7, 0.7, 1.0))
    wood = gltf.add_material("wood", (0.55, 0.4, 0.25, 1.0))
    light = gltf.add_material("light", WHITE, emissive=(1.0, 1.0, 1.0), emissive_strength=200.0)

    floor = quad((0, 0, 1), (10, 0, 0), (0, 0, -7))  # x in [-10, 10], z in [-6, 8], normal +Y
    gltf.add_node("floor", mesh=add_geometry(gltf, "floor", floor, grey))
    wall = quad((0, 2.5, -6), (10, 0, 0), (0, 2.5, 0))  # normal +Z
    gltf.add_node("back_wall", mesh=add_geometry(gltf, "back_wall", wall, grey))

    parent = gltf.add_node("fence", translation=(FENCE_X[0], 0, 0))
    sx, sy, sz = FENCE_SLAT
    slat = add_geometry(gltf, "slat", box((-sx / 2, 0, -sz / 2), (sx / 2, sy, sz / 2)), wood)
    first_x = -FENCE_SPACING * (FENCE_SLATS - 1) / 2
    for i in range(FENCE_SLATS):
        gltf.add_node("slat_%02d" % i, parent=parent, mesh=slat, translation=(first_x + i * FENCE_SPACING, 0, 0))
    # Two rails just behind the slats (z in [-0.06, -0.02]), so no face of a rail meets a face of a slat.
    half_length = -first_x + 0.2
    rail = add_geometry(gltf, "rail", box((-half_length, -0.04, -0.06), (half_length, 0.04, -0.02)), wood)
    for name, y in (("rail_low", 0.35), ("rail_high", 1.15)):
        gltf.add_node(name, parent=parent, mesh=rail, translation=(0, y, 0))
    keys = [(x, 0.0, 0.0) for x in FENCE_X]
    gltf.add_animation("fence_move", [(parent, "translation", FENCE_TIMES, keys, "LINEAR")])

    panel = quad((0, 0, 0), (0.2, 0, 0), (0, 0.5, 0))  # faces +Z; turned 45 degrees about +X below
    gltf.add_node("light", mesh=add_geometry(gltf, "light", panel, light), translation=(0, 3.5, -3),
                  rotation=axis_angle((1, 0, 0), 45))

    camera = gltf.add_camera("camera", yfov=math.radians(45), znear=0.05)
    gltf.add_node("camera", camera=camera, translation=(0, 1.6, 5), rotation=axis_angle((1, 0, 0), -12))
    return gltf


# --- Occlusion -------------------------------------------------------------------------------------------
# The TRMV PICA scene [TRMV21 Sec. 6, Fig. 1 right and Fig. 12]: objects moving in front of a detailed,
# indirectly lit background, so every frame uncovers background whose history the objects hid (TRMV shows
# the indirect light alone). A closed room x in [-4, 4], y in [0, 5], z in [-3, 6]. The background is the
# back wall below y = 2.5, with a checker base colour texture (a 32 x 32 PNG of 4 x 4 cells of 8 texels,
# repeated so that a cell is 0.5 m); above it the wall is white. The only light is a cove: a 7 x 0.3 m
# strip at y = 2.7, 1 m in front of the back wall, facing straight up, hidden from the camera by a
# valance. It lights the ceiling and the walls above y = 2.7 directly; the textured wall, the floor and
# the objects are all below its plane and get bounced light only, mostly from the ceiling it washes. The
# camera sees the directly lit white wall above the valance along the top of the image (10% of it). An
# orange box (0.8 x 1.6 x 0.5 m) slides left to right 1.2 m in front of the back wall (x = -3 -> 3 in
# 3 s, 2 m/s) and a blue cube (0.6 m) right to left closer to the camera (x = 2.5 -> -2.5, 1.67 m/s).
# The camera is static, pitched 8 degrees down.

OCCLUSION_CELL_TEXELS = 8
OCCLUSION_CELLS = 4
OCCLUSION_CELL_SIZE = 0.5  # metres
OCCLUSION_WALL_TOP = 2.5   # the textured part of the back wall, y in [0, 2.5]
OCCLUSION_HEIGHT = 5.0


def checker_png():
    """A 32 x 32 checker of cream and brick-red 8 x 8 texel cells, sRGB-encoded."""
    cream, brick = (225, 212, 180, 255), (150, 62, 48, 255)
    n = OCCLUSION_CELL_TEXELS * OCCLUSION_CELLS
    rows = [[cream if (x // OCCLUSION_CELL_TEXELS + y // OCCLUSION_CELL_TEXELS) % 2 == 0 else brick
             for x in range(n)] for y in range(n)]
    return gltf_writer.png_rgba8(n, n, rows)


def occlusion():
    gltf = gltf_writer.GltfBuilder("occlusion")
    white = gltf.add_material("white", WHITE)
    floor = gltf.add_material("floor", (0.6, 0.55, 0.5, 1.0))
    texture = gltf.add_png_texture(checker_png(), "checker")
    checker = gltf.add_material("checker", (1.0, 1.0, 1.0, 1.0), texture=texture)
    orange = gltf.add_material("orange", (0.8, 0.42, 0.15, 1.0))
    blue = gltf.add_material("blue", (0.15, 0.3, 0.7, 1.0))
    light = gltf.add_material("light", WHITE, emissive=(1.0, 1.0, 1.0), emissive_strength=150.0)

    walls = {wall: white for wall in WALLS if wall != "back"}
    walls["floor"] = floor
    add_room(gltf, "room", (-4, 0, -3), (4, OCCLUSION_HEIGHT, 6), walls)
    # The back wall in two quads facing +Z: the textured background below y = 2.5, white above it.
    top, height = OCCLUSION_WALL_TOP, OCCLUSION_HEIGHT
    positions, normals, uvs, indices = quad((0, top / 2, -3), (4, 0, 0), (0, top / 2, 0))
    repeat = OCCLUSION_CELLS * OCCLUSION_CELL_SIZE  # one texture repeat covers 2 m
    uvs = [(u * 8 / repeat, v * top / repeat) for u, v in uvs]
    gltf.add_node("back_wall", mesh=add_geometry(gltf, "back_wall", (positions, normals, uvs, indices), checker))
    upper = quad((0, (top + height) / 2, -3), (4, 0, 0), (0, (height - top) / 2, 0))
    gltf.add_node("back_wall_top", mesh=add_geometry(gltf, "back_wall_top", upper, white))

    # The cove. The light faces straight up at y = 2.7, 1 m in front of the wall, so it washes the ceiling
    # 2.3 m above it broadly, and the whole textured wall (y <= 2.5) is below its plane. The valance
    # (y in [2.5, 2.71], z in [-1.8, -1.75], 2 cm short of the side walls) hides it: the camera's line of
    # sight to the light's front edge (y = 2.7, z = -1.85) passes the valance at
    # y = 1.4 + 1.3 * 6.25 / 6.35 = 2.68. The valance's top is only 1 cm above the light's plane, so the
    # light does not shine on it from close by (which would make fireflies in the bounced light).
    valance = box((-3.98, 2.5, -1.8), (3.98, 2.71, -1.75))
    gltf.add_node("valance", mesh=add_geometry(gltf, "valance", valance, white))
    panel = quad((0, 2.7, -2.0), (3.5, 0, 0), (0, 0, -0.15))  # cross(x, -z) = +Y
    gltf.add_node("light", mesh=add_geometry(gltf, "light", panel, light))

    tall = add_geometry(gltf, "tall_box", box((-0.4, 0, -0.25), (0.4, 1.6, 0.25)), orange)
    tall_node = gltf.add_node("tall_box", mesh=tall, translation=(-3, 0, -1.8))
    cube = add_geometry(gltf, "cube", box((-0.3, 0, -0.3), (0.3, 0.6, 0.3)), blue)
    cube_node = gltf.add_node("cube", mesh=cube, translation=(2.5, 0, 0.5), rotation=axis_angle((0, 1, 0), 30))
    gltf.add_animation("objects_move", [
        (tall_node, "translation", [0.0, 3.0], [(-3, 0, -1.8), (3, 0, -1.8)], "LINEAR"),
        (cube_node, "translation", [0.0, 3.0], [(2.5, 0, 0.5), (-2.5, 0, 0.5)], "LINEAR"),
    ])

    camera = gltf.add_camera("camera", yfov=math.radians(50), znear=0.05)
    gltf.add_node("camera", camera=camera, translation=(0.05, 1.4, 4.5), rotation=axis_angle((1, 0, 0), -8))
    return gltf


# --- Static ----------------------------------------------------------------------------------------------
# The still scene of the SVGF temporal-stability test [SVGF17 Sec. 5.4, Fig. 10]: "static light, camera, and
# scene", where any change between frames is the filter's own flicker and it must converge. A Cornell-like
# room x in [-2, 2], y in [0, 2.6], z in [-2, 2], open at z = 2, with an orange left and a blue right wall,
# a 0.7 m cube and a 0.6 x 1.5 x 0.6 m column, lit by one 0.8 x 0.8 m ceiling light. No animation at all.


def static():
    gltf = gltf_writer.GltfBuilder("static")
    white = gltf.add_material("white", WHITE)
    orange = gltf.add_material("orange", (0.75, 0.35, 0.1, 1.0))
    blue = gltf.add_material("blue", (0.1, 0.25, 0.6, 1.0))
    light = gltf.add_material("light", WHITE, emissive=(1.0, 0.92, 0.8), emissive_strength=20.0)

    materials = {"floor": white, "ceiling": white, "back": white, "left": orange, "right": blue}
    add_room(gltf, "room", (-2, 0, -2), (2, 2.6, 2), materials)  # no front wall
    panel = quad((0, 2.59, 0), (0.4, 0, 0), (0, 0, 0.4))  # cross(x, z) = -Y: facing down
    gltf.add_node("light", mesh=add_geometry(gltf, "light", panel, light))
    cube = add_geometry(gltf, "cube", box((-0.35, 0, -0.35), (0.35, 0.7, 0.35)), white)
    gltf.add_node("cube", mesh=cube, translation=(0.6, 0, 0.4), rotation=axis_angle((0, 1, 0), 25))
    column = add_geometry(gltf, "column", box((-0.3, 0, -0.3), (0.3, 1.5, 0.3)), white)
    gltf.add_node("column", mesh=column, translation=(-0.7, 0, -0.8), rotation=axis_angle((0, 1, 0), -20))

    camera = gltf.add_camera("camera", yfov=math.radians(40), znear=0.05)
    eye = (0.03, 1.3, 4.8)
    gltf.add_node("camera", camera=camera, translation=eye, rotation=look_at(eye, (0, 1.2, 0)))
    return gltf


# --- Shadow fold -----------------------------------------------------------------------------------------
# The scene for TRMV's shadow motion vector under a moving light [TRMV21 Sec. 4.1, Eq. 3: the light term
# T^-1 l_i] and its falloff on non-planar receivers [Eq. 4] (the paper's Fig. 9, apples: curved receivers
# under a fast moving area light). A moving light and a static occluder over a receiver with a fold, and
# nothing more: a grey floor (y = 0); a step block x in [-2, 0], y in [0, 0.4], z in [-1.5, 1.5], whose
# +X face (x = 0) is the fold's vertical part, floor -> face -> top; a thin slab (0.3 x 0.04 x 1 m,
# x in [0.45, 0.75], y in [1.2, 1.24], z in [-0.5, 0.5]) on two thin posts, static; and one 0.2 x 0.2 m
# quad light facing down at y = 2.8, z = 0, whose x is LINEAR -0.6 -> 3.4 over t = 0-2 s (2 m/s).
# The light moves along +X, so the slab's shadow moves along -X, across the fold: floor, face, top.
#
# Where the shadow falls. The line from the light's centre l = (x_l, 2.8, 0) through the slab's bottom
# centre b = (0.6, 1.2, 0) is p(t) = l + t (b - l) (the shadow ray's own line, Eq. 3's l -> b); it reaches
# height y at t = (2.8 - y) / 1.6: the floor at t = 1.75, the step's top at t = 1.5. So the shadow's
# centre is at x = 0.6 + 0.75 (0.6 - x_l) on the floor and x = 0.6 + 0.5 (0.6 - x_l) on the top, and it
# meets the face x = 0 where x_l = t 0.6 / (t - 1): at its foot (y = 0) for x_l = 1.4 (t = 1.0 s, frame 30)
# and at its top edge (y = 0.4) for x_l = 1.8 (t = 1.2 s, frame 36). Before frame 30 the centre lies on
# the floor (at x = 1.5 at frame 0), after frame 36 on the top (x = -0.8 at frame 60); in between it runs
# down the face, 2 m/s on average. The whole shadow (the slab's edges x = 0.45 and 0.75 by the same
# lines) first touches the face's foot at x_l = 1.05 (t = 0.825 s) and leaves its top edge at x_l = 2.25
# (t = 1.425 s).
# Its umbra stays wider than the light's penumbra: on the floor the slab's 0.3 m width becomes 0.525 m,
# of which 0.2 (1.2 / 1.6) = 0.15 m on each side is penumbra (the light's width times b / a).
# The shadow moves 0.75 * 2 = 1.5 m/s on the floor, 1 m/s on the top. The posts' thin shadows cross the
# fold too, at |z| >= 0.43 (the lines from the light at z = 0 spread them outwards), away from z = 0.
#
# The light's strength. Straight below it, at 2.8 m, the small quad gives E = L A cos_l cos_r / d^2 =
# L 0.04 / 7.84 = 0.0051 L; L = 500 gives E = 2.55, and the 0.7 grey floor reflects 0.7 E / pi = 0.57. On
# the step's top (d = 2.4 m, reflectance 0.75) that is 0.83; where the shadow starts, 2.1 m aside
# (d^2 = 12.25, both cosines 0.8), the floor reflects 0.23.
#
# The camera is static at (4, 2.4, 0.8), looking at (0.35, 0.2, -0.1), 30 degrees down, yfov 40
# degrees: it sees the floor in front of the step, the face, the top and the slab from above, and only
# below its own height (30 > 20 degrees, so even the top corners of the view point downwards), so never
# the light at y = 2.8. The floor (x, z in [-20, 20]) fills the view: the top corners' rays reach it
# about 15 m away.
# At 640x360 the shadow's centre moves from about (345, 287) px at frame 0 to (285, 111) at frame 60, and
# the face is 38 px high where it crosses it (z = 0).

SHADOW_FOLD_TIMES = [0.0, 2.0]
SHADOW_FOLD_LIGHT_X = [-0.6, 3.4]
SHADOW_FOLD_LIGHT_Y = 2.8
SHADOW_FOLD_LIGHT_STRENGTH = 500.0
SHADOW_FOLD_STEP = ((-2.0, 0.0, -1.5), (0.0, 0.4, 1.5))     # the block: lo and hi corners
SHADOW_FOLD_SLAB = ((0.45, 1.2, -0.5), (0.75, 1.24, 0.5))  # the occluder
SHADOW_FOLD_POST_Z = 0.45                                  # the posts under the slab's ends, x = 0.6


def shadow_fold():
    gltf = gltf_writer.GltfBuilder("shadow-fold")
    grey = gltf.add_material("grey", (0.7, 0.7, 0.7, 1.0))
    step_material = gltf.add_material("step", WHITE)
    wood = gltf.add_material("wood", (0.55, 0.4, 0.25, 1.0))
    light = gltf.add_material("light", WHITE, emissive=(1.0, 1.0, 1.0),
                              emissive_strength=SHADOW_FOLD_LIGHT_STRENGTH)

    floor = quad((0, 0, 0), (20, 0, 0), (0, 0, -20))  # cross(x, -z) = +Y
    gltf.add_node("floor", mesh=add_geometry(gltf, "floor", floor, grey))
    gltf.add_node("step", mesh=add_geometry(gltf, "step", box(*SHADOW_FOLD_STEP), step_material))
    gltf.add_node("slab", mesh=add_geometry(gltf, "slab", box(*SHADOW_FOLD_SLAB), wood))
    # The posts (4 cm square) end inside the slab, at y = 1.22, so no face of a post meets a face of the slab.
    post = add_geometry(gltf, "post", box((-0.02, 0, -0.02), (0.02, 1.22, 0.02)), wood)
    for name, z in (("post_back", -SHADOW_FOLD_POST_Z), ("post_front", SHADOW_FOLD_POST_Z)):
        gltf.add_node(name, mesh=post, translation=(0.6, 0, z))

    panel = quad((0, 0, 0), (0.1, 0, 0), (0, 0, 0.1))  # cross(x, z) = -Y: facing down
    keys = [(x, SHADOW_FOLD_LIGHT_Y, 0.0) for x in SHADOW_FOLD_LIGHT_X]
    node = gltf.add_node("light", mesh=add_geometry(gltf, "light", panel, light), translation=keys[0])
    gltf.add_animation("light_slide", [(node, "translation", SHADOW_FOLD_TIMES, keys, "LINEAR")])

    camera = gltf.add_camera("camera", yfov=math.radians(40), znear=0.05)
    eye = (4.0, 2.4, 0.8)
    gltf.add_node("camera", camera=camera, translation=eye, rotation=look_at(eye, (0.35, 0.2, -0.1)))
    return gltf


SCENES = {"cornell": cornell, "pillars": pillars, "flicker": flicker, "falling-light": falling_light,
          "glossy": glossy, "fence": fence, "occlusion": occlusion, "static": static,
          "shadow-fold": shadow_fold}


def main():
    for name, make in SCENES.items():
        make().write(os.path.join(HERE, name + ".gltf"))
    make_test_fixtures.write_all(os.path.join(REPO, "tests", "data"))


if __name__ == "__main__":
    main()
