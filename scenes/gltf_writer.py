"""A tiny glTF 2.0 writer: one embedded buffer, meshes, nodes, materials, a camera, animations.

Used by make_scenes.py. Standard library only. Everything is written in insertion order and floats are
written as the shortest decimal that reads back as the same float32, so the same calls produce the same
bytes on every run (the .gltf files in git are regenerated, never edited by hand).

glTF references in comments: "spec 3.6.2" means Sec. 3.6.2 of the glTF 2.0 specification.
"""

import base64
import json
import math
import struct
import zlib

# Accessor component types and element types (spec 3.6.2.2, Table "componentType").
BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT, UNSIGNED_INT, FLOAT = 5120, 5121, 5122, 5123, 5125, 5126
STRUCT_CODE = {BYTE: "b", UNSIGNED_BYTE: "B", SHORT: "h", UNSIGNED_SHORT: "H", UNSIGNED_INT: "I", FLOAT: "f"}
TYPE_SIZE = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
# bufferView targets (spec 3.6.1.1): vertex attributes and vertex indices.
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963


def f32(x):
    """The shortest decimal that rounds to the same float32 as x, returned as a Python float.

    json writes a Python float with repr(), which is the shortest decimal for the float64; a float64
    made from a short string prints back as that string, so 0.3 stays "0.3" and not 0.30000001192092896.
    """
    if not math.isfinite(x):
        return x
    target = struct.pack("<f", x)
    for digits in range(1, 10):  # 9 significant digits always round-trip a float32 (IEEE 754)
        candidate = float("%.*g" % (digits, x))
        if struct.pack("<f", candidate) == target:
            return candidate
    return x


def f32_list(values):
    return [f32(v) for v in values]


def png_rgba8(width, height, rows):
    """A PNG file (PNG spec, 2nd ed.) with 8-bit RGBA pixels; rows[y][x] = (r, g, b, a), row 0 on top."""

    def chunk(kind, data):
        # Each chunk: length, type, data, CRC-32 of type + data (PNG spec Sec. 5.3).
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    # IHDR: width, height, bit depth 8, colour type 6 (RGBA), compression 0, filter 0, no interlace.
    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    # Every scanline starts with its filter type, 0 = None (PNG spec Sec. 9.2).
    raw = b"".join(b"\x00" + bytes(c for pixel in row for c in pixel) for row in rows)
    # The sRGB chunk (rendering intent 0, perceptual) says the samples are sRGB-encoded.
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"sRGB", b"\x00")
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


class GltfBuilder:
    """Collects glTF objects and binary data; write() embeds the buffer as a base64 data URI."""

    def __init__(self, scene_name):
        self.doc = {
            "asset": {"version": "2.0", "generator": "RTDR scenes/make_scenes.py"},
            "scene": 0,
            "scenes": [{"name": scene_name, "nodes": []}],
        }
        self.blob = bytearray()

    def _append(self, key, obj):
        """Appends obj to the top-level array `key` and returns its index."""
        self.doc.setdefault(key, []).append(obj)
        return len(self.doc[key]) - 1

    # --- Binary data -----------------------------------------------------------------------------------

    def add_accessor(self, values, component_type, type_name, target=None, bounds=False):
        """Packs values (scalars or tuples) into a new bufferView and returns the accessor index.

        bounds=True writes min/max, which the spec requires on POSITION and on animation inputs.
        """
        width = TYPE_SIZE[type_name]
        rows = [v if isinstance(v, (tuple, list)) else (v,) for v in values]
        assert all(len(r) == width for r in rows), "every element needs %d components" % width
        flat = [c for r in rows for c in r]
        data = struct.pack("<%d%s" % (len(flat), STRUCT_CODE[component_type]), *flat)
        while len(self.blob) % 4:  # bufferViews start 4-byte aligned (spec 3.6.2.4 "Data Alignment")
            self.blob.append(0)
        view = {"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)}
        if target is not None:
            view["target"] = target
        self.blob += data
        accessor = {"bufferView": self._append("bufferViews", view), "componentType": component_type,
                    "count": len(rows), "type": type_name}
        if bounds:
            # Componentwise min/max of the stored float32 values; non-finite values (only in the NaN
            # fixture) are skipped, since JSON cannot hold them.
            stored = [struct.unpack("<%df" % width, struct.pack("<%df" % width, *r)) for r in rows]
            columns = [[c for c in col if math.isfinite(c)] or [0.0] for col in zip(*stored)]
            accessor["min"] = f32_list(min(col) for col in columns)
            accessor["max"] = f32_list(max(col) for col in columns)
        return self._append("accessors", accessor)

    # --- Geometry ----------------------------------------------------------------------------------------

    def primitive(self, positions, normals=None, uvs=None, indices=None, material=None,
                  index_type=UNSIGNED_SHORT):
        """One triangle-list primitive (mode 4, the default); returns the JSON object for add_mesh."""
        attributes = {"POSITION": self.add_accessor(positions, FLOAT, "VEC3", ARRAY_BUFFER, bounds=True)}
        if normals is not None:
            attributes["NORMAL"] = self.add_accessor(normals, FLOAT, "VEC3", ARRAY_BUFFER)
        if uvs is not None:
            attributes["TEXCOORD_0"] = self.add_accessor(uvs, FLOAT, "VEC2", ARRAY_BUFFER)
        prim = {"attributes": attributes}
        if indices is not None:
            prim["indices"] = self.add_accessor(indices, index_type, "SCALAR", ELEMENT_ARRAY_BUFFER)
        if material is not None:
            prim["material"] = material
        return prim

    def add_mesh(self, name, primitives):
        return self._append("meshes", {"name": name, "primitives": primitives})

    # --- Materials and textures --------------------------------------------------------------------------

    def add_material(self, name, base_color, roughness=1.0, metallic=0.0, emissive=None,
                     emissive_strength=None, texture=None, extras=None):
        """A metallic-roughness material (spec 3.9.2); emissive_strength uses KHR_materials_emissive_strength."""
        pbr = {"baseColorFactor": f32_list(base_color), "metallicFactor": f32(metallic),
               "roughnessFactor": f32(roughness)}
        if texture is not None:
            pbr["baseColorTexture"] = {"index": texture}
        material = {"name": name, "pbrMetallicRoughness": pbr}
        if emissive is not None:
            material["emissiveFactor"] = f32_list(emissive)
        if emissive_strength is not None:
            material["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": f32(emissive_strength)}}
            self.use_extension("KHR_materials_emissive_strength")
        if extras is not None:
            material["extras"] = extras
        return self._append("materials", material)

    def add_png_texture(self, png_bytes, name):
        """An embedded PNG image with a nearest-filter, repeat-wrap sampler; returns the texture index."""
        uri = "data:image/png;base64," + base64.b64encode(png_bytes).decode("ascii")
        image = self._append("images", {"name": name, "uri": uri})
        # 9728 = NEAREST filter, 10497 = REPEAT wrap (spec 3.8.4 "Samplers").
        sampler = self._append("samplers", {"magFilter": 9728, "minFilter": 9728, "wrapS": 10497, "wrapT": 10497})
        return self._append("textures", {"sampler": sampler, "source": image})

    def use_extension(self, name):
        used = self.doc.setdefault("extensionsUsed", [])
        if name not in used:
            used.append(name)

    # --- Nodes, camera, animation ------------------------------------------------------------------------

    def add_node(self, name, parent=None, mesh=None, camera=None, translation=None, rotation=None, scale=None,
                 root=True):
        """A node with TRS (rotation as a quaternion x, y, z, w).

        With no parent it is a root of the scene, unless root=False (add_child attaches it later).
        """
        node = {"name": name}
        if mesh is not None:
            node["mesh"] = mesh
        if camera is not None:
            node["camera"] = camera
        for key, value in (("translation", translation), ("rotation", rotation), ("scale", scale)):
            if value is not None:
                node[key] = f32_list(value)
        index = self._append("nodes", node)
        if parent is not None:
            self.add_child(parent, index)
        elif root:
            self.doc["scenes"][0]["nodes"].append(index)
        return index

    def add_matrix_node(self, name, matrix):
        """A root node placed by a column-major 4x4 `matrix` instead of TRS (spec 3.5.3)."""
        index = self._append("nodes", {"name": name, "matrix": f32_list(matrix)})
        self.doc["scenes"][0]["nodes"].append(index)
        return index

    def add_child(self, parent, child):
        self.doc["nodes"][parent].setdefault("children", []).append(child)

    def add_camera(self, name, yfov, znear, zfar=None):
        """A perspective camera (spec 3.10.2); it looks down its node's -Z axis with +Y up."""
        perspective = {"yfov": f32(yfov), "znear": f32(znear)}
        if zfar is not None:
            perspective["zfar"] = f32(zfar)
        return self._append("cameras", {"name": name, "type": "perspective", "perspective": perspective})

    def add_animation(self, name, channels):
        """channels: (node, path, times, values, interpolation); path is translation, rotation or scale."""
        animation = {"name": name, "channels": [], "samplers": []}
        for node, path, times, values, interpolation in channels:
            width = 4 if path == "rotation" else 3
            sampler = {"input": self.add_accessor(times, FLOAT, "SCALAR", bounds=True),
                       "interpolation": interpolation,
                       "output": self.add_accessor(values, FLOAT, "VEC%d" % width)}
            animation["samplers"].append(sampler)
            animation["channels"].append({"sampler": len(animation["samplers"]) - 1,
                                          "target": {"node": node, "path": path}})
        return self._append("animations", animation)

    def set_scene_extras(self, extras):
        self.doc["scenes"][0]["extras"] = extras

    # --- Output ------------------------------------------------------------------------------------------

    def to_json(self):
        """The finished document: the buffer goes last, as one base64 data URI."""
        doc = dict(self.doc)
        uri = "data:application/octet-stream;base64," + base64.b64encode(bytes(self.blob)).decode("ascii")
        doc["buffers"] = [{"byteLength": len(self.blob), "uri": uri}]
        return doc

    def write(self, path):
        write_json(path, self.to_json())


def to_text(doc, indent=""):
    """A glTF document as JSON: objects and arrays of objects one item per line, arrays of numbers on one line.

    json.dumps does the scalars (allow_nan=False keeps the file valid JSON); a final newline ends the file.
    """
    inner = indent + " "
    if isinstance(doc, dict) and doc:
        items = [inner + json.dumps(k) + ": " + to_text(v, inner) for k, v in doc.items()]
        text = "{\n" + ",\n".join(items) + "\n" + indent + "}"
    elif isinstance(doc, list) and any(isinstance(v, (dict, list)) for v in doc):
        text = "[\n" + ",\n".join(inner + to_text(v, inner) for v in doc) + "\n" + indent + "]"
    else:
        text = json.dumps(doc, allow_nan=False, separators=(", ", ": "))
    return text + "\n" if indent == "" else text


def write_text(path, text):
    with open(path, "w", encoding="ascii", newline="\n") as f:
        f.write(text)


def write_json(path, doc):
    write_text(path, to_text(doc))
