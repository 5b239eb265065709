#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Limits of the input that the malformed-input table does not cover, through the `tangent`
command. Each test makes its own temporary folder.

  test_limits.py shared TANGENT NODE_DIR   2,000 primitives sharing accessors bake to one TANGENT
                                           accessor (and, split, to one set of rebuilt
                                           accessors); the outputs pass the Khronos validator
  test_limits.py vertex-buffer TANGENT NODE_DIR
                                           2,000 primitives on one vertex buffer, each with its own
                                           indices, bake to one shared TANGENT accessor (and, each
                                           split, to a compacted set per primitive); two that
                                           disagree on shared vertices (one mirrored) to one shared
                                           and one compacted; the outputs check clean and pass the
                                           Khronos validator
  test_limits.py check-vertex-buffer TANGENT
                                           2,000 baked primitives on one vertex buffer check clean,
                                           each judged on the 4 vertices it draws; with one
                                           primitive's stored tangents turned on its own vertices,
                                           exactly that primitive has findings; a re-bake keeps
                                           every TANGENT (and recomputes only the turned one)
  test_limits.py inputs TANGENT            a check configuration nested 1e6 deep, a broken data:
                                           URI of 2 MB and an input path longer than PATH_MAX:
                                           refused with a short message that says what is wrong
"""
import json
import math
import os
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import shared_accessors  # noqa: E402

failures = []


def expect(condition, what):
    if not condition:
        failures.append(what)


def run(argv):
    done = subprocess.run(argv, capture_output=True, timeout=300)
    return done.returncode, (done.stdout + done.stderr).decode(errors="replace")


def glb_json(path):
    with open(path, "rb") as f:
        data = f.read()
    length = struct.unpack_from("<I", data, 12)[0]
    return json.loads(data[20:20 + length])


def test_shared(tangent, node_dir):
    count = 2000
    with tempfile.TemporaryDirectory() as folder:
        outputs = []
        for split in (False, True):
            source = os.path.join(folder, f"in-{int(split)}.gltf")
            shared_accessors.write(count, source, split)
            output = os.path.join(folder, f"out-{int(split)}.glb")
            code, message = run([tangent, "bake", source, "-o", output, "--quiet"])
            expect(code == 0, f"bake split={split}: exit {code}: {message[:400]}")
            if code != 0:
                continue
            outputs.append(output)
            doc = glb_json(output)
            primitives = [p for mesh in doc["meshes"] for p in mesh["primitives"]]
            expect(len(primitives) == count, f"split={split}: {len(primitives)} primitives, expected {count}")
            tangents = {p["attributes"].get("TANGENT") for p in primitives}
            expect(len(tangents) == 1 and None not in tangents,
                   f"split={split}: TANGENT accessors {sorted(map(str, tangents))[:5]}, expected one shared")
            layouts = {json.dumps([p["attributes"], p.get("indices")], sort_keys=True) for p in primitives}
            expect(len(layouts) == 1, f"split={split}: {len(layouts)} different attribute sets, expected one")
            # Only what the primitives use: the four inputs (or their rebuilt copies) and TANGENT.
            expect(len(doc["accessors"]) == 5, f"split={split}: {len(doc['accessors'])} accessors, expected 5")
            vertices = doc["accessors"][primitives[0]["attributes"]["POSITION"]]["count"]
            expect(vertices == (6 if split else 4), f"split={split}: {vertices} vertices after the bake")
            code, message = run([tangent, "check", output])
            expect(code == 0, f"check of the baked split={split}: exit {code}: {message[:400]}")
        if os.path.isdir(os.path.join(node_dir, "node_modules", "gltf-validator")) and outputs:
            code, message = run(["node", os.path.join(node_dir, "validate.mjs")] + outputs)
            expect(code == 0, f"validator: exit {code}: {message[:800]}")
        else:
            failures.append(f"gltf-validator is not installed in {node_dir} (scripts/test.sh runs npm ci)")


def primitives_of(doc):
    return [p for mesh in doc["meshes"] for p in mesh["primitives"]]


def bake_checked(tangent, source, output, what, extra=()):
    """Bakes and checks; the baked document, or None when bake failed."""
    code, message = run([tangent, "bake", source, "-o", output, "--quiet", *extra])
    expect(code == 0, f"{what}: bake exit {code}: {message[:400]}")
    if code != 0:
        return None
    code, message = run([tangent, "check", output])
    expect(code == 0, f"{what}: check of the baked file: exit {code}: {message[:400]}")
    doc = glb_json(output)
    for p in primitives_of(doc):
        attributes = p["attributes"]
        counts = {doc["accessors"][attributes[name]]["count"] for name in ("POSITION", "NORMAL", "TEXCOORD_0", "TANGENT")}
        expect(len(counts) == 1, f"{what}: a primitive's attribute counts differ: {counts}")
    return doc


def test_vertex_buffer(tangent, node_dir):
    count = 2000
    with tempfile.TemporaryDirectory() as folder:
        outputs = []
        # Disjoint quads: one TANGENT over the whole buffer, the input's accessors kept.
        for tangent_format in ("float", "short"):
            source = os.path.join(folder, "in.gltf")
            shared_accessors.write(count, source, layout="vertex-buffer")
            output = os.path.join(folder, f"out-{tangent_format}.glb")
            doc = bake_checked(tangent, source, output, f"vertex buffer, {tangent_format}", ["--tangent-format", tangent_format])
            if doc is None:
                continue
            outputs.append(output)
            primitives = primitives_of(doc)
            expect(len(primitives) == count, f"vertex buffer: {len(primitives)} primitives, expected {count}")
            tangents = {p["attributes"].get("TANGENT") for p in primitives}
            expect(len(tangents) == 1 and None not in tangents, f"vertex buffer: {len(tangents)} TANGENT accessors, expected one shared")
            positions = {p["attributes"]["POSITION"] for p in primitives}
            indices = {p["indices"] for p in primitives}
            expect(len(positions) == 1 and len(indices) == count, f"vertex buffer: {len(positions)} POSITION and {len(indices)} "
                   f"indices accessors, expected 1 and {count}")
            expect(len(doc["accessors"]) == 3 + count + 1, f"vertex buffer: {len(doc['accessors'])} accessors, expected {count + 4}")
            vertices = doc["accessors"][positions.pop()]["count"]
            expect(vertices == 4 * count, f"vertex buffer: {vertices} vertices after the bake, expected {4 * count}")
            # About 420 bytes a primitive (4 vertices, 6 indices, its JSON); quadratic was 64 kB each at 1,000.
            size = os.path.getsize(output)
            expect(size < 1000 * count, f"vertex buffer: {size} bytes written for {count} primitives")
        # Each quad folded (a vertex split in each): every primitive its own compacted set.
        source = os.path.join(folder, "in-split.gltf")
        shared_accessors.write(count, source, split=True, layout="vertex-buffer")
        output = os.path.join(folder, "out-split.glb")
        doc = bake_checked(tangent, source, output, "vertex buffer, split")
        if doc is not None:
            outputs.append(output)
            primitives = primitives_of(doc)
            tangents = {p["attributes"]["TANGENT"] for p in primitives}
            expect(len(tangents) == count, f"vertex buffer, split: {len(tangents)} TANGENT accessors, expected {count}")
            expect(len(doc["accessors"]) == 5 * count, f"vertex buffer, split: {len(doc['accessors'])} accessors, expected {5 * count}")
            vertices = {doc["accessors"][p["attributes"]["POSITION"]]["count"] for p in primitives}
            expect(vertices == {6}, f"vertex buffer, split: vertex counts {vertices}, expected 6 (4 used, the fold splits 2)")
            size = os.path.getsize(output)
            expect(size < 2000 * count, f"vertex buffer, split: {size} bytes written for {count} primitives")
        # Two quads sharing an edge, the second mirrored: the first shares the buffer's TANGENT,
        # the second gets its own 4 vertices.
        source = os.path.join(folder, "in-conflict.gltf")
        shared_accessors.write(2, source, layout="conflict")
        output = os.path.join(folder, "out-conflict.glb")
        doc = bake_checked(tangent, source, output, "vertex buffer, conflict")
        if doc is not None:
            outputs.append(output)
            first, second = primitives_of(doc)
            counts = [doc["accessors"][p["attributes"]["POSITION"]]["count"] for p in (first, second)]
            expect(counts == [6, 4], f"vertex buffer, conflict: vertex counts {counts}, expected [6, 4]")
            expect(first["attributes"]["TANGENT"] != second["attributes"]["TANGENT"], "vertex buffer, conflict: one TANGENT for both")
        if os.path.isdir(os.path.join(node_dir, "node_modules", "gltf-validator")) and outputs:
            code, message = run(["node", os.path.join(node_dir, "validate.mjs")] + outputs)
            expect(code == 0, f"validator: exit {code}: {message[:800]}")
        else:
            failures.append(f"gltf-validator is not installed in {node_dir} (scripts/test.sh runs npm ci)")


def glb_chunks(path):
    """The JSON document and the BIN chunk of a .glb."""
    with open(path, "rb") as f:
        data = f.read()
    length = struct.unpack_from("<I", data, 12)[0]
    bin_start = 20 + length
    bin_length = struct.unpack_from("<I", data, bin_start)[0]
    return json.loads(data[20:20 + length]), bytearray(data[bin_start + 8:bin_start + 8 + bin_length])


def write_glb(path, doc, binary):
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    binary = bytes(binary) + b"\0" * (-len(binary) % 4)
    with open(path, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 28 + len(text) + len(binary)))
        f.write(struct.pack("<II", len(text), 0x4E4F534A) + text)
        f.write(struct.pack("<II", len(binary), 0x004E4942) + binary)


def accessor_offset(doc, index):
    """Byte offset and stride of a tightly stored accessor in the BIN chunk."""
    accessor = doc["accessors"][index]
    view = doc["bufferViews"][accessor["bufferView"]]
    size = {5121: 1, 5123: 2, 5125: 4, 5126: 4}[accessor["componentType"]] * {"SCALAR": 1, "VEC4": 4}[accessor["type"]]
    return view.get("byteOffset", 0) + accessor.get("byteOffset", 0), view.get("byteStride", size)


def check_json(tangent, path):
    done = subprocess.run([tangent, "check", path, "--format", "json"], capture_output=True, timeout=300)
    try:
        return done.returncode, json.loads(done.stdout)["files"][0]
    except (ValueError, KeyError, IndexError):
        return done.returncode, {"primitives": [], "error": (done.stdout + done.stderr).decode(errors="replace")[:400]}


def test_check_vertex_buffer(tangent):
    """check judges each primitive of a shared vertex buffer on the vertices it draws (not the
    whole buffer), and bake keeps what check passes."""
    count, turned = 2000, 1234
    with tempfile.TemporaryDirectory() as folder:
        source = os.path.join(folder, "in.gltf")
        shared_accessors.write(count, source, layout="vertex-buffer")
        baked = os.path.join(folder, "baked.glb")
        code, message = run([tangent, "bake", source, "-o", baked, "--quiet"])
        expect(code == 0, f"bake: exit {code}: {message[:400]}")
        if code != 0:
            return
        code, report = check_json(tangent, baked)
        primitives = report["primitives"]
        expect(code == 0 and report.get("status") == "clean", f"check of the baked file: exit {code}, {report.get('error', '')}")
        expect(len(primitives) == count, f"check: {len(primitives)} primitives, expected {count}")
        vertices = {p["vertices"] for p in primitives}
        expect(vertices == {4}, f"check: vertex counts {vertices}, expected 4 (the vertices each primitive draws)")

        # Turn the stored tangents of one primitive's 4 vertices by 30 degrees in their plane
        # (still orthogonal, of the right w: `reference` sees it) and lengthen its first one by
        # 20% (`unit`, a per-vertex check: it must not reach the other primitives).
        doc, binary = glb_chunks(baked)
        primitive = primitives_of(doc)[turned]
        start, stride = accessor_offset(doc, primitive["indices"])
        fmt = {5121: "<B", 5123: "<H", 5125: "<I"}[doc["accessors"][primitive["indices"]]["componentType"]]
        drawn = {struct.unpack_from(fmt, binary, start + i * stride)[0] for i in range(doc["accessors"][primitive["indices"]]["count"])}
        expect(len(drawn) == 4, f"primitive {turned} draws {len(drawn)} vertices, expected 4")
        start, stride = accessor_offset(doc, primitive["attributes"]["TANGENT"])
        expect(doc["accessors"][primitive["attributes"]["TANGENT"]]["componentType"] == 5126, "the baked TANGENT is not float")
        c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
        for v in drawn:
            x, y, z, w = struct.unpack_from("<4f", binary, start + v * stride)
            # The quads lie in z = 0 with normal +z: a turn about z stays in the tangent plane.
            scale = 1.2 if v == min(drawn) else 1.0
            struct.pack_into("<4f", binary, start + v * stride, scale * (c * x - s * y), scale * (s * x + c * y), scale * z, w)
        corrupted = os.path.join(folder, "turned.glb")
        write_glb(corrupted, doc, binary)
        code, report = check_json(tangent, corrupted)
        flagged = [(p["mesh"], p["primitive"], [f["check"] for f in p["findings"]]) for p in report["primitives"] if p["findings"]]
        expect(code == 1, f"check of the turned file: exit {code}, expected 1 {report.get('error', '')}")
        expect(flagged == [(turned, 0, ["unit", "reference"])], f"check of the turned file: findings {flagged[:3]} on "
               f"{len(flagged)} primitives, expected only on mesh {turned} primitive 0 (unit, reference)")

        # Re-bakes: every TANGENT of the baked file kept; of the turned file, all but one.
        for path, expected in ((baked, {"kept": count}), (corrupted, {"kept": count - 1, "baked": 1})):
            rebaked, report_path = os.path.join(folder, "rebaked.glb"), os.path.join(folder, "report.json")
            code, message = run([tangent, "bake", path, "-o", rebaked, "--quiet", "--report", report_path])
            expect(code == 0, f"re-bake of {os.path.basename(path)}: exit {code}: {message[:400]}")
            if code != 0:
                continue
            with open(report_path) as f:
                results = [r for entry in json.load(f) for r in entry["primitives"]]
            actions = {}
            for r in results:
                actions[r["action"]] = actions.get(r["action"], 0) + 1
            expect(actions == expected, f"re-bake of {os.path.basename(path)}: actions {actions}, expected {expected}")
            if path == corrupted:
                recomputed = [(r["mesh"], r["primitive"]) for r in results if r["action"] == "baked"]
                expect(recomputed == [(turned, 0)], f"re-bake of the turned file: recomputed {recomputed[:5]} ({len(recomputed)})")


def test_inputs(tangent):
    with tempfile.TemporaryDirectory() as folder:
        source = os.path.join(folder, "in.gltf")
        shared_accessors.write(1, source)
        # A check configuration nested a million deep: refused like a deep glTF, no crash.
        config = os.path.join(folder, "deep.json")
        with open(config, "w") as f:
            f.write("{\"only\": " + "[" * 1000000 + "]" * 1000000 + "}")
        code, message = run([tangent, "check", source, "--config", config])
        expect(code == 2, f"deep config: exit {code}, expected 2: {message[:400]}")
        expect("deep.json" in message and "nests deeper than" in message, f"deep config: message {message[:400]!r}")
        # A broken data: URI of 2 MB: the message names the buffer and says base64, quoting none of it.
        doc = shared_accessors.document(1)
        doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + "@" * 2000000
        broken = os.path.join(folder, "broken.gltf")
        with open(broken, "w") as f:
            json.dump(doc, f)
        for command in (["bake", broken, "-o", os.path.join(folder, "out.glb")], ["check", broken], ["info", broken]):
            code, message = run([tangent] + command)
            expect(code in (1, 2) and "/buffers/0 uri" in message and "base64" in message,
                   f"{command[0]} broken data: URI: exit {code}: {message[:300]!r}")
            expect(len(message) < 1000, f"{command[0]} broken data: URI: a message of {len(message)} characters")
        # An input name longer than PATH_MAX: the name is too long, not missing.
        long_name = os.path.join(folder, "/".join(["d" * 200] * 30) + ".gltf")
        for command in (["bake", long_name, "-o", os.path.join(folder, "out.glb")], ["check", long_name], ["info", long_name]):
            code, message = run([tangent] + command)
            expect(code in (1, 2), f"{command[0]} long path: exit {code}: {message[:300]}")
            expect("too long" in message and "no such file" not in message,
                   f"{command[0]} long path: message {message[:300]!r}")


def main():
    if len(sys.argv) >= 4 and sys.argv[1] == "shared":
        test_shared(sys.argv[2], sys.argv[3])
    elif len(sys.argv) >= 4 and sys.argv[1] == "vertex-buffer":
        test_vertex_buffer(sys.argv[2], sys.argv[3])
    elif len(sys.argv) >= 3 and sys.argv[1] == "check-vertex-buffer":
        test_check_vertex_buffer(sys.argv[2])
    elif len(sys.argv) >= 3 and sys.argv[1] == "inputs":
        test_inputs(sys.argv[2])
    else:
        sys.exit(__doc__)
    for failure in failures:
        print("FAIL " + failure)
    print(f"{sys.argv[1]}: {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
