#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the committed seed corpus of the fuzz targets (tests/fuzz/corpus): small valid
inputs of every shape the targets read, from the base asset of tests/malformed. Rerun after
changing it; fuzzing adds its finds to a copy, never here (crashes go to regressions/).

Not written here: corpus/gltf/quad_draco.glb and quad_meshopt.glb, the quad.glb seed (with
its image) through `gltf-transform draco` and `gltf-transform meshopt` (tests/node, pinned):
real KHR_draco_mesh_compression and EXT_meshopt_compression streams for the fuzzer to cut."""
import base64
import copy
import json
import os
import struct
import random
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "malformed"))
import make_cases as m  # noqa: E402


def write(folder, name, data):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data)


gltf = os.path.join(here, "corpus", "gltf")
embedded = "data:application/octet-stream;base64," + base64.b64encode(m.BIN).decode()
doc = m.base_document(embedded)
write(gltf, "quad_embedded.gltf", json.dumps(doc).encode())
write(gltf, "quad_external.gltf", json.dumps(m.base_document("base.bin")).encode())
write(gltf, "quad.glb", m.glb({**m.base_document(), "buffers": [{"byteLength": len(m.BIN)}]}))
variant = copy.deepcopy(doc)
variant["meshes"][0]["primitives"][0]["mode"] = 5
variant["accessors"][3]["count"] = 4
write(gltf, "quad_strip.gltf", json.dumps(variant).encode())
variant = copy.deepcopy(doc)
variant["accessors"][2]["sparse"] = {"count": 1, "indices": {"bufferView": 3, "componentType": 5123},
                                     "values": {"bufferView": 2}}
variant["materials"][0]["normalTexture"]["extensions"] = {"KHR_texture_transform": {"rotation": 0.5, "scale": [2, 1]}}
write(gltf, "quad_sparse_transform.gltf", json.dumps(variant).encode())
variant = copy.deepcopy(doc)
variant["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": 1, "NORMAL": 1}]
variant["nodes"] = [{"children": [1], "scale": [-1, 1, 1]}, {"mesh": 0}]
variant["scenes"] = [{"nodes": [0]}]
write(gltf, "quad_morph_nodes.gltf", json.dumps(variant).encode())

mesh = os.path.join(here, "corpus", "mesh_file")
write(mesh, "tri.obj", b"\0" + b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n")
write(mesh, "quad.obj", b"\0" + b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n")
write(mesh, "tri.ply", b"\1" + (m.__dict__.get("ply_header") % 1) + m.__dict__.get("ply_body") + b"3 0 1 2\n")
write(mesh, "tri.off", b"\2" + b"STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n")
write(mesh, "wedge.ply", b"\1" + b"ply\nformat ascii 1.0\ncomment corner UVs\nelement vertex 3\nproperty float x\nproperty float y\n"
      b"property float z\nproperty float nx\nproperty float ny\nproperty float nz\nelement face 1\n"
      b"property list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n"
      b"0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2 6 0 0 1 0 0 1\n")
for order, fmt in (("<", b"binary_little_endian"), (">", b"binary_big_endian")):
    write(mesh, f"tri_{fmt.decode()}.ply", b"\1" + b"ply\nformat " + fmt + b" 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
          b"property float z\nproperty float texture_u\nproperty float texture_v\nelement face 1\n"
          b"property list uchar uint vertex_indices\nend_header\n"
          + struct.pack(order + "15f", 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1) + struct.pack(order + "B3I", 3, 0, 1, 2))
write(mesh, "tri_binary.off", b"\2" + b"STNOFF BINARY\n" + struct.pack("<3I", 3, 1, 0)
      + struct.pack("<24f", 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 0, 1) + struct.pack("<4I", 3, 0, 1, 2))
write(mesh, "quad_comments.off", b"\2" + b"# a comment\nSTCNOFF 4 1 0\n0 0 0 0 0 1 1 0 0 0 0\n1 0 0 0 0 1 0 1 0 1 0 # ends here\n"
      b"1 1 0 0 0 1 0 0 1 1 1\n0 1 0 0 0 1 1 1 1 0 1\n4 0 1 2 3 255 0 0\n")

core = os.path.join(here, "corpus", "core")
rng = random.Random(20261122)
for i in range(8):
    write(core, f"random_{i}", bytes(rng.randrange(256) for _ in range(64 + 48 * i)))
print("seed corpus written")
