#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Compressed input round trip (issue 11, item 4): our own clean bakes, compressed by the tools
pipelines use, read back by `tangent`.

For each input (the generated test assets and, where ../shared/assets exists, the shared
sample assets) and each compressor (gltf-transform draco, gltf-transform meshopt, gltfpack -c):
  1. a clean bake (`tangent bake --overwrite`) is compressed; `info` names the compression of
     every primitive (text and JSON); `check` gives the same verdict as on the clean bake
     (at default settings);
  2. the input without TANGENT is compressed and baked: the Khronos validator reports 0
     errors; the output declares KHR_draco_mesh_compression / EXT_meshopt_compression exactly
     while some primitive / bufferView still uses it, and the bake report names what it
     removed; the tangents match those baked from the uncompressed source (corners matched by
     world position, triangle centre, normal and normal-texture UV) within the quantization's
     error;
  3. no input is modified.

Usage: roundtrip.py TANGENT TEST_ASSETS_TOOL SOURCE_DIR generated|shared
Exit 77 (skipped) where the shared assets are absent, 1 under CI=true (skip_or_fail.sh).
"""
import hashlib
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

import numpy as np

# check runs at its default settings on every compressed copy: meshopt and gltfpack store
# quantized accessors, whose rounding check's rules allow for; Draco quantizes positions and
# UVs inside its stream and decodes them to floats, and check finds the Draco grid that holds
# the decoded values (tangent_rules.cpp). A label listed here would run
# with a wider --tolerance instead.
CHECK_TOLERANCE = {}

# Tangents baked from a compressed file against those baked from its source, per corner
# (degrees). MikkTSpace is sensitive to the quantized UVs and normals on small or thin
# triangles, so the bound is on a high percentile; the median must stay small, and w must
# agree almost everywhere (it flips only where a UV triangle is degenerate after quantizing).
MEDIAN_LIMIT_DEG = 1.0
P95_LIMIT_DEG = 6.0
W_AGREEMENT_MIN = 0.98
MAX_COMPARED_CORNERS = 3000
# The generated asset of 360,000 corners (index widening) is left out of the round trip: it
# tests nothing compression adds and would dominate the run time.
SKIPPED_GENERATED = {"many_splits.glb"}

# Where a compressor itself changes what tangents are computed from, the clean copy's check
# and the tangent comparison are not asserted (everything else is); each was verified by hand.
COMPRESSOR_CHANGES = {
    ("quantized.glb", "meshopt"):
        "gltf-transform 4.5.1 meshopt requantizes the non-normalized SHORT positions flat in z (its own "
        "accessor min/max and `gltf-transform inspect` give z = 0)",
    ("second_uv_set.glb", "gltfpack"):
        "gltfpack 0.18 drops KHR_texture_transform's texCoord override: the normal texture then samples "
        "TEXCOORD_0 instead of TEXCOORD_1",
}

# Bakes that baked some primitives and kept a compression extension others still use.
KEPT_IN_USE = []

DRACO = "KHR_draco_mesh_compression"
MESHOPT = "EXT_meshopt_compression"


def run(args, expect=0):
    result = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if expect is not None and result.returncode != expect:
        raise AssertionError(f"{' '.join(map(str, args))}: exit {result.returncode}, expected {expect}\n{result.stdout[-3000:]}")
    return result


def read_gltf(path):
    """(document, [buffer bytes]) of a .glb or .gltf with external buffers."""
    data = open(path, "rb").read()
    if data[:4] == b"glTF":
        json_length = struct.unpack_from("<I", data, 12)[0]
        doc = json.loads(data[20:20 + json_length])
        rest = 20 + json_length
        bin_chunk = b""
        if rest + 8 <= len(data):
            bin_length = struct.unpack_from("<I", data, rest)[0]
            bin_chunk = data[rest + 8:rest + 8 + bin_length]
        buffers = []
        for i, buffer in enumerate(doc.get("buffers", [])):
            buffers.append(bin_chunk if "uri" not in buffer and i == 0 else
                           open(os.path.join(os.path.dirname(path), buffer["uri"]), "rb").read() if "uri" in buffer else b"")
        return doc, buffers
    doc = json.loads(data)
    buffers = [open(os.path.join(os.path.dirname(path), b["uri"]), "rb").read() if "uri" in b else b""
               for b in doc.get("buffers", [])]
    return doc, buffers


def write_glb(path, doc, bin_bytes):
    text = json.dumps(doc).encode()
    text += b" " * ((4 - len(text) % 4) % 4)
    bin_bytes = bin_bytes + b"\0" * ((4 - len(bin_bytes) % 4) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text
    if bin_bytes:
        body += struct.pack("<II", len(bin_bytes), 0x004E4942) + bin_bytes
    with open(path, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)


COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
DTYPES = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}
NORMALIZE = {5120: 127.0, 5121: 255.0, 5122: 32767.0, 5123: 65535.0}


def accessor_values(doc, buffers, index):
    """Values of an uncompressed, non-sparse accessor as float64 (normalized ints decoded)."""
    accessor = doc["accessors"][index]
    view = doc["bufferViews"][accessor["bufferView"]]
    assert "extensions" not in view, "a baked output's accessor is still compressed"
    components = COMPONENTS[accessor["type"]]
    dtype = np.dtype(DTYPES[accessor["componentType"]])
    element = components * dtype.itemsize
    stride = view.get("byteStride", element)
    start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    raw = buffers[view["buffer"]]
    rows = [np.frombuffer(raw, dtype, components, start + i * stride) for i in range(accessor["count"])] \
        if stride != element else [np.frombuffer(raw, dtype, components * accessor["count"], start)]
    values = np.concatenate(rows).reshape(accessor["count"], components).astype(np.float64)
    if accessor.get("normalized"):
        values = np.maximum(values / NORMALIZE[accessor["componentType"]], -1.0)
    return values


def node_matrices(doc):
    """mesh index -> list of world matrices of the nodes that show it."""
    def local(node):
        if "matrix" in node:
            return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T
        t = np.array(node.get("translation", [0, 0, 0]), dtype=np.float64)
        x, y, z, w = node.get("rotation", [0, 0, 0, 1])
        r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                      [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                      [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
        s = np.diag(node.get("scale", [1, 1, 1]))
        m = np.eye(4)
        m[:3, :3] = r @ s
        m[:3, 3] = t
        return m
    found = {}
    nodes = doc.get("nodes", [])
    roots = doc["scenes"][doc.get("scene", 0)]["nodes"] if doc.get("scenes") else range(len(nodes))
    stack = [(n, np.eye(4)) for n in roots]
    while stack:
        n, parent = stack.pop()
        world = parent @ local(nodes[n])
        if "mesh" in nodes[n]:
            found.setdefault(nodes[n]["mesh"], []).append(world)
        stack.extend((c, world) for c in nodes[n].get("children", []))
    return found


def uv_transform(doc, primitive):
    """The normal texture's UV set and its KHR_texture_transform as a function on uvs."""
    material = doc["materials"][primitive["material"]] if "material" in primitive else {}
    normal_texture = material.get("normalTexture", {})
    tex_coord = normal_texture.get("texCoord", 0)
    transform = normal_texture.get("extensions", {}).get("KHR_texture_transform", {})
    tex_coord = transform.get("texCoord", tex_coord)
    offset = np.array(transform.get("offset", [0, 0]))
    scale = np.array(transform.get("scale", [1, 1]))
    c, s = np.cos(transform.get("rotation", 0.0)), np.sin(transform.get("rotation", 0.0))

    def apply(uv):
        u, v = uv[:, 0] * scale[0], uv[:, 1] * scale[1]
        return np.stack([c * u + s * v + offset[0], -s * u + c * v + offset[1]], axis=1)
    return tex_coord, apply


def baked_corners(path):
    """Every triangle corner of the primitives with a TANGENT, in world space: position, the
    triangle's centre (which tells apart the copies of a vertex split at a mirrored seam),
    normal, normal-texture UV, tangent xyz, w."""
    doc, buffers = read_gltf(path)
    worlds = node_matrices(doc)
    parts = []
    for m, mesh in enumerate(doc.get("meshes", [])):
        for primitive in mesh["primitives"]:
            attributes = primitive["attributes"]
            if "TANGENT" not in attributes or "NORMAL" not in attributes or primitive.get("mode", 4) != 4:
                continue
            tex_coord, transform = uv_transform(doc, primitive)
            if f"TEXCOORD_{tex_coord}" not in attributes:
                continue
            positions = accessor_values(doc, buffers, attributes["POSITION"])
            normals = accessor_values(doc, buffers, attributes["NORMAL"])
            uvs = transform(accessor_values(doc, buffers, attributes[f"TEXCOORD_{tex_coord}"]))
            tangents = accessor_values(doc, buffers, attributes["TANGENT"])
            corners = (accessor_values(doc, buffers, primitive["indices"])[:, 0].astype(np.int64)
                       if "indices" in primitive else np.arange(len(positions)))
            for world in worlds.get(m, []):
                linear = world[:3, :3]
                normal_matrix = np.linalg.inv(linear).T
                p = (positions @ linear.T + world[:3, 3])[corners]
                centre = p.reshape(-1, 3, 3).mean(axis=1).repeat(3, axis=0)
                n = (normals @ normal_matrix.T)[corners]
                t = (tangents[:, :3] @ linear.T)[corners]
                n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)
                t /= np.maximum(np.linalg.norm(t, axis=1, keepdims=True), 1e-30)
                w = tangents[corners, 3] * np.sign(np.linalg.det(linear))
                parts.append((p, centre, n, uvs[corners], t, w))
    return tuple(np.concatenate([part[i] for part in parts]) for i in range(6))


def compare_tangents(compressed_bake, source_bake):
    """Per triangle corner of the compressed bake: the angle (degrees) to the tangent at the
    nearest corner of the source bake (by position, triangle centre, normal and UV), and
    whether w agrees."""
    p1, c1, n1, uv1, t1, w1 = baked_corners(compressed_bake)
    p0, c0, n0, uv0, t0, w0 = baked_corners(source_bake)
    # A brute-force nearest search: a fixed sample of the compressed bake's corners.
    sample = np.random.default_rng(11).permutation(len(p1))[:MAX_COMPARED_CORNERS]
    p1, c1, n1, uv1, t1, w1 = (a[sample] for a in (p1, c1, n1, uv1, t1, w1))
    size = max(np.ptp(p0, axis=0).max(), 1e-12)
    key0 = np.concatenate([p0 / size * 100, c0 / size * 100, n0, uv0 * 10], axis=1)
    key1 = np.concatenate([p1 / size * 100, c1 / size * 100, n1, uv1 * 10], axis=1)
    nearest = np.empty(len(key1), dtype=np.int64)
    norms0 = (key0 * key0).sum(axis=1)
    for start in range(0, len(key1), 256):
        block = key1[start:start + 256]
        distances = norms0[None, :] - 2 * block @ key0.T
        nearest[start:start + 256] = distances.argmin(axis=1)
    cosine = np.clip((t1 * t0[nearest]).sum(axis=1), -1, 1)
    angles = np.degrees(np.arccos(cosine))
    return angles, w1 == w0[nearest]


def declared(doc, name):
    return name in doc.get("extensionsUsed", []), name in doc.get("extensionsRequired", [])


def uses_draco(doc):
    return any(DRACO in p.get("extensions", {}) for m in doc.get("meshes", []) for p in m["primitives"])


def uses_meshopt(doc):
    return any(MESHOPT in v.get("extensions", {}) for v in doc.get("bufferViews", []))


def primitive_uses_meshopt(doc, primitive):
    accessors = list(primitive["attributes"].values()) + ([primitive["indices"]] if "indices" in primitive else [])
    accessors += [a for target in primitive.get("targets", []) for a in target.values()]
    views = doc.get("bufferViews", [])
    for a in accessors:
        accessor = doc["accessors"][a]
        used = [accessor.get("bufferView")] + [accessor.get("sparse", {}).get(part, {}).get("bufferView")
                                               for part in ("indices", "values")]
        if any(v is not None and MESHOPT in views[v].get("extensions", {}) for v in used):
            return True
    return False


def strip_tangents(source, target):
    """A copy of a .glb without TANGENT attributes (their accessors left unused)."""
    doc, buffers = read_gltf(source)
    for mesh in doc.get("meshes", []):
        for primitive in mesh["primitives"]:
            primitive["attributes"].pop("TANGENT", None)
            for morph in primitive.get("targets", []):
                morph.pop("TANGENT", None)
    write_glb(target, doc, buffers[0] if buffers else b"")


def sha256(path):
    return hashlib.sha256(open(path, "rb").read()).hexdigest()


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    tangent, make_assets, source_dir, mode = sys.argv[1:]
    gltf_transform = os.path.join(source_dir, "tests/node/node_modules/.bin/gltf-transform")
    if not os.path.exists(gltf_transform):
        sys.exit(f"{gltf_transform} is missing: run scripts/test.sh (npm ci in tests/node)")
    if not shutil.which("gltfpack"):
        sys.exit("gltfpack is missing: run scripts/install-deps.sh")
    work = tempfile.mkdtemp(prefix="tangent-compressed-")
    try:
        if mode == "shared":
            shared = os.path.join(source_dir, "../shared/assets")
            if not os.path.isdir(shared):
                os.execv(os.path.join(source_dir, "tests/support/skip_or_fail.sh"),
                         ["skip_or_fail.sh", f"{shared} is absent: compressed round trip of the shared assets not run"])
            inputs = sorted(os.path.join(shared, f) for f in os.listdir(shared) if f.endswith(".glb"))
        else:
            listed = run([make_assets, os.path.join(work, "generated")]).stdout.split()
            # The .glb of each generated asset (its .gltf twin is the same document).
            inputs = [f for f in listed if f.endswith(".glb") and os.path.basename(f) not in SKIPPED_GENERATED]
        failures = []
        for source in inputs:
            try:
                failures += roundtrip(tangent, gltf_transform, source, os.path.join(work, os.path.basename(source)))
            except AssertionError as e:
                failures.append(f"{source}: {e}")
        if mode == "generated":
            print(f"{len(KEPT_IN_USE)} bakes kept a compression extension that unbaked data still uses: "
                  + ", ".join(KEPT_IN_USE))
            if not KEPT_IN_USE:
                failures.append("no bake kept a compression extension in use: that case went untested")
        for failure in failures:
            print("FAIL", failure)
        return 1 if failures else 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


def compressors(gltf_transform):
    return {
        "draco": ([gltf_transform, "draco"], DRACO),
        "meshopt": ([gltf_transform, "meshopt"], MESHOPT),
        "gltfpack": (["gltfpack", "-c", "-i"], MESHOPT),
    }


def compress(command, source, target):
    args = command[0] + [source, "-o", target] if command[0][0] == "gltfpack" else command[0] + [source, target]
    run(args)


def roundtrip(tangent, gltf_transform, source, work):
    os.makedirs(work, exist_ok=True)
    name = os.path.basename(source)
    failures = []
    clean = os.path.join(work, "clean.glb")
    run([tangent, "bake", source, "-o", clean, "--overwrite", "--quiet"])
    clean_check = json.loads(run([tangent, "check", clean, "--format", "json"], expect=None).stdout)["files"][0]
    bare = os.path.join(work, "bare.glb")
    strip_tangents(source, bare)
    reference = os.path.join(work, "reference.glb")
    run([tangent, "bake", bare, "-o", reference, "--quiet"])
    bakes = []
    for label, command in compressors(gltf_transform).items():
        extension = command[1]
        where = f"{name} {label}"
        # 1. a clean bake, compressed: info names the compression, check agrees.
        packed = os.path.join(work, f"clean-{label}.glb")
        compress(command, clean, packed)
        packed_hash = sha256(packed)
        info = json.loads(run([tangent, "info", packed, "--json"]).stdout)
        packed_doc, _ = read_gltf(packed)
        for mesh in info["meshes"]:
            for primitive in mesh["primitives"]:
                doc_primitive = packed_doc["meshes"][mesh["index"]]["primitives"][primitive["index"]]
                expected = [DRACO] if DRACO in doc_primitive.get("extensions", {}) else []
                if primitive_uses_meshopt(packed_doc, doc_primitive):
                    expected += [MESHOPT]
                if primitive["compression"] != expected:
                    failures.append(f"{where}: info says mesh {mesh['index']} primitive {primitive['index']} used "
                                    f"{primitive['compression']}, expected {expected}")
        if not any(extension in p["compression"] for m in info["meshes"] for p in m["primitives"]):
            failures.append(f"{where}: info names {extension} for no primitive")
        text = run([tangent, "info", packed]).stdout
        if extension not in text:
            failures.append(f"{where}: info's text does not name {extension}")
        changed = COMPRESSOR_CHANGES.get((name, label))
        if changed:
            print(f"{where}: check verdict and tangents not compared: {changed}")
        tolerance = ["--tolerance", CHECK_TOLERANCE[label]] if label in CHECK_TOLERANCE else []
        check = json.loads(run([tangent, "check", packed, "--format", "json"] + tolerance, expect=None).stdout)["files"][0]
        if check["status"] != clean_check["status"] and not changed:
            failures.append(f"{where}: check says {check['status']} ({' '.join(tolerance) or 'default settings'}), "
                            f"the clean bake {clean_check['status']}: " +
                            json.dumps([f for p in check["primitives"] for f in p["findings"]])[:600])

        # 2. the source without TANGENT, compressed, then baked.
        bare_packed = os.path.join(work, f"bare-{label}.glb")
        compress(command, bare, bare_packed)
        bare_doc, _ = read_gltf(bare_packed)
        bare_hash = sha256(bare_packed)
        baked = os.path.join(work, f"baked-{label}.glb")
        report_path = os.path.join(work, f"report-{label}.json")
        run([tangent, "bake", bare_packed, "-o", baked, "--quiet", "--report", report_path])
        report = json.load(open(report_path))[0]
        bakes.append((bare_packed, baked))
        baked_doc, _ = read_gltf(baked)
        for ext, used in ((DRACO, uses_draco(baked_doc)), (MESHOPT, uses_meshopt(baked_doc))):
            was_used, was_required = declared(bare_doc, ext)
            now_used, now_required = declared(baked_doc, ext)
            if now_used != (used and was_used) or now_required != (used and was_required):
                failures.append(f"{where}: {ext} declared used={now_used} required={now_required} "
                                f"while {'still' if used else 'no longer'} used")
            if used and was_used and any(p["action"] == "baked" for p in report["primitives"]):
                KEPT_IN_USE.append(f"{where} {ext}")
            removed = ext in report.get("extensionsRemoved", [])
            if removed != (was_used and not used):
                failures.append(f"{where}: the bake report {'names' if removed else 'does not name'} {ext} as removed")
        angles, w_agrees = compare_tangents(baked, reference)
        if len(angles) and not changed:
            median, p95, worst = np.percentile(angles, 50), np.percentile(angles, 95), angles.max()
            agreement = w_agrees.mean()
            print(f"{where}: {len(angles)} corners, tangent angle to the uncompressed bake: median {median:.3f}, "
                  f"95th percentile {p95:.3f}, max {worst:.2f} deg; w agrees on {100 * agreement:.2f}%")
            if median > MEDIAN_LIMIT_DEG or p95 > P95_LIMIT_DEG or agreement < W_AGREEMENT_MIN:
                failures.append(f"{where}: tangents differ from the uncompressed bake beyond the quantization's error "
                                f"(median {median:.3f}, p95 {p95:.3f} deg, w agrees {100 * agreement:.2f}%)")
        # 3. inputs untouched.
        if sha256(packed) != packed_hash or sha256(bare_packed) != bare_hash:
            failures.append(f"{where}: an input was modified")
    # The validator on each compressed input and its bake: 0 errors, or (where the compressor
    # wrote an invalid file: gltfpack 0.18 renames custom attributes to ATTRIBUTE_n) none that
    # the input does not have.
    files = [f for pair in bakes for f in pair]
    validator = run(["node", os.path.join(os.path.dirname(gltf_transform), "../../validate.mjs")] + files, expect=None)
    results = {r["file"]: r for r in map(json.loads, validator.stdout.splitlines()) if r.get("file")}
    for compressed, baked in bakes:
        codes = lambda f: {e.split(" ")[0] for e in results[f]["firstErrors"]}
        if results[baked]["errors"] and (not results[compressed]["errors"] or codes(baked) - codes(compressed)):
            failures.append(f"{baked}: the validator finds errors the compressed input does not have: "
                            f"{results[baked]['firstErrors']} (input: {results[compressed]['firstErrors']})")
        elif results[baked]["errors"]:
            print(f"{os.path.basename(baked)} of {name}: validator errors only as in its input: {results[baked]['firstErrors']}")
    return failures


if __name__ == "__main__":
    sys.exit(main())
