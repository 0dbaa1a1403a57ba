"""The loader's test fixtures in tests/data/, written by make_scenes.py.

anim_test.gltf exercises everything the loader reads; its exact values are repeated in
tests/scenes_animation_test.cpp and tests/scenes_gltf_loader_test.cpp, which compute the expected results by
hand. The bad_*.gltf files each break one rule; the loader must reject each with a one-line rtdr::Error.
"""

import math
import os

import gltf_writer
from gltf_writer import UNSIGNED_BYTE, GltfBuilder, f32

SIN45 = math.sin(math.radians(45))  # written as the float32 0.70710677


def anim_test():
    """A parent with animated translation and a child with animated rotation and scale, a camera, a textured
    material with an animated emissive strength, and a primitive with no material. Key values:

      parent  rest translation (5, 5, 5), replaced by its track
              translation LINEAR  t = 0, 1, 2  ->  (0, 0, 0), (2, 0, 0), (2, 4, 0)        (animation "move")
      child   rest translation (0, 1, 0), child of parent
              rotation LINEAR     t = 0, 1, 2  ->  0, 90, 180 degrees about +Z, as quaternions (x, y, z, w)
                                  (0, 0, 0, 1), (0, 0, s, s), (0, 0, -1, 0), s = sin 45 degrees; the last
                                  two have dot -s < 0, so slerp must flip the last (shortest arc)
              scale STEP          t = 0.5, 1.5 ->  (0.5, 1, 1.5), (2, 3, 1)                (animation "turn")
      camera  translation (0, 0, 10), yfov 0.5, znear 0.1, zfar 100
      matrix_node  `matrix` = T(1, 2, 3) R(90 degrees about +Y) S(2, 3, 4)
      mirror_node  `matrix` = T(0, -1, 0) R(30 degrees about +Z) S(-1, 1, 1), a mirror
      material "checker": 2x2 sRGB PNG, rows top to bottom (255 255 255 255) (0 0 0 255) /
              (128 128 128 255) (255 0 128 128); emissive (1, 0.5, 0.25), KHR strength 3,
              extras rtdr_emissive_strength LINEAR t = 0, 1, 2 -> 2, 4, 0
      mesh "parts": primitive 0 a textured quad with UNSIGNED_BYTE indices and material "checker";
              primitive 1 a non-indexed triangle with no material
      scene extras rtdr_fps 24

    The child is written before its parent in the nodes array, so the loader must reorder them.
    """
    gltf = GltfBuilder("anim_test")
    rows = [[(255, 255, 255, 255), (0, 0, 0, 255)], [(128, 128, 128, 255), (255, 0, 128, 128)]]
    texture = gltf.add_png_texture(gltf_writer.png_rgba8(2, 2, rows), "checker")
    strength_track = {"times": [0.0, 1.0, 2.0], "values": [2.0, 4.0, 0.0], "interpolation": "LINEAR"}
    checker = gltf.add_material("checker", (1, 1, 1, 1), roughness=0.5, emissive=(1, 0.5, 0.25),
                                emissive_strength=3.0, texture=texture,
                                extras={"rtdr_emissive_strength": strength_track})

    quad = gltf.primitive(positions=[(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], normals=[(0, 0, 1)] * 4,
                          uvs=[(0, 1), (1, 1), (1, 0), (0, 0)], indices=[0, 1, 2, 0, 2, 3],
                          material=checker, index_type=UNSIGNED_BYTE)
    triangle = gltf.primitive(positions=[(0, 0, 1), (1, 0, 1), (0, 1, 1)])
    parts = gltf.add_mesh("parts", [quad, triangle])

    child = gltf.add_node("child", mesh=parts, translation=(0, 1, 0), root=False)
    parent = gltf.add_node("parent", translation=(5, 5, 5))
    gltf.add_child(parent, child)
    camera = gltf.add_camera("camera", yfov=0.5, znear=0.1, zfar=100)
    gltf.add_node("camera", camera=camera, translation=(0, 0, 10))
    gltf.add_matrix_node("matrix_node", trs_matrix((1, 2, 3), (0, 1, 0), 90, (2, 3, 4)))
    gltf.add_matrix_node("mirror_node", trs_matrix((0, -1, 0), (0, 0, 1), 30, (-1, 1, 1)))

    gltf.add_animation("move", [(parent, "translation", [0, 1, 2], [(0, 0, 0), (2, 0, 0), (2, 4, 0)], "LINEAR")])
    rotations = [(0, 0, 0, 1), (0, 0, SIN45, SIN45), (0, 0, -1, 0)]
    gltf.add_animation("turn", [(child, "rotation", [0, 1, 2], rotations, "LINEAR"),
                                (child, "scale", [0.5, 1.5], [(0.5, 1, 1.5), (2, 3, 1)], "STEP")])
    gltf.set_scene_extras({"rtdr_fps": 24})
    return gltf.to_json()


def trs_matrix(translation, axis, degrees, scale):
    """T * R * S as glTF's column-major 16 numbers, R a rotation about the x, y or z axis."""
    # Rounded so that cos 90 degrees is written as 0 and not 6e-17.
    c, s = round(math.cos(math.radians(degrees)), 12), round(math.sin(math.radians(degrees)), 12)
    k = axis.index(1)  # the rotation axis; i, j are the other two, in cyclic order (x -> y -> z -> x)
    i, j = (k + 1) % 3, (k + 2) % 3
    rotation = [[0.0] * 3 for _ in range(3)]  # rotation[column][row]
    rotation[k][k] = 1.0
    rotation[i][i], rotation[i][j] = c, s   # e_i -> c e_i + s e_j
    rotation[j][i], rotation[j][j] = -s, c  # e_j -> -s e_i + c e_j
    columns = [[r * scale[col] + 0.0 for r in rotation[col]] + [0.0] for col in range(3)]  # + 0.0: no "-0.0"
    return [v for column in columns for v in column] + list(translation) + [1.0]


# --- Malformed files ---------------------------------------------------------------------------------------

TRIANGLE = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]


def minimal(positions=TRIANGLE, indices=(0, 1, 2), camera=True, animation=None):
    """A valid one-triangle scene (plus an optional animation of the triangle's node), to break one rule."""
    gltf = GltfBuilder("minimal")
    mesh = gltf.add_mesh("triangle", [gltf.primitive(positions, indices=list(indices))])
    gltf.add_node("triangle", mesh=mesh)
    if camera:
        gltf.add_node("camera", camera=gltf.add_camera("camera", yfov=0.8, znear=0.1), translation=(0, 0, 3))
    if animation is not None:
        times, values, interpolation = animation
        gltf.add_animation("bad", [(0, "translation", times, values, interpolation)])
    return gltf.to_json()


def with_changes(doc, change):
    change(doc)
    return doc


def set_path(doc, path, value):
    """doc[path[0]][path[1]]... = value."""
    for key in path[:-1]:
        doc = doc[key]
    doc[path[-1]] = value


def node_cycle(doc):
    """Two nodes that are each other's child, reachable from the scene."""
    doc["nodes"] += [{"name": "a", "children": [3]}, {"name": "b", "children": [2]}]
    doc["scenes"][0]["nodes"].append(2)


def empty_buffer(doc):
    doc["buffers"] = [{"byteLength": 0, "uri": "data:application/octet-stream;base64,"}]


MOVE = ([0, 1, 2], [(0, 0, 0), (1, 0, 0), (2, 0, 0)], "LINEAR")

BAD_FILES = {
    # name: the document (a dict, or raw text for files that are not glTF at all)
    "bad_not_json": "This is not a glTF file.\n",
    "bad_accessor_range": with_changes(minimal(), lambda d: set_path(d, ["accessors", 0, "count"], 1000)),
    "bad_buffer_view_range": with_changes(minimal(), lambda d: set_path(d, ["bufferViews", 1, "byteLength"], 4000)),
    "bad_empty_buffer": with_changes(minimal(), empty_buffer),
    "bad_index_range": minimal(indices=(0, 1, 7)),
    "bad_lines": with_changes(minimal(), lambda d: set_path(d, ["meshes", 0, "primitives", 0, "mode"], 1)),
    "bad_material_index": with_changes(minimal(), lambda d: set_path(d, ["meshes", 0, "primitives", 0, "material"], 5)),
    "bad_nan_position": minimal(positions=[(0, 0, 0), (1, 0, 0), (float("nan"), 1, 0)]),
    "bad_no_camera": minimal(camera=False),
    "bad_orthographic": with_changes(minimal(), lambda d: set_path(d, ["cameras", 0], {
        "type": "orthographic", "orthographic": {"xmag": 1.0, "ymag": 1.0, "znear": 0.1, "zfar": 10.0}})),
    "bad_node_cycle": with_changes(minimal(), node_cycle),
    "bad_unsorted_keys": minimal(animation=([0, 2, 1], MOVE[1], "LINEAR")),
    "bad_key_count": minimal(animation=([0, 1, 2], MOVE[1][:2], "LINEAR")),
    # CUBICSPLINE stores in-tangent, value, out-tangent per key: 9 values for 3 keys.
    "bad_cubicspline": minimal(animation=(MOVE[0], MOVE[1] * 3, "CUBICSPLINE")),
    "bad_weights": with_changes(minimal(animation=MOVE),
                                lambda d: set_path(d, ["animations", 0, "channels", 0, "target", "path"], "weights")),
    # Column 1 leans by 0.5 in x: a shear, which no T * R * S can produce.
    "bad_matrix_shear": with_changes(minimal(), lambda d: set_path(d, ["nodes", 0, "matrix"], [
        1.0, 0.0, 0.0, 0.0, 0.5, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0])),
    "bad_emissive_track": with_changes(minimal(), lambda d: set_path(d, ["materials"], [{
        "name": "flicker", "extras": {"rtdr_emissive_strength": {"times": [0, 1], "values": [f32(1.0)]}}}])),
}


def write_all(data_dir):
    os.makedirs(data_dir, exist_ok=True)
    gltf_writer.write_json(os.path.join(data_dir, "anim_test.gltf"), anim_test())
    for name, doc in BAD_FILES.items():
        text = doc if isinstance(doc, str) else gltf_writer.to_text(doc)
        gltf_writer.write_text(os.path.join(data_dir, name + ".gltf"), text)
    # A valid file cut in half, as a failed download would leave it.
    text = gltf_writer.to_text(minimal())
    gltf_writer.write_text(os.path.join(data_dir, "bad_truncated.gltf"), text[: len(text) // 2])
