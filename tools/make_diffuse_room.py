#!/usr/bin/python3
"""Writes tests/data/diffuse-room.gltf: the scene tools/compare_cycles.sh was checked on.

    /usr/bin/python3 tools/make_diffuse_room.py

A closed room, 4 x 2.5 x 4 m, of diffuse glTF materials only (metallic 0, roughness 1): grey floor, white
ceiling and back wall, a red left and a green right wall, a grey front wall behind the camera; a 1 x 0.6 m
rectangular light 1 cm below the ceiling, facing down, glTF doubleSided (so its back lights the ceiling above
it, in RTDR as in Cycles: scenes/README.md); two blocks, one white, one blue-grey. The camera stands inside,
near the front wall, looking down -Z. Not a shipped scene: a user's kind of scene, for comparing with Blender.
Built with the shipped scenes' writer (scenes/gltf_writer.py), so the output is deterministic.
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "scenes"))

import gltf_writer  # noqa: E402
from scene_geometry import add_geometry, add_room, axis_angle, box, quad  # noqa: E402


def diffuse_room():
    gltf = gltf_writer.GltfBuilder("diffuse-room")
    grey = gltf.add_material("grey", (0.5, 0.5, 0.5, 1.0))
    white = gltf.add_material("white", (0.8, 0.8, 0.8, 1.0))
    red = gltf.add_material("red", (0.7, 0.15, 0.1, 1.0))
    green = gltf.add_material("green", (0.15, 0.55, 0.15, 1.0))
    blue = gltf.add_material("blue_grey", (0.3, 0.35, 0.6, 1.0))
    light = gltf.add_material("light", (0.8, 0.8, 0.8, 1.0), emissive=(1.0, 0.9, 0.75), emissive_strength=12.0)
    gltf.doc["materials"][light]["doubleSided"] = True
    add_room(gltf, "room", (-2.0, 0.0, -2.0), (2.0, 2.5, 2.0),
             {"floor": grey, "ceiling": white, "back": white, "front": grey, "left": red, "right": green})
    # The light: 1 x 0.6 m, 1 cm below the ceiling, facing down (cross(+x, +z) = -Y).
    gltf.add_node("light", mesh=add_geometry(gltf, "light", quad((0, 2.49, -0.3), (0.5, 0, 0), (0, 0, 0.3)), light))
    cube = add_geometry(gltf, "white_cube", box((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5)), white)
    gltf.add_node("short_block", mesh=cube, translation=(0.7, 0.4, -0.6), rotation=axis_angle((0, 1, 0), -20),
                  scale=(0.8, 0.8, 0.8))
    tall = add_geometry(gltf, "blue_cube", box((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5)), blue)
    gltf.add_node("tall_block", mesh=tall, translation=(-0.8, 0.8, -1.1), rotation=axis_angle((0, 1, 0), 15),
                  scale=(0.7, 1.6, 0.7))
    # 60 degrees vertical field of view, square images; 1.9 m in front of the room's centre, at 1.3 m.
    camera = gltf.add_camera("camera", yfov=math.radians(60.0), znear=0.05)
    gltf.add_node("camera", camera=camera, translation=(0, 1.3, 1.9))
    return gltf


if __name__ == "__main__":
    diffuse_room().write(os.path.join(HERE, "..", "tests", "data", "diffuse-room.gltf"))
