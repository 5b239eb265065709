#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the malformed-input table: one folder per case under OUT, and OUT/cases.json.

Each case is a valid base asset (a normal-mapped quad: POSITION, NORMAL, TEXCOORD_0, indices,
an external buffer and image) with one thing broken, as a hostile or careless producer would
break it: every JSON size/offset/count/stride out of range, dangling references, URIs that try
to leave the asset's folder, truncated GLB headers, OBJ/PLY/OFF with impossible counts or
indices. For each case the table gives the exit code each command must return and a phrase
its message must contain (besides the file's name). run_cases.py runs the table.

Usage: make_cases.py OUT
"""
import base64
import copy
import json
import os
import struct
import sys

# A 1x1 PNG (the image is carried through, never decoded by bake, check or info).
PNG = base64.b64decode(
    "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGP4//8/AAX+Av4N70a4AAAAAElFTkSuQmCC")


def base_geometry():
    positions = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]
    normals = [0, 0, 1] * 4
    uvs = [0, 1, 1, 1, 1, 0, 0, 0]
    indices = [0, 1, 2, 0, 2, 3]
    blob = struct.pack("<12f", *positions) + struct.pack("<12f", *normals) + struct.pack("<8f", *uvs)
    blob += struct.pack("<6H", *indices)
    blob += b"\0" * ((4 - len(blob) % 4) % 4)
    return blob


BIN = base_geometry()


def base_document(buffer_uri="base.bin"):
    doc = {
        "asset": {"version": "2.0", "generator": "libtangent tests/malformed"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "quad"}],
        "meshes": [{"name": "quad", "primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0, "mode": 4}]}],
        "materials": [{"name": "bumpy", "normalTexture": {"index": 0}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{}],
        "images": [{"uri": "tex.png", "mimeType": "image/png"}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48, "target": 34962},
            {"buffer": 0, "byteOffset": 48, "byteLength": 48, "target": 34962},
            {"buffer": 0, "byteOffset": 96, "byteLength": 32, "target": 34962},
            {"buffer": 0, "byteOffset": 128, "byteLength": 12, "target": 34963},
        ],
        "buffers": [{"uri": buffer_uri, "byteLength": len(BIN)}],
    }
    return doc


def glb(doc, bin_bytes=BIN):
    text = json.dumps(doc).encode()
    text += b" " * ((4 - len(text) % 4) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(bin_bytes), 0x004E4942) + bin_bytes
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


cases = []


def add(name, files, expect, input_name="in.gltf", bake=1, check=2, info=1, dirs=(), links=()):
    """files: name -> bytes; expect: phrase every command's message contains."""
    cases.append({"name": name, "files": files, "dirs": list(dirs), "links": list(links), "input": input_name,
                  "expect": expect, "exit": {"bake": bake, "check": check, "info": info}})


def gltf_case(name, mutate, expect, **kw):
    doc = base_document()
    mutate(doc)
    files = {"in.gltf": json.dumps(doc).encode(), "base.bin": BIN, "tex.png": PNG}
    files.update(kw.pop("extra", {}))
    add(name, files, expect, **kw)


def setter(path, value):
    """A mutation setting doc[path...] = value (DELETE removes the key)."""
    def mutate(doc):
        node = doc
        for key in path[:-1]:
            node = node[key]
        if value is DELETE:
            del node[path[-1]]
        else:
            node[path[-1]] = value
    return mutate


DELETE = object()

# --- the control: the base asset is valid, so every failure below comes from its one change.
# (check finds TANGENT missing: exit 1, a finding, where every case below is exit 2, unreadable)
add("control_valid", {"in.gltf": json.dumps(base_document()).encode(), "base.bin": BIN, "tex.png": PNG}, "",
    bake=0, check=1, info=0)
add("control_valid_glb", {"in.glb": glb({**base_document(), "buffers": [{"byteLength": len(BIN)}]}), "tex.png": PNG}, "",
    input_name="in.glb", bake=0, check=1, info=0)

# --- JSON itself
deep = "[" * 20000 + "]" * 20000
gltf_case("json_deep_extras", setter(["asset", "extras"], "DEEP"), "nests deeper than 256",
          )
cases[-1]["files"]["in.gltf"] = cases[-1]["files"]["in.gltf"].replace(b'"DEEP"', deep.encode())
add("json_not_json", {"in.gltf": b"{\"asset\": {\"version\": \"2.0\"", "base.bin": BIN}, "not valid glTF JSON")
add("json_array_root", {"in.gltf": b"[1, 2, 3]"}, "must be an object")
add("json_empty_file", {"in.gltf": b""}, "is empty (0 bytes)")
gltf_case("asset_missing", setter(["asset"], DELETE), "/asset")
gltf_case("asset_version_1", setter(["asset", "version"], "1.0"), "/asset/version")
gltf_case("accessors_not_array", setter(["accessors"], {"0": {}}), "/accessors: must be an array")
gltf_case("accessor_not_object", setter(["accessors", 1], 7), "/accessors/1: must be an object")

# --- buffers
gltf_case("buffer_bytelength_missing", setter(["buffers", 0, "byteLength"], DELETE), "/buffers/0/byteLength: is required")
gltf_case("buffer_bytelength_zero", setter(["buffers", 0, "byteLength"], 0), "/buffers/0/byteLength")
gltf_case("buffer_bytelength_negative", setter(["buffers", 0, "byteLength"], -140), "/buffers/0/byteLength")
gltf_case("buffer_bytelength_huge", setter(["buffers", 0, "byteLength"], 2 ** 50), "/buffers/0/byteLength")
gltf_case("buffer_bytelength_float", setter(["buffers", 0, "byteLength"], 140.5), "must be an integer")
gltf_case("buffer_file_shorter", setter(["buffers", 0, "byteLength"], len(BIN) + 4000), "buffer")

# --- bufferViews: every field
for field, value, phrase in [
        ("byteOffset", -16, "/bufferViews/0/byteOffset"),
        ("byteOffset", 2 ** 62, "/bufferViews/0/byteOffset"),
        ("byteOffset", "0", "/bufferViews/0/byteOffset: must be an integer"),
        ("byteLength", 0, "/bufferViews/0/byteLength"),
        ("byteLength", 4000, "/bufferViews/0: byteOffset 0 + byteLength 4000 overruns buffer 0"),
        ("byteLength", DELETE, "/bufferViews/0/byteLength: is required"),
        ("byteStride", 2, "/bufferViews/0/byteStride"),
        ("byteStride", 6, "is not a multiple of 4"),
        ("byteStride", 256, "/bufferViews/0/byteStride"),
        ("buffer", 5, "/bufferViews/0/buffer: refers to buffers 5"),
        ("buffer", -1, "/bufferViews/0/buffer: refers to buffers -1"),
        ("buffer", DELETE, "/bufferViews/0/buffer: is required")]:
    tag = "missing" if value is DELETE else str(value).replace("-", "minus")
    gltf_case(f"bufferview_{field}_{tag}", setter(["bufferViews", 0, field], value), phrase)

# --- accessors: every field of POSITION's accessor
for field, value, phrase in [
        ("count", 0, "/accessors/0/count"),
        ("count", -1, "/accessors/0/count"),
        ("count", 2 ** 31, "/accessors/0: its elements need bytes"),
        ("count", 2 ** 40, "/accessors/0/count"),
        ("count", 5, "/accessors/0: its elements need bytes 0 to 60"),
        ("count", DELETE, "/accessors/0/count: is required"),
        ("componentType", 5124, "/accessors/0/componentType"),
        ("componentType", 9999, "/accessors/0/componentType"),
        ("componentType", DELETE, "/accessors/0/componentType: is required"),
        ("type", "VEC5", "/accessors/0/type"),
        ("type", 3, "/accessors/0/type: must be a string"),
        ("type", DELETE, "/accessors/0/type: is required"),
        ("bufferView", 99, "/accessors/0/bufferView: refers to bufferViews 99"),
        ("bufferView", -2, "/accessors/0/bufferView"),
        ("byteOffset", -4, "/accessors/0/byteOffset"),
        ("byteOffset", 2, "is not a multiple of the component size"),
        ("byteOffset", 48, "/accessors/0: its elements need bytes 48 to 96")]:
    tag = "missing" if value is DELETE else str(value).replace("-", "minus")
    gltf_case(f"accessor_{field}_{tag}", setter(["accessors", 0, field], value), phrase)


def sparse(count=1, index_view=3, index_type=5123, index_offset=0, value_view=2, value_offset=0):
    return setter(["accessors", 2, "sparse"], {
        "count": count, "indices": {"bufferView": index_view, "componentType": index_type, "byteOffset": index_offset},
        "values": {"bufferView": value_view, "byteOffset": value_offset}})


gltf_case("sparse_count_huge", sparse(count=2 ** 31), "/accessors/2/sparse/count")
gltf_case("sparse_count_zero", sparse(count=0), "/accessors/2/sparse/count")
gltf_case("sparse_indices_view_missing", sparse(index_view=40), "/accessors/2/sparse/indices/bufferView")
gltf_case("sparse_indices_float", sparse(index_type=5126), "/accessors/2/sparse/indices/componentType")
gltf_case("sparse_values_offset_past", sparse(value_offset=32), "/accessors/2/sparse/values: the sparse values need bytes")
# Sparse indices read from the UV view as UNSIGNED_INT: float bits, far beyond count 4.
doc = base_document()
doc["accessors"][2]["sparse"] = {"count": 1, "indices": {"bufferView": 2, "componentType": 5125, "byteOffset": 8},
                                 "values": {"bufferView": 2}}
add("sparse_index_target_out_of_range", {"in.gltf": json.dumps(doc).encode(), "base.bin": BIN, "tex.png": PNG},
    "is out of range (count 4)")

# Strictly increasing sparse indices (glTF 2.0 3.6.2.3): the index view read from byte 4 is 2, 0.
gltf_case("sparse_indices_not_increasing", sparse(count=2, index_offset=4), "/accessors/2/sparse/indices")
cases[-1]["expect2"] = "must strictly increase"


# Accessors without a bufferView are zeros the file does not store: three of 2 GiB each in a
# file of 2 KB, refused at load (the budget for values a file implies without storing them, in
# proportion to the bytes it stores), before any allocation.
def unstored(with_sparse):
    def mutate(doc):
        for a in doc["accessors"][:3]:
            del a["bufferView"]
            a["count"] = 2 ** 31 // 12
            if with_sparse:
                a["sparse"] = {"count": 1, "indices": {"bufferView": 3, "componentType": 5123},
                               "values": {"bufferView": 0 if a["type"] == "VEC3" else 2}}
    return mutate


for tag, with_sparse in (("", False), ("_sparse", True)):
    gltf_case("accessors_unstored_huge" + tag, unstored(with_sparse), "/accessors/0: has no bufferView")
    cases[-1]["expect2"] = "may imply at most"

# --- meshes and primitives
gltf_case("primitives_empty", setter(["meshes", 0, "primitives"], []), "/meshes/0/primitives")
gltf_case("primitives_not_array", setter(["meshes", 0, "primitives"], {}), "/meshes/0/primitives")
gltf_case("attributes_missing", setter(["meshes", 0, "primitives", 0, "attributes"], DELETE), "/attributes: is required")
gltf_case("attribute_string", setter(["meshes", 0, "primitives", 0, "attributes", "POSITION"], "0"), "/attributes/POSITION")
gltf_case("attribute_negative", setter(["meshes", 0, "primitives", 0, "attributes", "POSITION"], -1), "/attributes/POSITION")
gltf_case("attribute_dangling", setter(["meshes", 0, "primitives", 0, "attributes", "NORMAL"], 99), "/attributes/NORMAL")
gltf_case("indices_dangling", setter(["meshes", 0, "primitives", 0, "indices"], 99), "/indices: refers to accessors 99")
gltf_case("material_dangling", setter(["meshes", 0, "primitives", 0, "material"], 7), "/material: refers to materials 7")
gltf_case("mode_9", setter(["meshes", 0, "primitives", 0, "mode"], 9), "/mode")
gltf_case("mode_negative", setter(["meshes", 0, "primitives", 0, "mode"], -1), "/mode")
gltf_case("targets_not_array", setter(["meshes", 0, "primitives", 0, "targets"], {"POSITION": 0}), "/targets")
gltf_case("target_dangling", setter(["meshes", 0, "primitives", 0, "targets"], [{"POSITION": 12}]), "/targets/0/POSITION")
gltf_case("index_count_not_triangles", setter(["accessors", 3, "count"], 5), "is not a multiple of 3")
gltf_case("attribute_count_mismatch", setter(["accessors", 1, "count"], 3), "POSITION has 4")
# What bake refuses, info refuses too (it used to describe these and exit 0).
gltf_case("normal_type_vec2", setter(["accessors", 1, "type"], "VEC2"), "NORMAL (accessor 1): must be VEC3, found VEC2")
gltf_case("position_type_vec2", setter(["accessors", 0, "type"], "VEC2"), "POSITION (accessor 0): must be VEC3, found VEC2")
gltf_case("position_missing", setter(["meshes", 0, "primitives", 0, "attributes", "POSITION"], DELETE),
          "primitive 0: has no POSITION attribute")


files = {"in.gltf": json.dumps(base_document()).encode(), "tex.png": PNG,
         "base.bin": BIN[:128] + struct.pack("<6H", 0, 1, 2, 0, 2, 40) + BIN[140:]}
add("index_value_out_of_range", files, "index 40 at position 5 is out of range")


# --- compressed data (KHR_draco_mesh_compression, EXT_meshopt_compression): streams that are
# no streams. tests/compressed covers real encoder output, cut and miscounted.
def meshopt_view(extension):
    def mutate(doc):
        doc["extensionsUsed"] = doc["extensionsRequired"] = ["EXT_meshopt_compression"]
        doc["bufferViews"][0]["extensions"] = {"EXT_meshopt_compression": extension}
    return mutate


def draco_primitive(doc):
    doc["extensionsUsed"] = doc["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    doc["meshes"][0]["primitives"][0]["extensions"] = {
        "KHR_draco_mesh_compression": {"bufferView": 1, "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}}}


# The 12 index bytes read as an attribute stream: no room for its 32-byte tail.
gltf_case("meshopt_stream_truncated", meshopt_view({"buffer": 0, "byteOffset": 128, "byteLength": 12, "byteStride": 12,
                                                    "count": 4, "mode": "ATTRIBUTES"}),
          "bufferViews[0] EXT_meshopt_compression: the compressed stream is malformed or truncated")
gltf_case("meshopt_count_huge", meshopt_view({"buffer": 0, "byteLength": 48, "byteStride": 12, "count": 2 ** 28,
                                              "mode": "ATTRIBUTES"}),
          "bufferViews[0] EXT_meshopt_compression: count 268435456 x byteStride 12 is over the limit of 2 GiB")
# Normals read as a Draco stream.
gltf_case("draco_stream_garbage", draco_primitive,
          "meshes[0].primitives[0] KHR_draco_mesh_compression: the Draco stream in bufferView 1 cannot be decoded")

# --- materials, textures, images
gltf_case("normaltexture_dangling", setter(["materials", 0, "normalTexture", "index"], 9), "/normalTexture/index: refers to textures 9")
gltf_case("normaltexture_no_index", setter(["materials", 0, "normalTexture"], {"scale": 1}), "/normalTexture/index: is required")
gltf_case("texcoord_negative", setter(["materials", 0, "normalTexture", "texCoord"], -1), "/normalTexture/texCoord")
gltf_case("texcoord_missing_uv_set", setter(["materials", 0, "normalTexture", "texCoord"], 1),
          "has no TEXCOORD_1 attribute", check=1)
gltf_case("texture_source_dangling", setter(["textures", 0, "source"], 9), "/textures/0/source: refers to images 9")
gltf_case("texture_sampler_dangling", setter(["textures", 0, "sampler"], 9), "/textures/0/sampler")
gltf_case("image_bufferview_dangling", setter(["images", 0], {"bufferView": 99, "mimeType": "image/png"}), "/images/0/bufferView")

# --- nodes, scenes, skins, animations
gltf_case("node_mesh_dangling", setter(["nodes", 0, "mesh"], 9), "/nodes/0/mesh")
gltf_case("node_child_dangling", setter(["nodes", 0, "children"], [99]), "/nodes/0/children/0")
gltf_case("node_cycle", setter(["nodes"], [{"mesh": 0, "children": [1]}, {"children": [0]}]), "the node hierarchy has a cycle")
gltf_case("node_self_child", setter(["nodes"], [{"mesh": 0, "children": [0]}]), "node")
gltf_case("node_two_parents", setter(["nodes"], [{"children": [2]}, {"children": [2]}, {"mesh": 0}]), "has two parents")
gltf_case("scene_dangling", setter(["scene"], 5), "/scene: refers to scenes 5")
gltf_case("scene_nodes_dangling", setter(["scenes", 0, "nodes"], [99]), "/scenes/0/nodes/0")
gltf_case("skin_joint_dangling", setter(["skins"], [{"joints": [99]}]), "/skins/0/joints/0")
gltf_case("animation_input_dangling", setter(["animations"], [{"samplers": [{"input": 99, "output": 0}], "channels": []}]),
          "/animations/0/samplers/0/input")
gltf_case("animation_channel_sampler", setter(["animations"], [{"samplers": [{"input": 0, "output": 0}],
                                                                  "channels": [{"sampler": 5, "target": {"node": 0}}]}]),
          "/animations/0/channels/0/sampler")

# --- animations and morph targets (glTF 2.0 3.7.2.2 and 3.11): the base quad with a morph
# target, its mesh and node weights, and one animation over every path, interpolation and
# output format the spec allows; each case below breaks one rule of it.
ANIM_BIN = (struct.pack("<2f", 0, 1)                                                  # times
            + struct.pack("<18f", 0, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 2, 2, 2, 0, 0, 0)  # VEC3 x 6
            + struct.pack("<8f", 0, 0, 0, 1, 0, 0, 0.7071, 0.7071)                    # VEC4 float x 2
            + struct.pack("<8h", 0, 0, 0, 32767, 0, 0, 23170, 23170)                  # VEC4 short x 2
            + struct.pack("<6f", 0, 1, 0, 0, 0, 0))                                   # SCALAR x 6


def animated_document():
    doc = base_document()
    doc["buffers"].append({"uri": "anim.bin", "byteLength": len(ANIM_BIN)})
    doc["bufferViews"] += [{"buffer": 1, "byteOffset": offset, "byteLength": length}
                           for offset, length in ((0, 8), (8, 72), (80, 32), (112, 16), (128, 24))]
    doc["accessors"] += [
        {"bufferView": 4, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},  # 4 times
        {"bufferView": 5, "componentType": 5126, "count": 2, "type": "VEC3"},                            # 5 translation
        {"bufferView": 6, "componentType": 5126, "count": 2, "type": "VEC4"},                            # 6 rotation
        {"bufferView": 7, "componentType": 5122, "normalized": True, "count": 2, "type": "VEC4"},        # 7 rotation
        {"bufferView": 5, "componentType": 5126, "count": 6, "type": "VEC3"},                            # 8 cubic scale
        {"bufferView": 8, "componentType": 5126, "count": 2, "type": "SCALAR"},                          # 9 weights
    ]
    doc["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": 1}]
    doc["meshes"][0]["weights"] = [0.0]
    doc["nodes"][0]["weights"] = [0.5]
    doc["nodes"].append({"name": "pivot"})
    doc["scenes"][0]["nodes"] = [0, 1]
    doc["animations"] = [{"name": "every path", "samplers": [
        {"input": 4, "output": 5},
        {"input": 4, "output": 6, "interpolation": "STEP"},
        {"input": 4, "output": 8, "interpolation": "CUBICSPLINE"},
        {"input": 4, "output": 9, "interpolation": "LINEAR"},
        {"input": 4, "output": 7}], "channels": [
        {"sampler": 0, "target": {"node": 0, "path": "translation"}},
        {"sampler": 1, "target": {"node": 0, "path": "rotation"}},
        {"sampler": 2, "target": {"node": 0, "path": "scale"}},
        {"sampler": 3, "target": {"node": 0, "path": "weights"}},
        {"sampler": 4, "target": {"node": 1, "path": "rotation"}}]}]
    return doc


def anim_case(name, mutate, expect, **kw):
    doc = animated_document()
    mutate(doc)
    add(name, {"in.gltf": json.dumps(doc).encode(), "base.bin": BIN, "anim.bin": ANIM_BIN, "tex.png": PNG}, expect, **kw)


def animation_pointer(doc):
    doc["extensionsUsed"] = ["KHR_animation_pointer"]
    doc["animations"][0]["channels"][4]["target"] = {
        "path": "pointer", "extensions": {"KHR_animation_pointer": {"pointer": "/nodes/1/rotation"}}}


def input_unsigned_byte(doc):
    doc["accessors"].append({"bufferView": 4, "componentType": 5121, "count": 2, "type": "SCALAR", "min": [0], "max": [1]})
    doc["animations"][0]["samplers"][0]["input"] = 10


def second_primitive_without_targets(doc):
    primitive = dict(doc["meshes"][0]["primitives"][0])
    del primitive["targets"]
    doc["meshes"][0]["primitives"].append(primitive)


# Valid: they pass as the base quad does (check finds TANGENT missing).
anim_case("animation_valid", lambda doc: None, "", bake=0, check=1, info=0)
anim_case("animation_pointer_valid", animation_pointer, "", bake=0, check=1, info=0)
CHANNEL, SAMPLER = ["animations", 0, "channels"], ["animations", 0, "samplers"]
for name, mutate, phrase in [
        ("animation_path_unknown", setter(CHANNEL + [1, "target", "path"], "scale_xyz"),
         '/animations/0/channels/1/target/path: "scale_xyz" is not one of translation, rotation, scale, weights'),
        ("animation_path_missing", setter(CHANNEL + [0, "target", "path"], DELETE), "/animations/0/channels/0/target/path: is required"),
        ("animation_path_pointer_unused", setter(CHANNEL + [4, "target", "path"], "pointer"),
         '/animations/0/channels/4/target/path: "pointer" is not one of'),
        ("animation_target_missing", setter(CHANNEL + [0, "target"], DELETE), "/animations/0/channels/0/target: is required"),
        ("animation_target_node_dangling", setter(CHANNEL + [0, "target", "node"], 9),
         "/animations/0/channels/0/target/node: refers to nodes 9"),
        ("animation_target_twice", setter(CHANNEL + [4, "target", "node"], 0),
         "/animations/0/channels/4/target: animates the same node and path as /animations/0/channels/1"),
        ("animation_interpolation_unknown", setter(SAMPLER + [1, "interpolation"], "QUADRATIC"),
         '/animations/0/samplers/1/interpolation: "QUADRATIC" is not one of LINEAR, STEP, CUBICSPLINE'),
        ("animation_input_unsigned_byte", input_unsigned_byte,
         "/animations/0/samplers/0/input: accessor 10 is SCALAR UNSIGNED_BYTE; an animation sampler's input (keyframe times) "
         "must be SCALAR FLOAT"),
        ("animation_input_no_min_max", setter(["accessors", 4, "min"], DELETE),
         "/animations/0/samplers/0/input: accessor 4 has no min and max"),
        ("animation_output_translation_vec4", setter(SAMPLER + [0, "output"], 6),
         "/animations/0/samplers/0/output: accessor 6 is VEC4 FLOAT; a translation channel (/animations/0/channels/0) needs VEC3 FLOAT"),
        ("animation_output_rotation_short", setter(["accessors", 7, "normalized"], DELETE),
         "/animations/0/samplers/4/output: accessor 7 is VEC4 SHORT; a rotation channel (/animations/0/channels/4) needs VEC4 FLOAT or normalized"),
        ("animation_output_rotation_mat2", setter(["accessors", 6, "type"], "MAT2"),
         "/animations/0/samplers/1/output: accessor 6 is MAT2 FLOAT; a rotation channel (/animations/0/channels/1) needs VEC4"),
        ("animation_output_weights_vec3", setter(SAMPLER + [3, "output"], 5),
         "/animations/0/samplers/3/output: accessor 5 is VEC3 FLOAT; a weights channel (/animations/0/channels/3) needs SCALAR"),
        ("animation_output_count", setter(["accessors", 5, "count"], 3),
         "/animations/0/samplers/0/output: accessor 5 has 3 elements; a translation channel (/animations/0/channels/0) with 2 keyframes needs 2"),
        ("animation_output_count_cubicspline", setter(SAMPLER + [2, "output"], 5),
         "accessor 5 has 2 elements; a scale channel (/animations/0/channels/2) with 2 keyframes (CUBICSPLINE: 3 each) needs 6"),
        ("animation_output_count_weights", setter(["accessors", 9, "count"], 4),
         "accessor 9 has 4 elements; a weights channel (/animations/0/channels/3) with 2 keyframes of 1 morph target(s) needs 2"),
        ("animation_weights_node_without_mesh", setter(CHANNEL + [3, "target", "node"], 1),
         "/animations/0/channels/3/target: animates the weights of node 1, which has no mesh"),
        ("morph_target_counts_differ", second_primitive_without_targets,
         "/meshes/0/primitives/1/targets: has 0 morph target(s); primitive 0 of the mesh has 1"),
        ("morph_mesh_weights_longer", setter(["meshes", 0, "weights"], [0.0, 0.0]),
         "/meshes/0/weights: has 2 weight(s); mesh 0 has 1 morph target(s)"),
        ("morph_node_weights_longer", setter(["nodes", 0, "weights"], [0.5, 0.5, 0.5]),
         "/nodes/0/weights: has 3 weight(s); mesh 0 has 1 morph target(s)"),
        ("morph_node_weights_without_mesh", setter(["nodes", 1, "weights"], [1.0]), "/nodes/1/weights: needs a mesh"),
        ("morph_weight_not_number", setter(["meshes", 0, "weights"], ["0"]), "/meshes/0/weights/0: must be a number")]:
    anim_case(name, mutate, phrase)
# A sample model with morph targets and a weights animation, where the system has it.
MORPH_CUBE = "/usr/share/assimp/models/glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube"
if os.path.exists(MORPH_CUBE + ".gltf") and os.path.exists(MORPH_CUBE + ".bin"):
    with open(MORPH_CUBE + ".gltf", "rb") as f, open(MORPH_CUBE + ".bin", "rb") as g:
        add("animation_sample_morph_cube", {"in.gltf": f.read(), "AnimatedMorphCube.bin": g.read()}, "",
            bake=0, check=0, info=0)

# KHR_texture_transform: members of the wrong type are named by their JSON path (they were
# "type must be number, but is array" from bake and check, and passed info).
TRANSFORM = ["materials", 0, "normalTexture", "extensions", "KHR_texture_transform"]
gltf_case("texture_transform_valid", setter(TRANSFORM[:-1], {"KHR_texture_transform": {"offset": [0.5, 0], "rotation": 0.25,
                                                                                       "scale": [2, 2], "texCoord": 0}}),
          "", bake=0, check=1, info=0)
for name, member, value, phrase in [
        ("texture_transform_offset_nested", "offset", [[1], [2]], "offset: must be an array of 2 numbers"),
        ("texture_transform_scale_three", "scale", [1, 2, 3], "scale: must be an array of 2 numbers"),
        ("texture_transform_rotation_array", "rotation", [1], "rotation: must be a number")]:
    gltf_case(name, setter(TRANSFORM[:-1], {"KHR_texture_transform": {member: value}}),
              "/materials/0/normalTexture/extensions/KHR_texture_transform/" + phrase)

# --- URIs: everything that is not data: or a relative path inside the asset's folder
for tag, uri, phrase in [
        ("parent_escape", "../../../../../../etc/passwd", "leaves the asset root"),
        ("absolute", "/etc/passwd", "is an absolute path"),
        ("file_scheme", "file:///etc/passwd", "has a scheme"),
        ("http_scheme", "http://example.com/base.bin", "has a scheme"),
        ("percent_escape", "%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/etc/passwd", "leaves the asset root"),
        ("nul_byte", "base.bin%00.png", "NUL"),
        ("missing_file", "nowhere.bin", "does not exist"),
        ("directory", "sub", "names a directory"),
        ("empty", "", "is empty"),
        ("symlink_escape", "link.bin", "leaves the asset root"),
        ("symlink_device", "zero.bin", "leaves the asset root")]:
    doc = base_document(uri)
    add(f"buffer_uri_{tag}", {"in.gltf": json.dumps(doc).encode(), "base.bin": BIN, "tex.png": PNG},
        "/buffers/0 uri", dirs=["sub"] if tag == "directory" else [],
        links=[["link.bin", "/etc/hostname"], ["zero.bin", "/dev/zero"]] if tag.startswith("symlink") else [])
    cases[-1]["expect2"] = phrase
for tag, uri, phrase in [
        ("parent_escape", "../../../../../../etc/passwd", "leaves the asset root"),
        ("absolute", "/etc/passwd", "is an absolute path"),
        ("file_scheme", "file:///etc/passwd", "has a scheme")]:
    gltf_case(f"image_uri_{tag}", setter(["images", 0, "uri"], uri), "/images/0 uri")
    cases[-1]["expect2"] = phrase

# data: URIs that are not base64 (tinygltf said "File not found" and echoed the whole URI):
# the message names the buffer, says what is wrong and quotes none of the payload.
for tag, uri, phrase in [
        ("bad_character", "data:application/octet-stream;base64," + "@" * 200000, "has a character that is not base64"),
        ("not_base64", "data:application/octet-stream," + "x" * 200000, "data: URI is not base64")]:
    add(f"buffer_data_uri_{tag}", {"in.gltf": json.dumps(base_document(uri)).encode(), "tex.png": PNG}, "/buffers/0 uri")
    cases[-1]["expect2"] = phrase

# --- GLB container: truncated at every header field, lengths that lie
valid_glb = glb({**base_document(), "buffers": [{"byteLength": len(BIN)}]})
for cut in (0, 4, 8, 12, 16, 19):
    add(f"glb_truncated_{cut}", {"in.glb": valid_glb[:cut]}, "GLB is truncated" if cut >= 4 else "is empty (0 bytes)",
        input_name="in.glb")
add("glb_not_glb", {"in.glb": json.dumps(base_document()).encode()}, "not a GLB file", input_name="in.glb")
add("glb_truncated_in_json", {"in.glb": valid_glb[:40]}, "GLB header says", input_name="in.glb")
add("glb_truncated_in_bin", {"in.glb": valid_glb[:-20]}, "GLB header says", input_name="in.glb")


def patched(offset, value):
    data = bytearray(valid_glb)
    data[offset:offset + 4] = struct.pack("<I", value)
    return bytes(data)


add("glb_version_1", {"in.glb": patched(4, 1)}, "GLB version 1 is not 2", input_name="in.glb")
add("glb_length_too_large", {"in.glb": patched(8, len(valid_glb) + 100)}, "GLB header says", input_name="in.glb")
add("glb_json_chunk_overruns", {"in.glb": patched(12, 0x7FFFFFF0)}, "not a valid JSON chunk", input_name="in.glb")
add("glb_first_chunk_not_json", {"in.glb": patched(16, 0x004E4942)}, "not a valid JSON chunk", input_name="in.glb")
json_length = struct.unpack_from("<I", valid_glb, 12)[0]
add("glb_bin_chunk_overruns", {"in.glb": patched(20 + json_length, 0x7FFFFFF0)}, "BIN chunk overruns", input_name="in.glb")
add("glb_bin_shorter_than_buffer", {"in.glb": glb({**base_document(), "buffers": [{"byteLength": len(BIN) + 64}]})},
    "buffer", input_name="in.glb")

# --- OBJ, PLY, OFF
tri_obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
add("obj_face_index_out_of_range", {"in.obj": tri_obj + b"f 1/1/1 2/2/1 99/3/1\n"}, "vertex 99", input_name="in.obj")
add("obj_negative_index_before_start", {"in.obj": tri_obj + b"f -1/1/1 -2/2/1 -9/3/1\n"}, "", input_name="in.obj")
add("obj_no_uvs", {"in.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"}, "has no texture coordinates", input_name="in.obj")
add("off_huge_face_count", {"in.off": b"OFF\n3 999999999 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
    "OFF header declares 3 vertices and 999999999 faces", input_name="in.off")
add("off_huge_vertex_count", {"in.off": b"OFF\n999999999 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
    "OFF header declares 999999999 vertices", input_name="in.off")
add("off_bad_keyword", {"in.off": b"OFX\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"}, "OFF line 1", input_name="in.off")
add("off_counts_not_numbers", {"in.off": b"OFF\nthree 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"}, "OFF line 2",
    input_name="in.off")
add("off_face_index_out_of_range", {"in.off": b"STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 7\n"},
    "face 1 corner 3 '7' is not a vertex index below 3", input_name="in.off")
add("off_face_corner_count_huge", {"in.off": b"STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n37777777777 0 1 2\n"},
    "face 1 declares", input_name="in.off")
# OpenMesh read OFF numbers as one stream across lines: a short vertex line shifted every later
# number, and a face count that overflowed became 4 billion corners (fuzz_mesh_file).
add("off_short_vertex_line", {"in.off": b"STOFF\n3 1 0\n0\n0 11 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n"},
    "OFF line 3: vertex 1 lists 1 value(s); STOFF needs 5 (x y z s t)", input_name="in.off")
add("off_number_with_garbage", {"in.off": b"STOFF\n3 1 0\n0 0 0 0 0\n1 0 -0=== 1 0\n0 1 0 0 1\n3 0 1 2\n"},
    "OFF line 4: vertex 2 value '-0===' is not a finite number", input_name="in.off")
add("off_infinite_coordinate", {"in.off": b"STOFF\n3 1 0\n0 0 0 0 0\n1e39 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n"},
    "vertex 2 value '1e39' is not a finite number", input_name="in.off")
add("off_face_count_overflows", {"in.off": b"STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n" + b"6" * 60 + b"\n"},
    "face 1 declares '66666666666666666666' corners", input_name="in.off")
add("off_st_extra_values", {"in.off": b"STOFF\n3 1 0\n0 0 0 0 0 9 9\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n"},
    "OFF line 3: vertex 1 lists 7 values; STOFF has no colours, so exactly 5 (x y z s t)", input_name="in.off")
add("off_homogeneous", {"in.off": b"4OFF\n3 1 0\n0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n"}, "4OFF (homogeneous coordinates) is not read",
    input_name="in.off")
add("off_binary_face_corners_huge",
    {"in.off": b"STOFF BINARY\n" + struct.pack("<3I", 3, 1, 0) + struct.pack("<15f", 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1)
     + struct.pack("<I", 4000000000)}, "binary OFF face 1 declares 4000000000 corners", input_name="in.off")
add("off_binary_truncated",
    {"in.off": b"OFF BINARY\n" + struct.pack("<3I", 3, 0, 0) + struct.pack("<6f", 0, 0, 0, 1, 0, 0)},
    "binary OFF ends inside a vertex", input_name="in.off")
add("off_truncated_faces", {"in.off": b"OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"}, "the file ends after 1 of 2 faces",
    input_name="in.off")
ply_header = (b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              b"property float s\nproperty float t\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n")
ply_body = b"0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n"
add("ply_huge_face_count", {"in.ply": (ply_header % 2000000000) + ply_body + b"3 0 1 2\n"},
    "PLY header declares 2000000000 face elements", input_name="in.ply")
add("ply_element_without_count", {"in.ply": ply_header.replace(b"element vertex 3", b"element ver") % 1 + ply_body},
    "PLY header line 3: expected 'element NAME COUNT'", input_name="in.ply")
add("ply_free_text_line", {"in.ply": ply_header.replace(b"element vertex 3", b"eleme5\tproperty list uchar int x\nelement vertex 3") % 1 + ply_body},
    "PLY header line 3: unknown keyword", input_name="in.ply")
add("ply_no_end_header", {"in.ply": b"ply\nformat ascii 1.0\nelement vertex 3\n"}, "no end_header", input_name="in.ply")
add("ply_bad_property", {"in.ply": ply_header.replace(b"property float x", b"property quaternion x") % 1 + ply_body},
    "PLY header line 4", input_name="in.ply")
# OpenMesh allocated a face list's declared length before reading it (2 billion corners: GBs).
add("ply_list_count_huge_ascii", {"in.ply": (ply_header % 1) + ply_body + b"200 0 1 2\n"},
    "PLY face 1 (1-based) property vertex_indices: a list of 200 items, more than the rest of the file holds", input_name="in.ply")
add("ply_list_count_huge_binary",
    {"in.ply": b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               b"property float s\nproperty float t\nelement face 1\nproperty list uint int vertex_indices\nend_header\n"
               + struct.pack(">15f", 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1) + struct.pack(">4I", 2000000000, 0, 1, 2)},
    "a list of 2000000000 items, more than the rest of the file holds", input_name="in.ply")
add("ply_negative_index",
    {"in.ply": b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               b"property float s\nproperty float t\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
               + struct.pack("<15f", 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1) + struct.pack("<B3i", 3, 0, 1, -1)},
    "PLY face 1 (1-based) property vertex_indices: corner 3 is vertex -1, not a vertex index", input_name="in.ply")
add("ply_negative_list_count",
    {"in.ply": b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               b"property float s\nproperty float t\nelement face 1\nproperty list char int vertex_indices\nend_header\n"
               + struct.pack("<15f", 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1) + struct.pack("<b3i", -1, 0, 1, 2)},
    "property vertex_indices: a list count of -1 (negative)", input_name="in.ply")
add("ply_value_not_a_number", {"in.ply": (ply_header % 1) + ply_body.replace(b"1 0 0 1 0", b"1 0 x 1 0") + b"3 0 1 2\n"},
    "PLY vertex 2 (1-based) property z: 'x' is not a number", input_name="in.ply")
add("ply_body_truncated", {"in.ply": (ply_header % 2) + ply_body + b"3 0 1 2\n3 0 1"},
    "PLY face 2 (1-based) property vertex_indices: the file ends here", input_name="in.ply")
add("ply_face_of_two_corners", {"in.ply": (ply_header % 1) + ply_body + b"2 0 1\n"},
    "a face of 2 corners (a face needs at least 3)", input_name="in.ply")
add("ply_corner_uvs_miscounted",
    {"in.ply": (ply_header % 1).replace(b"vertex_indices\n", b"vertex_indices\nproperty list uchar float texcoord\n")
               + ply_body + b"3 0 1 2 4 0 0 1 0\n"},
    "property texcoord: lists 4 values for a face of 3 corners", input_name="in.ply")
add("ply_face_index_out_of_range", {"in.ply": (ply_header % 1) + ply_body + b"3 0 1 5\n"}, "refers to vertex 6",
    input_name="in.ply")

# --- the input itself
add("input_is_directory", {}, "is a directory", dirs=["in.gltf"])
add("input_missing", {}, "no such file")

if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    table = []
    for case in cases:
        folder = os.path.join(out, case["name"])
        os.makedirs(folder, exist_ok=True)
        for name, data in case["files"].items():
            with open(os.path.join(folder, name), "wb") as f:
                f.write(data)
        for name in case["dirs"]:
            os.makedirs(os.path.join(folder, name), exist_ok=True)
        for name, target in case["links"]:
            link = os.path.join(folder, name)
            if os.path.lexists(link):
                os.remove(link)
            os.symlink(target, link)
        entry = {k: v for k, v in case.items() if k not in ("files", "dirs", "links")}
        table.append(entry)
    with open(os.path.join(out, "cases.json"), "w") as f:
        json.dump(table, f, indent=1)
    print(f"{len(table)} cases written to {out}")
