# SPDX-License-Identifier: MIT
"""Work a file implies without storing it, and GLB headers that claim more than the file holds.

An accessor without a bufferView is `count` zeros: a few bytes of JSON can declare a billion
triangles. bake, check and info refuse such a file by name (the accessor, what it implies and
the budget: kImpliedValuesFree in accessors.hpp) in bounded memory and time, while a morph
target's sparse accessor, as long as the POSITION it moves, still loads. A GLB whose header
claims a JSON chunk over the limit is refused before the file is read. The memory bound is an
address-space limit (prlimit) where the CLI is not built with AddressSanitizer, which reserves
terabytes of address space by design."""
import json
import os
import pathlib
import resource
import struct
import subprocess
import time

import pytest

from test_outputs import CLI, glb_bytes, grid, write

# Exit codes for input a command cannot read (tests/malformed/make_cases.py: check's 1 is a finding).
REFUSED = {"bake": 1, "check": 2, "info": 1}
COMMANDS = {
    "bake": lambda path: ["bake", path, "-o", path.with_name("out.glb")],
    "check": lambda path: ["check", path],
    "info": lambda path: ["info", path],
}


def sanitized():
    with open(CLI, "rb") as binary:
        return b"__asan_init" in binary.read()


def run_limited(args, memory_bytes=1 << 30, timeout=60):
    """Runs the CLI under an address-space limit (none under ASan): (exit status, stderr, seconds)."""
    def limit():
        if not sanitized_cli:
            resource.setrlimit(resource.RLIMIT_AS, (memory_bytes, memory_bytes))
    start = time.monotonic()
    done = subprocess.run([CLI, *map(str, args)], capture_output=True, timeout=timeout, preexec_fn=limit)
    stderr = done.stderr.decode(errors="replace")
    assert "AddressSanitizer" not in stderr and "runtime error:" not in stderr, stderr
    return done.returncode, stderr, time.monotonic() - start


sanitized_cli = sanitized()


def zero_data(doc, blob, accessor, count):
    """`doc` with accessor `accessor` made `count` elements without a bufferView (zeros)."""
    doc = json.loads(json.dumps(doc))
    entry = doc["accessors"][accessor]
    entry.pop("bufferView", None)
    entry.pop("byteOffset", None)
    entry["count"] = count
    entry.pop("min", None)
    entry.pop("max", None)
    if accessor == 0:
        entry["min"], entry["max"] = [0, 0, 0], [0, 0, 0]
    return doc


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("triangles", [10**6, 10**7, 10**9])
def test_indices_without_data_are_refused_by_the_work_they_imply(tmp_path, command, triangles):
    doc, blob = grid(4)
    path = write(tmp_path / "zeros.glb", glb_bytes(zero_data(doc, blob, 3, 3 * triangles), blob))
    assert path.stat().st_size < 5000
    status, stderr, seconds = run_limited(COMMANDS[command](path))
    assert status == REFUSED[command], stderr
    assert "zeros.glb" in stderr and "/accessors/3" in stderr and "has no bufferView" in stderr, stderr
    assert "bad_alloc" not in stderr
    assert seconds < 30, seconds  # a bound on runaway work, far above the refusal's milliseconds


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("vertices", [10**6, 10**9])
def test_positions_without_data_are_refused(tmp_path, command, vertices):
    doc, blob = grid(4)
    # Every attribute as long as POSITION, all without data; the stored indices stay in range.
    doc = zero_data(doc, blob, 0, vertices)
    for accessor in (1, 2):
        doc = zero_data(doc, blob, accessor, vertices)
    path = write(tmp_path / "zeros.glb", glb_bytes(doc, blob))
    status, stderr, seconds = run_limited(COMMANDS[command](path))
    assert status == REFUSED[command], stderr
    assert "zeros.glb" in stderr and "has no bufferView" in stderr, stderr


def test_a_sparse_morph_target_as_long_as_its_positions_still_bakes(tmp_path):
    doc, blob = grid(64)  # 4,096 vertices
    count = 64 * 64
    # Target 0 moves vertex 5 by +z: two sparse arrays after the grid's data.
    sparse_indices = struct.pack("<I", 5)
    sparse_values = struct.pack("<3f", 0, 0, 0.5)
    view = len(doc["bufferViews"])
    doc["bufferViews"] += [{"buffer": 0, "byteOffset": len(blob), "byteLength": 4},
                           {"buffer": 0, "byteOffset": len(blob) + 4, "byteLength": 12}]
    blob += sparse_indices + sparse_values
    doc["buffers"][0]["byteLength"] = len(blob)
    target = len(doc["accessors"])
    doc["accessors"].append({"componentType": 5126, "count": count, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0.5],
                             "sparse": {"count": 1, "indices": {"bufferView": view, "componentType": 5125},
                                        "values": {"bufferView": view + 1}}})
    doc["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": target}] * 8
    path = write(tmp_path / "morph.glb", glb_bytes(doc, blob))
    status, stderr, _ = run_limited(["bake", path, "-o", tmp_path / "out.glb"])
    assert status == 0, stderr
    for command in ("check", "info"):
        status, stderr, _ = run_limited([command, tmp_path / "out.glb"])
        assert status == 0, (command, stderr)


@pytest.mark.parametrize("command", COMMANDS)
def test_a_glb_header_claiming_600_mb_of_json_is_refused_before_reading(tmp_path, command):
    path = tmp_path / "claims.glb"
    size = 600 << 20
    with open(path, "wb") as f:
        f.write(struct.pack("<IIIII", 0x46546C67, 2, size, size - 20, 0x4E4F534A) + b"{")
        f.truncate(size)  # sparse: the claim is true to the file's length
    status, stderr, _ = run_limited(COMMANDS[command](path), memory_bytes=512 << 20)
    assert status == REFUSED[command], stderr
    assert "claims.glb" in stderr and "JSON chunk" in stderr and "limited to" in stderr, stderr
