#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Scenes of many primitives that share accessors, as CAD exporters write them (one mesh per
part, every part drawing the same small geometry with its own material): the scaling
benchmark for `tangent bake`, and the input of the correctness test (test_limits.py).

  shared_accessors.py write N OUT.gltf [--split]   one file of N primitives
  shared_accessors.py bench TANGENT [N ...]         times bake, check and info at each N

Every primitive refers to the same POSITION, NORMAL, TEXCOORD_0 and indices accessors; with
--split the UVs have a seam (a vertex whose corners get different frames), so bake must split
vertices. Not a timed test: the numbers are printed, nothing is asserted.
"""
import base64
import json
import os
import struct
import subprocess
import sys
import tempfile
import time

PNG = base64.b64decode(
    "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGP4//8/AAX+Av4N70a4AAAAAElFTkSuQmCC")


def geometry(split):
    """A quad (two triangles). With split, vertex 0's UVs fold the second triangle over the first
    (mirrored), so its corners get frames of opposite handedness: the vertex is split."""
    positions = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]
    normals = [0, 0, 1] * 4
    uvs = [0, 1, 1, 1, 1, 0, 0, 0] if not split else [0, 1, 1, 1, 1, 0, 2, 0]
    indices = [0, 1, 2, 0, 2, 3]
    blob = struct.pack("<12f", *positions) + struct.pack("<12f", *normals) + struct.pack("<8f", *uvs)
    blob += struct.pack("<6H", *indices) + b"\0\0"
    return blob


def document(count, split=False, materials=2):
    blob = geometry(split)
    primitive = {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "mode": 4}
    meshes = [{"primitives": [dict(primitive, material=i % materials)]} for i in range(count)]
    return {
        "asset": {"version": "2.0", "generator": "libtangent tests/limits"},
        "scene": 0,
        "scenes": [{"nodes": list(range(count))}],
        "nodes": [{"mesh": i} for i in range(count)],
        "meshes": meshes,
        "materials": [{"normalTexture": {"index": 0}} for _ in range(materials)],
        "textures": [{"source": 0}],
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(PNG).decode(), "mimeType": "image/png"}],
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
        "buffers": [{"uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode(),
                     "byteLength": len(blob)}],
    }


def write(count, path, split=False):
    with open(path, "w") as f:
        json.dump(document(count, split), f, separators=(",", ":"))


def timed(argv):
    start = time.perf_counter()
    done = subprocess.run(argv, capture_output=True)
    return time.perf_counter() - start, done.returncode


def bench(tangent, counts):
    print("primitives  file-bytes  bake-s  bake-split-s  check-s  info-s  (exit codes)")
    with tempfile.TemporaryDirectory() as folder:
        for count in counts:
            row, codes = [], []
            for split in (False, True):
                source = os.path.join(folder, f"in-{count}-{int(split)}.gltf")
                write(count, source, split)
                seconds, code = timed([tangent, "bake", source, "-o", os.path.join(folder, "out.glb"), "--quiet"])
                row.append(seconds)
                codes.append(code)
            size = os.path.getsize(os.path.join(folder, f"in-{count}-0.gltf"))
            for command in ("check", "info"):
                seconds, code = timed([tangent, command, os.path.join(folder, f"in-{count}-0.gltf")])
                row.append(seconds)
                codes.append(code)
            print(f"{count:10d}  {size:10d}  " + "  ".join(f"{s:6.2f}" for s in row) + f"  {codes}", flush=True)


def main():
    args = sys.argv[1:]
    if len(args) >= 3 and args[0] == "write":
        write(int(args[1]), args[2], "--split" in args[3:])
    elif len(args) >= 2 and args[0] == "bench":
        bench(args[1], [int(a) for a in args[2:]] or [1000, 8000, 64000])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
