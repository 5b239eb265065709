#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Scenes of many primitives that share accessors, as CAD exporters write them (one mesh per
part, every part drawing the same small geometry with its own material): the scaling
benchmark for `tangent bake`, and the input of the correctness test (test_limits.py).

  shared_accessors.py write N OUT.gltf [--split] [--vertex-buffer]   one file of N primitives
  shared_accessors.py write-conflict OUT.gltf                       two primitives, one mirrored
  shared_accessors.py bench TANGENT [N ...] [--vertex-buffer]       times bake, check and info

Every primitive refers to the same POSITION, NORMAL, TEXCOORD_0 and indices accessors; with
--split the UVs have a seam (a vertex whose corners get different frames), so bake must split
vertices. With --vertex-buffer the layout of CAD and architecture exporters: one vertex buffer
of N quads (4N vertices) that every primitive shares, and per primitive its own indices
accessor drawing its own quad; with --split each quad is folded as above. write-conflict: two
quads of one vertex buffer that share an edge, the second's UVs mirrored, so the frames the two
primitives give the edge's vertices disagree. Not a timed test: the numbers are printed, nothing
is asserted.
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


def vertex_buffer_document(positions, uvs, quads, materials=2):
    """One vertex buffer (POSITION, NORMAL +z, TEXCOORD_0) and one primitive per entry of
    `quads` (a list of 6 vertex indices each, UNSIGNED_INT), each with its own indices accessor
    into one index bufferView, each in its own mesh and node, every material normal-mapped."""
    vertices = len(positions) // 3
    count = len(quads)
    blob = struct.pack(f"<{len(positions)}f", *positions)
    blob += struct.pack(f"<{3 * vertices}f", *([0, 0, 1] * vertices))
    blob += struct.pack(f"<{len(uvs)}f", *uvs)
    index_offset = len(blob)
    blob += b"".join(struct.pack("<6I", *quad) for quad in quads)
    attributes = {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}
    meshes = [{"primitives": [{"attributes": attributes, "indices": 3 + i, "material": i % materials, "mode": 4}]}
              for i in range(count)]
    low = [min(positions[axis::3]) for axis in range(3)]
    high = [max(positions[axis::3]) for axis in range(3)]
    doc = document(count, materials=materials)
    doc["meshes"] = meshes
    doc["accessors"] = [
        {"bufferView": 0, "componentType": 5126, "count": vertices, "type": "VEC3", "min": low, "max": high},
        {"bufferView": 1, "componentType": 5126, "count": vertices, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": vertices, "type": "VEC2"},
    ] + [{"bufferView": 3, "byteOffset": 24 * i, "componentType": 5125, "count": 6, "type": "SCALAR"} for i in range(count)]
    doc["bufferViews"] = [
        {"buffer": 0, "byteOffset": 0, "byteLength": 12 * vertices, "target": 34962},
        {"buffer": 0, "byteOffset": 12 * vertices, "byteLength": 12 * vertices, "target": 34962},
        {"buffer": 0, "byteOffset": 24 * vertices, "byteLength": 8 * vertices, "target": 34962},
        {"buffer": 0, "byteOffset": index_offset, "byteLength": 24 * count, "target": 34963},
    ]
    doc["buffers"] = [{"uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode(),
                       "byteLength": len(blob)}]
    return doc


def vertex_buffer(count, split=False):
    """N quads side by side in rows of 256, each drawn by its own primitive."""
    positions, uvs, quads = [], [], []
    quad_uvs = [0, 1, 1, 1, 1, 0, 0, 0] if not split else [0, 1, 1, 1, 1, 0, 2, 0]
    for i in range(count):
        x, y = 2 * (i % 256), 2 * (i // 256)
        positions += [x, y, 0, x + 1, y, 0, x + 1, y + 1, 0, x, y + 1, 0]
        uvs += quad_uvs
        quads.append([4 * i, 4 * i + 1, 4 * i + 2, 4 * i, 4 * i + 2, 4 * i + 3])
    return vertex_buffer_document(positions, uvs, quads)


def conflict():
    """Two quads sharing the edge of vertices 1 and 2; the second quad's u runs against x (its
    UVs mirrored), so at vertices 1 and 2 the first primitive's frame is (+x, w) and the
    second's (-x, -w)."""
    positions = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 2, 1, 0]
    uvs = [0, 1, 1, 1, 1, 0, 0, 0, 0, 1, 0, 0]
    quads = [[0, 1, 2, 0, 2, 3], [1, 4, 5, 1, 5, 2]]
    return vertex_buffer_document(positions, uvs, quads)


def write(count, path, split=False, layout="shared"):
    doc = {"shared": lambda: document(count, split), "vertex-buffer": lambda: vertex_buffer(count, split),
           "conflict": conflict}[layout]()
    with open(path, "w") as f:
        json.dump(doc, f, separators=(",", ":"))


def timed(argv):
    start = time.perf_counter()
    done = subprocess.run(argv, capture_output=True)
    return time.perf_counter() - start, done.returncode


def bench(tangent, counts, layout="shared"):
    """Bake without and with a split, then check and info of the input and of the baked output
    (the unsplit one): wall seconds, and the size of the unsplit input and output."""
    print(f"layout {layout}")
    print("primitives  in-bytes  out-bytes  bake-s  bake-split-s  check-in-s  info-in-s  check-out-s  info-out-s  (exit codes)")
    with tempfile.TemporaryDirectory() as folder:
        for count in counts:
            row, codes = [], []
            for split in (False, True):
                source = os.path.join(folder, f"in-{count}-{int(split)}.gltf")
                write(count, source, split, layout)
                seconds, code = timed([tangent, "bake", source, "-o", os.path.join(folder, f"out-{int(split)}.glb"), "--quiet"])
                row.append(seconds)
                codes.append(code)
            source = os.path.join(folder, f"in-{count}-0.gltf")
            baked = os.path.join(folder, "out-0.glb")
            for path in (source, baked):
                for command in ("check", "info"):
                    seconds, code = timed([tangent, command, path])
                    row.append(seconds)
                    codes.append(code)
            sizes = f"{os.path.getsize(source):9d}  {os.path.getsize(baked) if os.path.exists(baked) else -1:9d}"
            print(f"{count:10d}  {sizes}  " + "  ".join(f"{s:6.2f}" for s in row) + f"  {codes}", flush=True)


def main():
    args = sys.argv[1:]
    layout = "vertex-buffer" if "--vertex-buffer" in args else "shared"
    args = [a for a in args if a != "--vertex-buffer"]
    if len(args) >= 3 and args[0] == "write":
        write(int(args[1]), args[2], "--split" in args[3:], layout)
    elif len(args) == 2 and args[0] == "write-conflict":
        write(2, args[1], layout="conflict")
    elif len(args) >= 2 and args[0] == "bench":
        bench(args[1], [int(a) for a in args[2:]] or [1000, 8000, 64000], layout)
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
