#!/usr/bin/python3
"""Writes the shipped glTF scenes and the loader's test fixtures. Run from anywhere:

    /usr/bin/python3 scenes/make_scenes.py

Writes scenes/cornell.gltf, scenes/pillars.gltf and tests/data/*.gltf (see make_test_fixtures.py).
The output is deterministic: running it again must leave `git status` clean.

Conventions (scenes/README.md): metres, +Y up, the camera looks down its node's -Z axis, every mesh is
a triangle list with counter-clockwise front faces and per-vertex normals, metallic 0 everywhere.
"""

import math
import os
import sys

sys.dont_write_bytecode = True  # keep scenes/ free of __pycache__
import gltf_writer  # noqa: E402  (the script's own folder is on sys.path)
import make_test_fixtures  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)


# --- Geometry helpers ------------------------------------------------------------------------------------

def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def scaled(a, s):
    return tuple(x * s for x in a)


def negated(a):
    return scaled(a, -1.0)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalized(a):
    return scaled(a, 1.0 / math.sqrt(sum(x * x for x in a)))


def quad(center, half_u, half_v):
    """A rectangle center +- half_u +- half_v facing cross(half_u, half_v), counter-clockwise from the front.

    Returns (positions, normals, uvs, indices); u runs along half_u, v along -half_v (glTF's UV origin is
    the top-left corner).
    """
    normal = normalized(cross(half_u, half_v))
    corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    positions = [add(center, add(scaled(half_u, su), scaled(half_v, sv))) for su, sv in corners]
    uvs = [((su + 1) / 2, (1 - sv) / 2) for su, sv in corners]
    return positions, [normal] * 4, uvs, [0, 1, 2, 0, 2, 3]


def merge(parts):
    """Concatenates (positions, normals, uvs, indices) tuples into one, offsetting the indices."""
    positions, normals, uvs, indices = [], [], [], []
    for p, n, t, i in parts:
        indices += [len(positions) + k for k in i]
        positions += p
        normals += n
        uvs += t
    return positions, normals, uvs, indices


def box(lo, hi):
    """An axis-aligned box from corner lo to corner hi: six outward-facing quads, 24 vertices."""
    c = scaled(add(lo, hi), 0.5)
    h = scaled(add(hi, negated(lo)), 0.5)  # half extents
    x, y, z = (h[0], 0, 0), (0, h[1], 0), (0, 0, h[2])
    return merge([
        quad(add(c, x), negated(z), y),           # +X face: cross(-z, y) = +x
        quad(add(c, negated(x)), z, y),           # -X face: cross(z, y) = -x
        quad(add(c, y), x, negated(z)),           # +Y face (top): cross(x, -z) = +y
        quad(add(c, negated(y)), x, z),           # -Y face (bottom): cross(x, z) = -y
        quad(add(c, z), x, y),                    # +Z face: cross(x, y) = +z
        quad(add(c, negated(z)), negated(x), y),  # -Z face: cross(-x, y) = -z
    ])


def axis_angle(axis, degrees):
    """The unit quaternion (x, y, z, w) of a rotation by `degrees` about `axis` (right-handed)."""
    half = math.radians(degrees) / 2
    a = normalized(axis)
    return (a[0] * math.sin(half), a[1] * math.sin(half), a[2] * math.sin(half), math.cos(half))


def add_geometry(gltf, name, geometry, material):
    """One mesh with one primitive from a (positions, normals, uvs, indices) tuple."""
    positions, normals, uvs, indices = geometry
    return gltf.add_mesh(name, [gltf.primitive(positions, normals, uvs, indices, material)])


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


def main():
    cornell().write(os.path.join(HERE, "cornell.gltf"))
    pillars().write(os.path.join(HERE, "pillars.gltf"))
    make_test_fixtures.write_all(os.path.join(REPO, "tests", "data"))


if __name__ == "__main__":
    main()
