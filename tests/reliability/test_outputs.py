# SPDX-License-Identifier: MIT
"""Nothing lost, nothing crashes: `tangent` on the trees, names and machines users have.

Output collisions, full disks (a small tmpfs in a private mount namespace), standard output
that cannot be written, an unusable TMPDIR, names that are not UTF-8 or carry terminal control
characters, stale temporaries, and `bake --recursive` interrupted by SIGINT and SIGKILL at
several points and run again. Each asserts exit codes, messages naming the file, that no
temporary or partial file remains, that inputs are unchanged and that earlier outputs stay
whole. Runs against the `tangent` of the build tree it is registered in (TANGENT_CLI), so the
sanitizer build runs it too."""
import base64
import hashlib
import json
import os
import pathlib
import shutil
import signal
import struct
import subprocess
import sys
import time
import xml.dom.minidom

import pytest

from conftest import skip_or_fail

CLI = os.environ["TANGENT_CLI"]
PNG = base64.b64decode(
    "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGP4//8/AAX+Av4N70a4AAAAAElFTkSuQmCC")


# --- assets -------------------------------------------------------------------------------

def grid(n, mesh_name="grid", generator="libtangent tests/reliability", extras=None, material=True):
    """An n x n vertex grid (a gently curved sheet) with NORMAL, TEXCOORD_0 and a normal-mapped
    material: (document, binary chunk)."""
    positions, normals, uvs, indices = [], [], [], []
    for j in range(n):
        for i in range(n):
            u, v = i / (n - 1), j / (n - 1)
            positions += [u, v, 0.1 * (u * u - v * v)]
            nx, ny = -0.2 * u, 0.2 * v
            length = (nx * nx + ny * ny + 1) ** 0.5
            normals += [nx / length, ny / length, 1 / length]
            uvs += [u, 1 - v]
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            indices += [a, a + 1, a + n + 1, a, a + n + 1, a + n]
    count = n * n
    blob = struct.pack(f"<{3 * count}f", *positions) + struct.pack(f"<{3 * count}f", *normals)
    blob += struct.pack(f"<{2 * count}f", *uvs) + struct.pack(f"<{len(indices)}I", *indices)
    primitive = {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "mode": 4}
    doc = {
        "asset": {"version": "2.0", "generator": generator},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"name": mesh_name, "primitives": [primitive]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3",
             "min": [0, 0, -0.1], "max": [1, 1, 0.1]},
            {"bufferView": 1, "componentType": 5126, "count": count, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": count, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 12 * count},
            {"buffer": 0, "byteOffset": 12 * count, "byteLength": 12 * count},
            {"buffer": 0, "byteOffset": 24 * count, "byteLength": 8 * count},
            {"buffer": 0, "byteOffset": 32 * count, "byteLength": 4 * len(indices)},
        ],
        "buffers": [{"byteLength": len(blob)}],
    }
    if material:
        primitive["material"] = 0
        doc["materials"] = [{"normalTexture": {"index": 0}}]
        doc["textures"] = [{"source": 0}]
        doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(PNG).decode(), "mimeType": "image/png"}]
    if extras is not None:
        doc["asset"]["extras"] = extras
    return doc, blob


def glb_bytes(doc, blob):
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(blob), 0x004E4942) + blob
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def gltf_bytes(doc, blob):
    """A .gltf with its buffer as a data: URI (one file)."""
    doc = json.loads(json.dumps(doc))
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(blob).decode()
    return json.dumps(doc).encode()


def write(path, data):
    path = pathlib.Path(os.fsdecode(path))  # bytes: a name that is not UTF-8, kept byte for byte
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)
    return path


# --- checks -------------------------------------------------------------------------------

def tangent(*args, env=None, stdout=subprocess.PIPE, timeout=300):
    done = subprocess.run([CLI, *map(os.fsdecode, args)], stdout=stdout, stderr=subprocess.PIPE, env=env, timeout=timeout)
    assert done.returncode >= 0, f"killed by signal {-done.returncode}: {done.stderr[-2000:]!r}"
    assert b"AddressSanitizer" not in done.stderr and b"runtime error:" not in done.stderr, done.stderr[-4000:]
    return done


def snapshot(folder):
    folder = pathlib.Path(folder)
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def temporaries(folder):
    return sorted(p.name for p in pathlib.Path(folder).rglob("*") if ".tmp-" in p.name or p.name.startswith("tangent-bake-"))


def assert_valid_glb(path):
    data = pathlib.Path(os.fsdecode(path)).read_bytes()
    magic, version, length = struct.unpack_from("<III", data, 0)
    assert (magic, version, length) == (0x46546C67, 2, len(data)), path
    json_length, kind = struct.unpack_from("<II", data, 12)
    assert kind == 0x4E4F534A
    doc = json.loads(data[20:20 + json_length])
    assert any("TANGENT" in p["attributes"] for m in doc["meshes"] for p in m["primitives"]), path
    return doc


def assert_gltf_pair_loads(path):
    """The .gltf parses and its .bin is there with the byteLength it declares."""
    path = pathlib.Path(path)
    doc = json.loads(path.read_bytes())
    for buffer in doc.get("buffers", []):
        if "uri" in buffer:
            assert (path.parent / buffer["uri"]).stat().st_size == buffer["byteLength"], buffer
    return doc


# --- output collisions --------------------------------------------------------------------

def test_two_inputs_of_one_name_into_one_folder_are_refused_before_anything_is_written(tmp_path):
    doc, blob = grid(4)
    a = write(tmp_path / "a" / "x.glb", glb_bytes(doc, blob))
    b = write(tmp_path / "b" / "x.glb", glb_bytes(doc, blob))
    (tmp_path / "out").mkdir()
    done = tangent("bake", a, b, "--out-dir", tmp_path / "out")
    assert done.returncode == 1
    assert str(a).encode() in done.stderr and str(b).encode() in done.stderr, done.stderr
    assert list((tmp_path / "out").iterdir()) == []


def test_several_inputs_never_write_over_another_inputs_buffer_even_one_baked_later(tmp_path):
    # y/a.gltf's output x/a.gltf would put its buffer in x/a.bin, the buffer of x/b.gltf, an
    # input baked after it. Before, x/a.bin was replaced (exit 1 only for x/b.gltf, its data gone).
    doc, blob = grid(4)
    write(tmp_path / "y" / "a.gltf", gltf_bytes(doc, blob))
    other = json.loads(json.dumps(doc))
    other["buffers"][0]["uri"] = "a.bin"
    write(tmp_path / "x" / "b.gltf", json.dumps(other).encode())
    write(tmp_path / "x" / "a.bin", blob)
    before = snapshot(tmp_path / "x")
    done = tangent("bake", tmp_path / "y" / "a.gltf", tmp_path / "x" / "b.gltf", "--out-dir", tmp_path / "x")
    assert done.returncode == 1, done.stderr  # x/b.gltf's own output would be itself
    after = snapshot(tmp_path / "x")
    assert {name: after[name] for name in before} == before, done.stderr
    written = assert_gltf_pair_loads(tmp_path / "x" / "a.gltf")
    assert written["buffers"][0]["uri"] == "a.1.bin"
    assert tangent("info", tmp_path / "x" / "b.gltf").returncode == 0


def test_two_inputs_with_different_images_of_one_name_never_share_one_copy(tmp_path):
    # a/m.gltf and b/k.gltf each use their own n.png; both baked into one folder, k's copy would
    # replace m's (m then showed k's texture, exit 0). The second is refused and m's copy stays;
    # an input whose n.png has the same bytes bakes.
    doc, blob = grid(4)
    document = gltf_bytes(with_external_image(doc, uri="n.png"), blob)
    inputs = []
    for folder, name, image in (("a", "m", PNG), ("b", "k", PNG + b"another image"), ("c", "s", PNG)):
        inputs.append(write(tmp_path / "in" / folder / f"{name}.gltf", document))
        write(tmp_path / "in" / folder / "n.png", image)
    done = tangent("bake", *inputs, "--out-dir", tmp_path / "out")
    assert done.returncode == 1, done.stderr
    assert b"out/n.png: bake would copy" in done.stderr and b"in/b/n.png" in done.stderr, done.stderr
    assert (tmp_path / "out" / "n.png").read_bytes() == PNG
    assert not (tmp_path / "out" / "k.gltf").exists()
    assert (tmp_path / "out" / "m.gltf").exists() and (tmp_path / "out" / "s.gltf").exists()
    assert temporaries(tmp_path / "out") == []


def test_a_tree_never_writes_over_a_file_another_input_uses(tmp_path):
    # in/b.gltf (allowed by --asset-root) reads out/a.bin, where in/a.gltf's output would put
    # its buffer: that one gets another name and out/a.bin stays as it was.
    doc, blob = grid(4)
    write(tmp_path / "in" / "a.gltf", gltf_bytes(doc, blob))
    other = json.loads(json.dumps(doc))
    other["buffers"][0]["uri"] = "../out/a.bin"
    write(tmp_path / "in" / "b.gltf", json.dumps(other).encode())
    write(tmp_path / "out" / "a.bin", blob)
    done = tangent("bake", tmp_path / "in", "--recursive", "--out-dir", tmp_path / "out", "--asset-root", tmp_path)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "out" / "a.bin").read_bytes() == blob
    assert assert_gltf_pair_loads(tmp_path / "out" / "a.gltf")["buffers"][0]["uri"] == "a.1.bin"
    assert_gltf_pair_loads(tmp_path / "out" / "b.gltf")
    assert tangent("info", tmp_path / "in" / "b.gltf", "--asset-root", tmp_path).returncode == 0


def test_an_output_folder_that_cannot_be_made_is_named(tmp_path):
    # A file stands where the output's folder would be made: the message names that folder
    # and why, not the temporary file that could not be opened after it.
    doc, blob = grid(4)
    asset = write(tmp_path / "in.glb", glb_bytes(doc, blob))
    write(tmp_path / "out" / "taken", b"a file")
    done = tangent("bake", asset, "-o", tmp_path / "out" / "taken" / "sub" / "x.glb")
    assert done.returncode != 0
    assert f"{tmp_path / 'out' / 'taken' / 'sub'}: cannot create the output's folder".encode() in done.stderr, done.stderr
    assert snapshot(tmp_path / "out") == {"taken": hashlib.sha256(b"a file").hexdigest()}


@pytest.mark.parametrize("command", ["check", "bake"])
def test_a_report_is_never_written_over_an_input_a_file_it_uses_or_an_output(tmp_path, command):
    # `check x.glb -o x.glb` and `bake ... --report cube.bin` replaced the input (or its buffer,
    # or its texture, or the bake's own output) with the report, exit 0.
    doc, blob = grid(4)
    document = json.loads(json.dumps(with_external_image(doc, uri="n.png")))
    document["buffers"][0]["uri"] = "in.bin"
    write(tmp_path / "in.gltf", json.dumps(document).encode())
    write(tmp_path / "in.bin", blob)
    write(tmp_path / "n.png", PNG)
    before = snapshot(tmp_path)
    targets = ["in.gltf", "in.bin", "n.png"] + (["out.glb"] if command == "bake" else [])
    for target in targets:
        if command == "check":
            done = tangent("check", tmp_path / "in.gltf", "--format", "json", "-o", tmp_path / target)
        else:
            done = tangent("bake", tmp_path / "in.gltf", "-o", tmp_path / "out.glb", "--report", tmp_path / target)
        assert done.returncode == 2, (target, done.stderr)
        assert b"never written over" in done.stderr and target.encode() in done.stderr, done.stderr
        assert snapshot(tmp_path) == before, target
    assert temporaries(tmp_path) == []


def test_recursive_inputs_that_become_one_glb_are_refused_with_no_manifest(tmp_path):
    doc, blob = grid(4)
    write(tmp_path / "in" / "m.glb", glb_bytes(doc, blob))
    write(tmp_path / "in" / "m.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n")
    write(tmp_path / "in" / "m.ply", b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
          b"property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
          b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    before = snapshot(tmp_path / "in")
    done = tangent("bake", tmp_path / "in", "--recursive", "--out-dir", tmp_path / "out")
    assert done.returncode == 1
    for name in (b"m.glb", b"m.obj", b"m.ply"):
        assert name in done.stderr, done.stderr
    assert not (tmp_path / "out").exists() or list((tmp_path / "out").rglob("*")) == []
    assert snapshot(tmp_path / "in") == before


def test_two_folders_of_one_name_are_refused(tmp_path):
    doc, blob = grid(4)
    write(tmp_path / "p" / "set" / "a.glb", glb_bytes(doc, blob))
    write(tmp_path / "q" / "set" / "a.glb", glb_bytes(doc, blob))
    done = tangent("bake", tmp_path / "p" / "set", tmp_path / "q" / "set", "--recursive", "--out-dir", tmp_path / "out")
    assert done.returncode == 1
    assert b"would both be written" in done.stderr
    assert not list((tmp_path / "out").rglob("*.glb")) if (tmp_path / "out").exists() else True


def test_two_folders_of_one_name_are_refused_even_when_their_files_differ(tmp_path):
    # p/set/a.glb and q/set/b.glb do not collide, but both trees went to out/set with one
    # manifest, each run replacing the other's records (no re-run ever resumed).
    doc, blob = grid(4)
    write(tmp_path / "p" / "set" / "a.glb", glb_bytes(doc, blob))
    write(tmp_path / "q" / "set" / "b.glb", glb_bytes(doc, blob))
    done = tangent("bake", tmp_path / "p" / "set", tmp_path / "q" / "set", "--recursive", "--out-dir", tmp_path / "out")
    assert done.returncode == 1, done.stderr
    assert b"would both be written" in done.stderr and b"one manifest" in done.stderr, done.stderr
    assert not (tmp_path / "out" / "set").exists()


# --- standard output and TMPDIR -------------------------------------------------------------

def test_output_to_a_full_device_fails(tmp_path):
    doc, blob = grid(4)
    asset = write(tmp_path / "a.glb", glb_bytes(doc, blob))
    with open("/dev/full", "wb") as full:
        for args in (("info", asset), ("info", asset, "--json"), ("check", asset, "--format", "json"),
                     ("bake", asset, "-o", "-"), ("bake", asset, "-o", tmp_path / "o.glb", "--report", "-")):
            done = tangent(*args, stdout=full)
            assert done.returncode != 0, args
            assert b"standard output" in done.stderr, (args, done.stderr)
    assert temporaries(tmp_path) == []


# (A read-only TMPDIR is left out: the tests run as root, for whom no folder is read-only.)
@pytest.mark.parametrize("tmpdir_kind", ["missing", "a file"])
def test_stdout_bake_with_an_unusable_tmpdir_says_so(tmp_path, tmpdir_kind):
    doc, blob = grid(4)
    asset = write(tmp_path / "a.glb", glb_bytes(doc, blob))
    tmpdir = tmp_path / "tmp"
    if tmpdir_kind == "a file":
        tmpdir.write_bytes(b"x")
    done = tangent("bake", asset, "-o", "-", env={**os.environ, "TMPDIR": str(tmpdir)})
    assert done.returncode == 1
    assert b"TMPDIR" in done.stderr and str(asset).encode() in done.stderr, done.stderr
    assert done.stdout == b""


# --- names that are not UTF-8, control characters --------------------------------------------

def test_file_names_that_are_not_utf8_reach_reports_as_valid_json(tmp_path):
    doc, blob = grid(4)
    folder = os.fsencode(tmp_path)
    asset = write(os.path.join(folder, b"n\xff.glb"), glb_bytes(doc, blob))
    report = tmp_path / "report.json"
    done = tangent("bake", asset, "-o", os.path.join(folder, b"o\xff.glb"), "--report", report)
    assert done.returncode == 0, done.stderr
    entries = json.loads(report.read_text(encoding="utf-8"))
    assert entries[0]["status"] == "ok" and entries[0]["input"].endswith("n\\xFF.glb")
    assert_valid_glb(os.path.join(folder, b"o\xff.glb"))
    for fmt in ("json", "sarif"):
        done = tangent("check", asset, "--format", fmt)
        assert done.returncode == 1  # the input has no TANGENT: a finding
        json.loads(done.stdout.decode("utf-8"))


def test_a_latin1_byte_in_the_asset_gives_valid_reports_in_every_format(tmp_path):
    doc, blob = grid(4, generator="GEN_MARK")
    data = glb_bytes(doc, blob).replace(b"GEN_MARK", b"gen\xc0\xe9_X")
    asset = write(tmp_path / "latin1.glb", data)
    for fmt in ("json", "sarif", "junit", "github", "text"):
        done = tangent("check", asset, "--format", fmt)
        assert done.returncode in (1, 2), (fmt, done.returncode, done.stderr)
        text = done.stdout.decode("utf-8")  # valid UTF-8, whatever the input held
        if fmt in ("json", "sarif"):
            json.loads(text)
        elif fmt == "junit":
            xml.dom.minidom.parseString(done.stdout)
        assert b"latin1.glb" in done.stdout + done.stderr
    done = tangent("bake", asset, "-o", tmp_path / "o.glb", "--report", tmp_path / "r.json")
    json.loads((tmp_path / "r.json").read_text(encoding="utf-8"))
    assert done.returncode in (0, 1)


def test_control_characters_from_names_never_reach_the_terminal(tmp_path):
    doc, blob = grid(4, mesh_name="m\x1b[2J\x1b]0;owned\x07\rX\x00Y")
    name = "e\x1b[31mvil\r.glb"
    asset = write(tmp_path / name, glb_bytes(doc, blob))
    runs = [("bake", asset, "-o", tmp_path / "o.glb"), ("info", asset), ("check", asset),
            ("check", asset, "--format", "github"), ("check", asset, "--format", "junit")]
    for args in runs:
        done = tangent(*args)
        for stream in (done.stdout, done.stderr):
            assert b"\x1b" not in stream and b"\r" not in stream and b"\x00" not in stream and b"\x07" not in stream, (
                args, stream)
        assert b"vil" in done.stdout + done.stderr


def test_a_newline_in_a_name_never_starts_a_line_of_its_own(tmp_path):
    # A file or mesh name with a newline would forge a line of the log ("FAKE ...") a reader
    # or a CI job takes for the tool's own.
    doc, blob = grid(4, mesh_name="m\nFAKE mesh ok")
    tree = tmp_path / "tree"
    tree.mkdir()
    asset = write(tree / "a\nFAKE ok.glb", glb_bytes(doc, blob))
    write(tree / "b\nFAKE error.glb", b"not a glb")
    # An OBJ's mesh takes the file's name: a check of its bake skips that mesh (no material), by name.
    obj = write(tmp_path / "c\nFAKE ok.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n")
    assert tangent("bake", obj, "-o", tmp_path / "obj.glb").returncode == 0
    runs = [("bake", asset, "-o", tmp_path / "o.glb"), ("info", asset), ("check", asset),
            ("check", asset, "--format", "github"), ("bake", tree, "--recursive", "--out-dir", tmp_path / "out"),
            ("check", tmp_path / "obj.glb")]
    for args in runs:
        done = tangent(*args)
        lines = (done.stdout + done.stderr).split(b"\n")
        assert not [line for line in lines if line.startswith(b"FAKE")], (args, lines)
        assert b"FAKE ok" in done.stdout + done.stderr, (args, lines)


def test_recursive_manifest_with_names_that_are_not_utf8_resumes(tmp_path):
    doc, blob = grid(4)
    folder = os.fsencode(tmp_path / "in")
    write(os.path.join(folder, b"caf\xe9.glb"), glb_bytes(doc, blob))
    write(os.path.join(folder, b"ok.glb"), glb_bytes(doc, blob))
    out = tmp_path / "out"
    done = tangent("bake", tmp_path / "in", "--recursive", "--out-dir", out)
    assert done.returncode == 0, done.stderr
    manifest = json.loads((out / "tangent-manifest.json").read_text(encoding="utf-8"))
    assert sorted(manifest["files"]) == ["caf\\xE9.glb", "ok.glb"]
    done = tangent("bake", tmp_path / "in", "--recursive", "--out-dir", out)
    assert done.returncode == 0
    assert done.stdout.count(b": unchanged") == 2, done.stdout


def test_double_dash_ends_the_options(tmp_path):
    doc, blob = grid(4)
    asset = write(tmp_path / "-dash.glb", glb_bytes(doc, blob))
    os.chdir(tmp_path)
    assert tangent("info", "--", "-dash.glb").returncode == 0
    assert tangent("check", "--allow-missing", "--", "-dash.glb").returncode == 0
    assert tangent("bake", "-o", "o.glb", "--", "-dash.glb").returncode == 0
    assert_valid_glb(tmp_path / "o.glb")
    assert tangent("info", "-dash.glb").returncode == 2  # without it: an unknown option


# --- temporaries --------------------------------------------------------------------------

def dead_pid():
    for pid in range(4_000_000, 3_000_000, -1):
        if not os.path.exists(f"/proc/{pid}"):
            return pid
    pytest.skip("no free process id found")


def test_stale_temporaries_of_dead_processes_are_removed_and_live_ones_kept(tmp_path):
    doc, blob = grid(4)
    asset = write(tmp_path / "a.glb", glb_bytes(doc, blob))
    out = tmp_path / "out"
    stale = write(out / f".o.glb.tmp-{dead_pid()}-0", b"half a file")
    live = write(out / f".o.glb.tmp-{os.getpid()}-0", b"being written by a running process")
    other = write(out / ".notes.tmp-abc", b"not of our pattern")
    assert tangent("bake", asset, "-o", out / "o.glb").returncode == 0
    assert not stale.exists()
    assert live.exists() and other.exists()


# --- full disks -----------------------------------------------------------------------------

def on_small_disk(tmp_path, script, size="1m"):
    """Runs `script` (sh) with $DISK a fresh tmpfs of `size`, in a private mount namespace (no
    mount outlives it); returns (exit status, output). Skips where mounting is not allowed."""
    disk = tmp_path / "disk"
    disk.mkdir()
    probe = subprocess.run(["unshare", "-m", "sh", "-c", f"mount -t tmpfs -o size=64k tmpfs '{disk}'"],
                           capture_output=True)
    if probe.returncode != 0:
        skip_or_fail("mounting a small tmpfs needs root and unshare: " + probe.stderr.decode(errors="replace").strip())
    full = f"mount -t tmpfs -o size={size} tmpfs \"$DISK\" && {script}"
    done = subprocess.run(["unshare", "-m", "sh", "-c", full], capture_output=True, timeout=300,
                          env={**os.environ, "DISK": str(disk), "T": CLI})
    return done.returncode, (done.stdout + done.stderr).decode(errors="replace")


# Fills the disk but for one page (tmpfs counts pages): a file grown until the disk is full,
# then cut by one page.
FILL_BUT_ONE_PAGE = ('(dd if=/dev/zero of="$DISK/filler" bs=4096 2>/dev/null || true) && '
                     'truncate -s -4096 "$DISK/filler"')


def test_a_full_disk_between_the_bin_and_the_gltf_leaves_the_previous_pair_whole(tmp_path):
    # 6 KB of extras: the .gltf needs two pages, its .bin (a 3x3 grid) one.
    doc, blob = grid(3, extras={"note": "x" * 6000}, material=False)
    asset = write(tmp_path / "in.gltf", gltf_bytes(doc, blob))
    script = f"""
      "$T" bake '{asset}' -o "$DISK/p.gltf" --all --quiet || exit 10
      mkdir "$DISK/before" && cp "$DISK"/p.* "$DISK/before/" || exit 11
      {FILL_BUT_ONE_PAGE}
      "$T" bake '{asset}' -o "$DISK/p.gltf" --all --method flat; echo "exit=$?"
      rm -f "$DISK/filler"
      for f in "$DISK"/before/*; do cmp "$f" "$DISK/$(basename "$f")" || echo "changed $f"; done
      ls -a "$DISK"
      cp -r "$DISK" '{tmp_path}/after'
    """
    status, output = on_small_disk(tmp_path, script)
    assert status == 0, output
    assert "exit=1" in output, output
    assert "No space left on device" in output and "p.gltf" in output, output
    assert "changed" not in output, output
    after = tmp_path / "after"
    assert sorted(p.name for p in after.iterdir() if p.is_file()) == ["p.bin", "p.gltf"], output
    assert_gltf_pair_loads(after / "p.gltf")


def test_a_full_disk_leaves_the_previous_glb_and_no_temporary(tmp_path):
    doc, blob = grid(24)
    asset = write(tmp_path / "in.glb", glb_bytes(doc, blob))
    script = f"""
      "$T" bake '{asset}' -o "$DISK/o.glb" --quiet || exit 10
      cp "$DISK/o.glb" "$DISK/o.before"
      {FILL_BUT_ONE_PAGE}
      "$T" bake '{asset}' -o "$DISK/o.glb" --method flat --report "$DISK/r.json"; echo "exit=$?"
      cmp "$DISK/o.glb" "$DISK/o.before" && echo same
      ls -a "$DISK"
    """
    status, output = on_small_disk(tmp_path, script)
    assert status == 0, output
    assert "exit=1" in output and "same" in output, output
    assert "No space left on device" in output and "o.glb" in output, output
    assert ".tmp-" not in output, output


def with_external_image(doc, uri="tex/n.png"):
    """The document with its image in a file beside it (`uri`) instead of a data: URI."""
    doc = json.loads(json.dumps(doc))
    doc["images"] = [{"uri": uri}]
    return doc


def keeping_images(suffix):
    """The options under which an output of `suffix` copies external images beside it (a .glb
    embeds them unless told to keep them external)."""
    return ["--keep-external"] if suffix == ".glb" else []


@pytest.mark.parametrize("suffix", [".glb", ".gltf"])
def test_a_full_disk_leaves_no_image_copy_or_folder_behind(tmp_path, suffix):
    # The image copy (one page) fits, the output after it does not: the failed bake takes the
    # copy and the folder it made for it away again.
    doc, blob = grid(24)
    asset = write(tmp_path / "in" / "in.gltf", gltf_bytes(with_external_image(doc), blob))
    write(tmp_path / "in" / "tex" / "n.png", PNG)
    keep = " ".join(keeping_images(suffix))
    script = f"""
      mkdir "$DISK/out" && echo kept > "$DISK/out/earlier.txt"
      {FILL_BUT_ONE_PAGE}
      "$T" bake '{asset}' -o "$DISK/out/o{suffix}" {keep}; echo "exit=$?"
      rm -f "$DISK/filler"
      cd "$DISK" && find . | sort
    """
    status, output = on_small_disk(tmp_path, script)
    assert status == 0, output
    assert "exit=1" in output, output
    assert "No space left on device" in output and ("o.glb" if suffix == ".glb" else "o.bin") in output, output
    listing = [line for line in output.splitlines() if line.startswith(".")]
    assert listing == [".", "./out", "./out/earlier.txt"], output


@pytest.mark.parametrize("suffix", [".glb", ".gltf"])
def test_a_full_disk_leaves_an_earlier_image_copy_as_it_was(tmp_path, suffix):
    # An earlier bake left its copy of the image beside the output, and the image has changed
    # since: the new copy (one page) fits, the output after it does not. The failed bake leaves
    # the earlier copy and output byte for byte: the copy is replaced only once the output is
    # written.
    doc, blob = grid(24)
    asset = write(tmp_path / "in" / "in.gltf", gltf_bytes(with_external_image(doc), blob))
    write(tmp_path / "in" / "tex" / "n.png", PNG)
    changed = write(tmp_path / "changed.png", PNG + b"\0" * 16)
    keep = " ".join(keeping_images(suffix))
    script = f"""
      "$T" bake '{asset}' -o "$DISK/out/o{suffix}" --quiet {keep} || exit 10
      cp '{changed}' '{asset.parent}/tex/n.png' && cp -r "$DISK/out" "$DISK/before" || exit 11
      {FILL_BUT_ONE_PAGE}
      "$T" bake '{asset}' -o "$DISK/out/o{suffix}" --method flat {keep}; echo "exit=$?"
      rm -f "$DISK/filler"
      cp -r "$DISK/out" '{tmp_path}/after' && cp -r "$DISK/before" '{tmp_path}/before'
    """
    status, output = on_small_disk(tmp_path, script)
    assert status == 0, output
    assert "exit=1" in output, output
    assert "No space left on device" in output, output
    before, after = snapshot(tmp_path / "before"), snapshot(tmp_path / "after")
    assert before.get("tex/n.png") == hashlib.sha256(PNG).hexdigest(), before
    assert after == before, output
    assert temporaries(tmp_path / "after") == [], output

    # With room, the same bake over the same folder replaces the copy.
    done = tangent("bake", asset, "-o", tmp_path / "after" / f"o{suffix}", "--quiet", *keeping_images(suffix))
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "after" / "tex" / "n.png").read_bytes() == changed.read_bytes()
    assert temporaries(tmp_path / "after") == []


def test_an_image_copy_that_would_replace_a_folder_is_refused_before_anything_is_written(tmp_path):
    doc, blob = grid(4)
    asset = write(tmp_path / "in" / "in.gltf", gltf_bytes(with_external_image(doc), blob))
    write(tmp_path / "in" / "tex" / "n.png", PNG)
    write(tmp_path / "out" / "tex" / "n.png" / "kept.txt", b"a folder where the copy would go")
    for suffix in (".glb", ".gltf"):
        done = tangent("bake", asset, "-o", tmp_path / "out" / f"o{suffix}", *keeping_images(suffix))
        assert done.returncode == 1, done.stderr
        kept = hashlib.sha256(b"a folder where the copy would go").hexdigest()
        assert snapshot(tmp_path / "out") == {"tex/n.png/kept.txt": kept}, done.stderr
        assert temporaries(tmp_path / "out") == []
        assert b"n.png: is a directory" in done.stderr, done.stderr


@pytest.mark.parametrize("suffix, taken", [(".glb", "o.glb"), (".gltf", "o.gltf"), (".gltf", "o.bin")])
def test_an_image_copy_that_would_go_where_the_output_is_written_is_refused(tmp_path, suffix, taken):
    # An image named as the output or its .bin: its copy would replace (or be replaced by) what
    # the bake writes. Before, o.bin held the PNG and the bake exited 0 with an unloadable output.
    doc, blob = grid(4)
    asset = write(tmp_path / "in" / "in.gltf", gltf_bytes(with_external_image(doc, uri=taken), blob))
    write(tmp_path / "in" / taken, PNG)
    (tmp_path / "out").mkdir()
    done = tangent("bake", asset, "-o", tmp_path / "out" / f"o{suffix}", *keeping_images(suffix))
    assert done.returncode == 1, done.stderr
    assert f"{taken}: the output is written there".encode() in done.stderr, done.stderr
    assert snapshot(tmp_path / "out") == {}, done.stderr
    assert temporaries(tmp_path / "out") == []


def test_a_batch_on_a_full_disk_names_the_file_and_keeps_earlier_outputs(tmp_path):
    # small.glb's output fits in the pages left, large.glb's does not: the batch goes on past
    # the failure, names it, and the outputs of an earlier run stay as they were.
    tree = tmp_path / "tree"
    small_doc, small_blob = grid(3)
    large_doc, large_blob = grid(40)
    write(tree / "large.gltf", gltf_bytes(with_external_image(large_doc), large_blob))
    write(tree / "tex" / "n.png", PNG)
    write(tree / "small.glb", glb_bytes(small_doc, small_blob))
    before = snapshot(tree)
    script = f"""
      "$T" bake '{tree}' --recursive --out-dir "$DISK/out" --quiet || exit 10
      cp -r "$DISK/out" '{tmp_path}/earlier'
      (dd if=/dev/zero of="$DISK/filler" bs=4096 2>/dev/null || true) && truncate -s -16384 "$DISK/filler"
      "$T" bake '{tree}' --recursive --out-dir "$DISK/out" --method flat; echo "exit=$?"
      rm -f "$DISK/filler"
      cp -r "$DISK/out" '{tmp_path}/after'
    """
    status, output = on_small_disk(tmp_path, script)
    assert status == 0, output
    assert "exit=1" in output, output
    failed = [line for line in output.splitlines() if line.startswith("error: ")]
    assert len(failed) == 1 and "No space left on device" in failed[0], output
    assert failed[0].startswith(f"error: {tree / 'large.gltf'}: "), output
    earlier, after = snapshot(tmp_path / "earlier"), snapshot(tmp_path / "after")
    assert temporaries(tmp_path / "after") == [], output
    # The failed file's earlier output (its .gltf, .bin and image copy) is untouched...
    assert {"large.gltf", "large.bin", "tex/n.png"} <= set(earlier), earlier
    for name in ("large.gltf", "large.bin", "tex/n.png"):
        assert after.get(name) == earlier[name], (name, output)
    assert not set(after) - set(earlier) - {"tangent-manifest.journal"}, (sorted(after), output)
    # ...and the file that fitted was baked again, with the other method.
    assert_valid_glb(tmp_path / "after" / "small.glb")
    assert after["small.glb"] != earlier["small.glb"], output
    assert snapshot(tree) == before


# --- images: carried through, never read to load --------------------------------------------

def peak_memory_kb(*args):
    """(exit status, peak resident memory in KiB) of one `tangent` run."""
    child = subprocess.Popen([CLI, *map(os.fsdecode, args)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(child.pid, 0)
    return os.waitstatus_to_exitcode(status), usage.ru_maxrss


def test_a_huge_texture_is_not_read_by_info_check_or_a_bake_beside_it(tmp_path):
    # A 1 GiB image file (sparse: no disk used): loading never reads image files, so info,
    # check and a bake into the same folder keeping it external (no copy to make) stay far
    # below its size. The
    # loader used to read each image whole and drop it.
    doc, blob = grid(8)
    asset = write(tmp_path / "in.gltf", gltf_bytes(with_external_image(doc), blob))
    image = tmp_path / "tex" / "n.png"
    image.parent.mkdir()
    with open(image, "wb") as f:
        f.truncate(1 << 30)
    assert tangent("bake", asset, "-o", tmp_path / "baked.gltf", "--quiet").returncode == 0
    limit_kb = 256 << 10
    for args in (["info", asset], ["check", tmp_path / "baked.gltf"], ["bake", asset, "-o", tmp_path / "o.glb", "--quiet", "--keep-external"]):
        status, peak = peak_memory_kb(*args)
        assert status == 0, args
        assert peak < limit_kb, (args, peak)


def test_embedded_images_survive_byte_for_byte_and_broken_ones_are_warnings(tmp_path):
    doc, blob = grid(6)  # its image: a data: URI
    uri = doc["images"][0]["uri"]
    # The same image in the GLB's buffer (a bufferView), a missing file and a data: URI
    # that is not base64: warnings (one per image, naming it), the URIs kept as they are.
    doc["images"] += [{"bufferView": 4, "mimeType": "image/png"}, {"uri": "missing.png"}, {"uri": "data:image/png,not-base64"}]
    doc["textures"] += [{"source": 1}, {"source": 2}, {"source": 3}]
    doc["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(PNG)})
    blob += PNG
    doc["buffers"][0]["byteLength"] = len(blob)
    asset = write(tmp_path / "in.glb", glb_bytes(doc, blob))
    done = tangent("bake", asset, "-o", tmp_path / "out" / "o.glb")
    assert done.returncode == 0, done.stderr
    warnings = [line for line in done.stderr.decode().splitlines() if line.startswith("warning: ")]
    assert len(warnings) == 2, done.stderr
    assert "/images/2 uri 'missing.png' names a file that does not exist" in warnings[0], warnings
    assert "/images/3 uri: data: URI is not base64" in warnings[1], warnings
    out = assert_valid_glb(tmp_path / "out" / "o.glb")
    data = (tmp_path / "out" / "o.glb").read_bytes()
    json_length = struct.unpack_from("<I", data, 12)[0]
    bin_chunk = data[28 + json_length:]
    # The data: URI image is embedded too (a .glb is one file), its bytes as they were.
    for image in out["images"][:2]:
        view = out["bufferViews"][image["bufferView"]]
        assert bin_chunk[view.get("byteOffset", 0):view.get("byteOffset", 0) + view["byteLength"]] == PNG
        assert image["mimeType"] == "image/png"
    assert [image.get("uri") for image in out["images"]] == [None, None, "missing.png", "data:image/png,not-base64"]
    # --keep-external carries the data: URI through as it is.
    done = tangent("bake", asset, "-o", tmp_path / "out" / "kept.glb", "--keep-external")
    assert done.returncode == 0, done.stderr
    kept = assert_valid_glb(tmp_path / "out" / "kept.glb")
    assert [image.get("uri") for image in kept["images"]] == [uri, None, "missing.png", "data:image/png,not-base64"]


# --- interrupted batches ------------------------------------------------------------------

def finished_files(out):
    """The files recorded as done: in the journal (a run in progress or killed) and in the
    manifest (a run that ended or stopped)."""
    finished = set()
    journal = out / "tangent-manifest.journal"
    if journal.exists():
        for line in journal.read_bytes().split(b"\n")[1:]:
            try:
                finished.add(json.loads(line)["file"])
            except (ValueError, KeyError):
                pass  # the last line may be cut
    manifest = out / "tangent-manifest.json"
    if manifest.exists():
        finished |= {key for key, record in json.loads(manifest.read_text())["files"].items() if record["ok"]}
    return finished


def interrupt_after(tree, out, more, sig):
    """Starts a recursive bake and sends `sig` once `more` further files are recorded as done."""
    already = len(finished_files(out))
    process = subprocess.Popen([CLI, "bake", str(tree), "--recursive", "--out-dir", str(out)],
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 300
    while len(finished_files(out)) < already + more and process.poll() is None and time.monotonic() < deadline:
        time.sleep(0.005)
    process.send_signal(sig)
    _, stderr = process.communicate(timeout=120)
    return process.returncode, stderr


def test_recursive_bake_interrupted_by_sigint_and_sigkill_resumes_where_it_stopped(tmp_path):
    tree, out = tmp_path / "tree", tmp_path / "out"
    doc, blob = grid(90)
    for k in range(24):
        write(tree / f"part{k // 8}" / f"g{k:02}.glb", glb_bytes(doc, blob))
    before = snapshot(tree)
    finished = set()
    for sig, count in ((signal.SIGINT, 2), (signal.SIGKILL, 4), (signal.SIGTERM, 5), (signal.SIGKILL, 3)):
        status, stderr = interrupt_after(tree, out, count, sig)
        print(f"{sig.name} after {count} more files: exit {status}, {len(finished_files(out))} finished")
        if status == 0:
            break  # it finished first: nothing left to interrupt
        if sig == signal.SIGKILL:
            assert status == -sig, (sig, status, stderr)
        else:
            # SIGINT and SIGTERM: the current file is finished, the manifest written, exit 130.
            assert status == 130, (sig, status, stderr)
            assert b"stopped after" in stderr and b"stopping after the current file" in stderr, stderr
            assert temporaries(out) == []
            assert not (out / "tangent-manifest.journal").exists()
        now = finished_files(out)
        assert finished <= now
        finished = now
        for glb in out.rglob("*.glb"):
            assert_valid_glb(glb)  # every output in place is whole
    assert finished, "no file finished before the interruptions"
    done = tangent("bake", tree, "--recursive", "--out-dir", out)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.decode().splitlines()
    for key in finished:
        assert any(f"/{key} -> " in line and line.endswith(": unchanged") for line in lines), (key, lines)
    baked = sum(line.endswith(": baked") for line in lines)
    assert baked == 24 - len(finished), lines
    assert temporaries(out) == []  # SIGKILL's leftovers removed by the next run
    assert not (out / "tangent-manifest.journal").exists()
    manifest = json.loads((out / "tangent-manifest.json").read_text())
    assert len(manifest["files"]) == 24 and all(r["ok"] for r in manifest["files"].values())
    for glb in out.rglob("*.glb"):
        assert_valid_glb(glb)
    assert snapshot(tree) == before


def test_a_second_ctrl_c_stops_at_once(tmp_path):
    tree, out = tmp_path / "tree", tmp_path / "out"
    doc, blob = grid(250)
    for k in range(6):
        write(tree / f"g{k}.glb", glb_bytes(doc, blob))
    process = subprocess.Popen([CLI, "bake", str(tree), "--recursive", "--out-dir", str(out)],
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    while not finished_files(out) and process.poll() is None:
        time.sleep(0.002)
    process.send_signal(signal.SIGINT)
    notice = process.stderr.readline()  # the first signal handled: the second comes mid-file
    assert b"stopping after the current file" in notice, notice
    process.send_signal(signal.SIGINT)
    stderr = notice + process.stderr.read()
    process.wait(timeout=120)
    assert process.returncode == -signal.SIGINT, (process.returncode, stderr)
    assert b"files being written were removed" in stderr
    assert temporaries(out) == []


# --- batch outcomes, progress, the size-and-time shortcut -------------------------------------

def test_batch_lines_say_baked_kept_unchanged_and_failed_as_the_report_does(tmp_path):
    tree, out = tmp_path / "tree", tmp_path / "out"
    doc, blob = grid(6)
    write(tree / "plain.glb", glb_bytes(doc, blob))
    write(tree / "broken.gltf", b'{"asset": ')
    # Baked once already: its tangents are kept.
    write(tmp_path / "plain.glb", glb_bytes(doc, blob))
    assert tangent("bake", tmp_path / "plain.glb", "-o", tree / "done.glb").returncode == 0
    done = tangent("bake", tree, "--recursive", "--out-dir", out, "--report", tmp_path / "r.json")
    assert done.returncode == 1
    lines = done.stdout.decode().splitlines()
    report = {pathlib.Path(e["input"]).name: e for e in json.loads((tmp_path / "r.json").read_text())}
    assert report["plain.glb"]["outcome"] == "baked" and report["done.glb"]["outcome"] == "kept"
    assert report["broken.gltf"]["outcome"] == "failed"
    for name, entry in report.items():
        if entry["outcome"] != "failed":
            assert any(name in line and line.endswith(": " + entry["outcome"]) for line in lines), (name, lines)
    assert "1 baked, 1 kept, 0 unchanged, 1 failed" in lines
    done = tangent("bake", tree, "--recursive", "--out-dir", out)
    assert "0 baked, 0 kept, 2 unchanged, 1 failed" in done.stdout.decode().splitlines()


def test_progress_line_on_a_terminal_only(tmp_path):
    tree, out = tmp_path / "tree", tmp_path / "out"
    doc, blob = grid(6)
    for k in range(3):
        write(tree / f"g{k}.glb", glb_bytes(doc, blob))
    # On a pipe: no progress line, no cursor movement.
    done = tangent("bake", tree, "--recursive", "--out-dir", out)
    assert b"\r" not in done.stderr and b"[1/3]" not in done.stderr + done.stdout
    # On a terminal (script(1) gives the command a pty): "[done/total] file" lines, cleared.
    if shutil.which("script") is None:
        skip_or_fail("script(1) from util-linux is not installed")
    command = f"'{CLI}' bake '{tree}' --recursive --out-dir '{tmp_path / 'out2'}'"
    shown = subprocess.run(["script", "-qec", command, "/dev/null"], capture_output=True, timeout=120)
    assert shown.returncode == 0, shown.stdout
    assert b"[0/3] g0.glb" in shown.stdout and b"[2/3] g2.glb" in shown.stdout, shown.stdout
    assert b"left" in shown.stdout and b"\r\x1b[K" in shown.stdout
    done = subprocess.run(["script", "-qec", command + " --quiet", "/dev/null"], capture_output=True, timeout=120)
    assert b"[0/3]" not in done.stdout


def test_unchanged_size_and_time_skip_hashing_and_verify_hashes(tmp_path):
    tree, out = tmp_path / "tree", tmp_path / "out"
    doc, blob = grid(6)
    asset = write(tree / "a.glb", glb_bytes(doc, blob))
    assert tangent("bake", tree, "--recursive", "--out-dir", out).returncode == 0
    stamps = json.loads((out / "tangent-manifest.json").read_text())["files"]["a.glb"]["stamps"]
    assert stamps[0]["size"] == asset.stat().st_size and stamps[0]["mtimeNs"] == asset.stat().st_mtime_ns
    # Same size, same modification time, other bytes (as no editor would leave it): taken as
    # unchanged without reading it...
    times = (asset.stat().st_atime_ns, asset.stat().st_mtime_ns)
    asset.write_bytes(asset.read_bytes().replace(b"tests/reliability", b"tests/reliabilitY"))
    os.utime(asset, ns=times)
    done = tangent("bake", tree, "--recursive", "--out-dir", out)
    assert done.stdout.decode().splitlines()[0].endswith(": unchanged"), done.stdout
    # ...and --verify reads every byte, so it sees the change.
    done = tangent("bake", tree, "--recursive", "--out-dir", out, "--verify")
    assert done.stdout.decode().splitlines()[0].endswith(": baked"), done.stdout
    # A new modification time: hashed again (same bytes now: unchanged).
    os.utime(asset, ns=(times[0], times[1] + 10**9))
    done = tangent("bake", tree, "--recursive", "--out-dir", out)
    assert done.stdout.decode().splitlines()[0].endswith(": unchanged"), done.stdout
    new_stamps = json.loads((out / "tangent-manifest.json").read_text())["files"]["a.glb"]["stamps"]
    assert new_stamps[0]["mtimeNs"] == times[1] + 10**9


@pytest.mark.parametrize("change", [["--tangent-format", "short"], ["--normals", "smooth"],
                                    ["--normals", "smooth", "--crease-angle", "10"], ["--method", "lengyel"]])
def test_a_tree_is_baked_again_when_an_option_that_changes_the_output_changes(tmp_path, change):
    # --tangent-format, --normals and --crease-angle were not in the manifest's options: a re-run
    # with any of them said "unchanged" and kept outputs made with the old ones.
    tree, out = tmp_path / "tree", tmp_path / "out"
    doc, blob = grid(6)
    del doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"]  # --normals decides them
    write(tree / "a.glb", glb_bytes(doc, blob))
    base = ["--normals", "smooth"] if change[-1] == "10" else []
    assert tangent("bake", tree, "--recursive", "--out-dir", out, *base).returncode == 0
    again = tangent("bake", tree, "--recursive", "--out-dir", out, *base)
    assert again.stdout.decode().splitlines()[0].endswith(": unchanged"), again.stdout
    done = tangent("bake", tree, "--recursive", "--out-dir", out, *change)
    assert done.returncode == 0, done.stderr
    assert done.stdout.decode().splitlines()[0].endswith(": baked"), done.stdout


def test_an_out_dir_inside_the_tree_keeps_the_assets_already_there(tmp_path):
    # `bake in --recursive --out-dir in/a` left in/a out of the inputs and then wrote in/x.glb's
    # output over the user's in/a/x.glb, exit 0. Now that asset is kept like an input (the
    # input whose output would replace it fails, naming it); the run's own outputs are rewritten
    # on later runs as usual.
    doc, blob = grid(5)
    write(tmp_path / "in" / "x.glb", glb_bytes(doc, blob))
    write(tmp_path / "in" / "y.glb", glb_bytes(doc, blob))
    users = write(tmp_path / "in" / "a" / "x.glb", glb_bytes(grid(4)[0], grid(4)[1])).read_bytes()
    done = tangent("bake", tmp_path / "in", "--recursive", "--out-dir", tmp_path / "in" / "a")
    assert done.returncode == 1, done.stderr
    assert b"a/x.glb: is a file that an input of this run uses" in done.stderr, done.stderr
    assert (tmp_path / "in" / "a" / "x.glb").read_bytes() == users
    assert_valid_glb(tmp_path / "in" / "a" / "y.glb")
    # y's output is the run's own: baked again when y changes.
    write(tmp_path / "in" / "y.glb", glb_bytes(grid(6)[0], grid(6)[1]))
    done = tangent("bake", tmp_path / "in", "--recursive", "--out-dir", tmp_path / "in" / "a")
    assert b"y.glb -> " in done.stdout and b": baked" in done.stdout, done.stdout
    assert (tmp_path / "in" / "a" / "x.glb").read_bytes() == users


@pytest.mark.parametrize("bad", [5, None, [1]])
def test_a_manifest_record_of_the_wrong_shape_is_forgotten_not_fatal(tmp_path, bad):
    # A record whose digest was 5 stopped the run after the files before it (later inputs neither
    # baked nor listed); null failed that input on every re-run with a bare json type_error.
    tree, out = tmp_path / "tree", tmp_path / "out"
    doc, blob = grid(4)
    for name in ("a", "b", "c"):
        write(tree / f"{name}.glb", glb_bytes(doc, blob))
    assert tangent("bake", tree, "--recursive", "--out-dir", out).returncode == 0
    manifest = json.loads((out / "tangent-manifest.json").read_text())
    if isinstance(bad, list):
        manifest["files"]["b.glb"] = bad
    else:
        manifest["files"]["b.glb"]["digest"] = bad
    (out / "tangent-manifest.json").write_text(json.dumps(manifest))
    done = tangent("bake", tree, "--recursive", "--out-dir", out)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.decode().splitlines()
    assert [line.rsplit(": ", 1)[1] for line in lines[:3]] == ["unchanged", "baked", "unchanged"], lines
    again = tangent("bake", tree, "--recursive", "--out-dir", out)
    assert [line.rsplit(": ", 1)[1] for line in again.stdout.decode().splitlines()[:3]] == ["unchanged"] * 3


def test_check_config_that_is_not_a_regular_file_is_refused(tmp_path):
    # --config /dev/zero read without end (std::bad_alloc); a FIFO waited forever.
    doc, blob = grid(4)
    asset = write(tmp_path / "a.glb", glb_bytes(doc, blob))
    fifo = tmp_path / "config.fifo"
    os.mkfifo(fifo)
    for config in ("/dev/zero", fifo):
        done = tangent("check", asset, "--config", config, timeout=30)
        assert done.returncode == 2, done.stderr
        assert b"the check configuration is not a regular file" in done.stderr, done.stderr


@pytest.mark.parametrize("deleted", ["a.bin", "tex/n.png"])
def test_a_tree_bakes_again_when_a_file_its_last_bake_wrote_is_gone(tmp_path, deleted):
    # Only the output .gltf itself was looked for: with its .bin or an image copy deleted the
    # re-run said "unchanged" (even with --verify) and left an output that no longer loads.
    tree, out = tmp_path / "tree", tmp_path / "out"
    doc, blob = grid(4)
    document = json.loads(json.dumps(with_external_image(doc)))
    document["buffers"][0]["uri"] = "a_in.bin"
    write(tree / "a.gltf", json.dumps(document).encode())
    write(tree / "a_in.bin", blob)
    write(tree / "tex" / "n.png", PNG)
    assert tangent("bake", tree, "--recursive", "--out-dir", out).returncode == 0
    (out / deleted).unlink()
    done = tangent("bake", tree, "--recursive", "--out-dir", out)
    assert done.returncode == 0, done.stderr
    assert done.stdout.decode().splitlines()[0].endswith(": baked"), done.stdout
    assert_gltf_pair_loads(out / "a.gltf")
    assert (out / "tex" / "n.png").read_bytes() == PNG
    again = tangent("bake", tree, "--recursive", "--out-dir", out)
    assert again.stdout.decode().splitlines()[0].endswith(": unchanged"), again.stdout


def test_an_obj_material_library_is_never_opened(tmp_path):
    # OpenMesh opened whatever `mtllib` named (outside the asset's folder too) and a FIFO there
    # hung the bake; OBJ materials are not used. Opening this FIFO for reading would block.
    os.mkfifo(tmp_path / "m.mtl")
    write(tmp_path / "t.obj", b"mtllib m.mtl\nmtllib ../outside.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\n"
                              b"vt 0 0\nvt 1 0\nvt 1 1\nusemtl x\nf 1/1 2/2 3/3\n")
    done = tangent("bake", tmp_path / "t.obj", "-o", tmp_path / "t.glb", timeout=60)
    assert done.returncode == 0, done.stderr
    assert_valid_glb(tmp_path / "t.glb")
