"""Geometry and placement helpers for make_scenes.py: vectors, quads, boxes, rooms, rotations, cameras.

Standard library only. Every mesh is a (positions, normals, uvs, indices) tuple of a triangle list with
counter-clockwise front faces and per-vertex normals pointing out of the front (scenes/README.md).
"""

import math


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


def quat_mul(a, b):
    """The quaternion product a * b (x, y, z, w): the rotation b, then a."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def look_at(eye, target):
    """The rotation (x, y, z, w) that turns a camera at `eye` to look at `target` with no roll.

    A camera looks down -Z. Pitching it by a about +X, then yawing by b about +Y, turns -Z into
    (-cos a sin b, sin a, -cos a cos b); solving for the forward direction f gives a = asin(f.y) and
    b = atan2(-f.x, -f.z).
    """
    f = normalized(add(target, negated(eye)))
    pitch, yaw = math.degrees(math.asin(f[1])), math.degrees(math.atan2(-f[0], -f[2]))
    return quat_mul(axis_angle((0, 1, 0), yaw), axis_angle((1, 0, 0), pitch))


# The six inner faces of a room: back is the z = lo face (seen from inside looking down -Z), front the
# z = hi face, left the x = lo face.
WALLS = ("floor", "ceiling", "back", "front", "left", "right")


def room(lo, hi, walls=WALLS):
    """The named inner faces of the box lo..hi, each a quad facing into the box: {name: geometry}."""
    c = scaled(add(lo, hi), 0.5)
    hx, hy, hz = scaled(add(hi, negated(lo)), 0.5)
    faces = {
        "floor": quad((c[0], lo[1], c[2]), (hx, 0, 0), (0, 0, -hz)),   # cross(x, -z) = +Y
        "ceiling": quad((c[0], hi[1], c[2]), (hx, 0, 0), (0, 0, hz)),  # cross(x, z) = -Y
        "back": quad((c[0], c[1], lo[2]), (hx, 0, 0), (0, hy, 0)),     # cross(x, y) = +Z
        "front": quad((c[0], c[1], hi[2]), (-hx, 0, 0), (0, hy, 0)),   # cross(-x, y) = -Z
        "left": quad((lo[0], c[1], c[2]), (0, hy, 0), (0, 0, hz)),     # cross(y, z) = +X
        "right": quad((hi[0], c[1], c[2]), (0, 0, hz), (0, hy, 0)),    # cross(z, y) = -X
    }
    return {name: faces[name] for name in walls}


def add_room(gltf, name, lo, hi, materials):
    """Adds the walls named in `materials` (wall -> material index) of room(lo, hi) as nodes "<name>_<wall>"."""
    for wall, geometry in room(lo, hi, tuple(materials)).items():
        node = "%s_%s" % (name, wall)
        gltf.add_node(node, mesh=add_geometry(gltf, node, geometry, materials[wall]))


def add_moving_camera(gltf, yfov_degrees, times, eyes, target):
    """A camera node that passes through eyes[k] at times[k] (LINEAR) always looking at `target`.

    Rotation keys are slerped between keys, so a key every 0.25 s or so keeps the target near the centre.
    """
    camera = gltf.add_camera("camera", yfov=math.radians(yfov_degrees), znear=0.05)
    rotations = [look_at(eye, target) for eye in eyes]
    node = gltf.add_node("camera", camera=camera, translation=eyes[0], rotation=rotations[0])
    gltf.add_animation("camera_move", [(node, "translation", times, eyes, "LINEAR"),
                                       (node, "rotation", times, rotations, "LINEAR")])
    return node
