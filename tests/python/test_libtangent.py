# SPDX-License-Identifier: MIT
"""The Python module against the C++ library and the `tangent` command (python/module.cpp).

Run by CTest (python.pytest) with PYTHONPATH at build/python and TANGENT_CLI,
TANGENT_ARRAYS_TOOL and TANGENT_SOURCE_DIR set."""
import json
import math
import os
import pathlib
import shutil
import subprocess
import threading
import time

import numpy as np
import pytest

import libtangent
from conftest import skip_or_fail

CLI = os.environ["TANGENT_CLI"]
ARRAYS_TOOL = os.environ["TANGENT_ARRAYS_TOOL"]
SOURCE = pathlib.Path(os.environ["TANGENT_SOURCE_DIR"])
DEMO = SOURCE / "data" / "demo"


def uv_sphere(columns, rows):
    """A UV sphere with a seam (duplicated vertices at u = 0 and 1) and poles."""
    u = np.linspace(0.0, 1.0, columns + 1, dtype=np.float64)
    v = np.linspace(0.0, 1.0, rows + 1, dtype=np.float64)
    uu, vv = np.meshgrid(u, v)
    theta, phi = uu * 2 * np.pi, vv * np.pi
    normals = np.stack([np.sin(phi) * np.cos(theta), np.cos(phi), np.sin(phi) * np.sin(theta)], axis=-1).reshape(-1, 3)
    positions = normals * 2.0
    uvs = np.stack([uu, vv], axis=-1).reshape(-1, 2)
    quads = []
    for r in range(rows):
        for c in range(columns):
            a, b = r * (columns + 1) + c, r * (columns + 1) + c + 1
            d, e = a + columns + 1, b + columns + 1
            quads += [[a, d, b], [b, d, e]]
    return (positions.astype(np.float32), normals.astype(np.float32), uvs.astype(np.float32),
            np.asarray(quads, dtype=np.uint32))


def mirrored_soup(seed):
    """Random triangles over shared vertices, some UV islands mirrored, some degenerate."""
    rng = np.random.default_rng(seed)
    n = 60
    positions = rng.normal(size=(n, 3)).astype(np.float32)
    normals = rng.normal(size=(n, 3))
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    uvs = rng.uniform(-1, 1, size=(n, 2)).astype(np.float32)
    uvs[n // 2:, 0] *= -1  # a mirrored half
    indices = rng.integers(0, n, size=(150, 3)).astype(np.uint32)
    indices[:5, 2] = indices[:5, 1]  # coincident corners
    return positions, normals.astype(np.float32), uvs, indices


def run_cpp(tmp_path, arrays, method, uv_origin, weighting="angle"):
    positions, normals, uvs, indices = arrays
    for name, values in (("positions.f32", positions), ("normals.f32", normals), ("uvs.f32", uvs), ("indices.u32", indices)):
        np.ascontiguousarray(values).tofile(tmp_path / name)
    subprocess.run([ARRAYS_TOOL, str(tmp_path), method, uv_origin, weighting], check=True)
    return (np.fromfile(tmp_path / "tangents.f32", dtype=np.float32).reshape(-1, 4),
            np.fromfile(tmp_path / "corner_vertex.u32", dtype=np.uint32))


@pytest.mark.parametrize("method", ["mikktspace", "lengyel", "lengyel:area", "lengyel:uniform", "flat", "meshopt"])
@pytest.mark.parametrize("uv_origin", ["top-left", "bottom-left"])
@pytest.mark.parametrize("mesh", ["sphere", "soup1", "soup2"])
def test_bit_identical_to_the_cpp_library(tmp_path, method, uv_origin, mesh):
    method, _, weighting = method.partition(":")
    weighting = weighting or "angle"
    arrays = uv_sphere(24, 12) if mesh == "sphere" else mirrored_soup(int(mesh[-1]))
    expected_tangents, expected_vertex = run_cpp(tmp_path, arrays, method, uv_origin, weighting)
    result = libtangent.compute_tangents(*arrays, method=method, weighting=weighting, uv_origin=uv_origin)
    assert result["tangents"].dtype == np.float32 and result["tangents"].shape == (arrays[3].size, 4)
    assert result["tangents"].tobytes() == expected_tangents.tobytes()
    assert result["corner_vertex"].tobytes() == expected_vertex.tobytes()
    assert result["report"]["method"] == method
    # The same bits for any thread count, and from flat or float64 input.
    again = libtangent.compute_tangents(*(a.reshape(-1).astype(np.float64) if a.dtype == np.float32 else a.reshape(-1).astype(np.int64)
                                          for a in arrays), method=method, weighting=weighting, uv_origin=uv_origin, threads=2)
    assert again["tangents"].tobytes() == result["tangents"].tobytes()


def documented_split(indices, tangents, vertex_count):
    """The vertex split compute_tangents documents, worked out here from its tangents: corners of
    input vertex v with the tangent of v's first corner keep v; each other distinct tangent of v
    is a new vertex, numbered from vertex_count up in order of first corner. Tangents compare by
    value (-0 and +0 alike: adding +0 turns -0 into +0), then by bits."""
    keys = [tuple(row) for row in (tangents + np.float32(0)).view(np.uint32).reshape(-1, 4).tolist()]
    first_key, new_vertex, corner_vertex = {}, {}, []
    for corner, vertex in enumerate(indices.ravel().tolist()):
        key = keys[corner]
        first_key.setdefault(vertex, key)
        if key == first_key[vertex]:
            corner_vertex.append(vertex)
        else:
            corner_vertex.append(new_vertex.setdefault((vertex, key), vertex_count + len(new_vertex)))
    return corner_vertex, len(new_vertex)


def test_report_and_vertex_split():
    arrays = uv_sphere(24, 12)
    result = libtangent.compute_tangents(*arrays)
    report = result["report"]
    assert report["method"] == "mikktspace" and report["triangles"] == 24 * 12 * 2
    assert report["corners"] == 3 * report["triangles"]
    # The sphere needs no split: smooth normals, one UV per vertex (the seam has its own
    # vertices) and no mirrored UVs, so every corner of a vertex gets that vertex's one frame;
    # the corners of the collapsed pole triangles take their vertex's frame too. Every corner
    # keeps its input vertex.
    assert report["splitVertices"] == 0
    assert result["corner_vertex"].tolist() == arrays[3].ravel().tolist()
    assert np.allclose(np.linalg.norm(result["tangents"][:, :3], axis=1), 1.0, atol=1e-6)
    assert set(np.unique(result["tangents"][:, 3])) <= {-1.0, 1.0}
    # A soup with a mirrored half does split: the whole numbering against the documented rule.
    soup = mirrored_soup(1)
    split = libtangent.compute_tangents(*soup)
    expected, extra = documented_split(soup[3], split["tangents"], len(soup[0]))
    assert extra > 0 and split["report"]["splitVertices"] == extra
    assert split["corner_vertex"].tolist() == expected


def test_calls_keep_their_workspace_until_released():
    arrays = uv_sphere(96, 48)
    libtangent.release_cached_workspaces()
    assert libtangent.cached_workspace_bytes() == 0
    first = libtangent.compute_tangents(*arrays, threads=1)
    held = libtangent.cached_workspace_bytes()
    assert held > 3 * 96 * 48 * 2 * 16  # the per-corner scratch stays for the next call
    again = libtangent.compute_tangents(*arrays, threads=1)
    assert libtangent.cached_workspace_bytes() == held
    assert first["tangents"].tobytes() == again["tangents"].tobytes()
    libtangent.release_cached_workspaces()
    assert libtangent.cached_workspace_bytes() == 0
    assert libtangent.compute_tangents(*arrays, threads=1)["tangents"].tobytes() == first["tangents"].tobytes()


def cli_bake_report(tmp_path, source, output):
    report = tmp_path / "report.json"
    subprocess.run([CLI, "bake", str(source), "-o", str(output), "--report", str(report), "--quiet"], check=True)
    return json.loads(report.read_text())[0]


@pytest.mark.parametrize("name", ["demo.gltf", "scene.gltf", "torus.gltf"])
def test_bake_report_and_bytes_equal_the_cli(tmp_path, name):
    output = tmp_path / "out.glb"
    expected = cli_bake_report(tmp_path, DEMO / name, output)
    cli_bytes = output.read_bytes()
    output.unlink()
    result = libtangent.bake(DEMO / name, output)
    assert result == expected
    assert output.read_bytes() == cli_bytes


def write_bent_strip_obj(path):
    """A gently curved strip with a fold of about 29 degrees along its middle, with UVs and no
    normals: bake generates them (smooth ones keep the fold sharp only below a 29-degree crease)."""
    rows = []
    for i in range(5):
        for j, z in ((0, 0.0), (1, 0.1), (2, 0.8)):
            rows.append(f"v {i} {j} {z + 0.08 * i * i}")
    for i in range(5):
        for j in range(3):
            rows.append(f"vt {i / 4} {j / 2}")
    for i in range(4):
        for j in range(2):
            a, b, c, d = 3 * i + j + 1, 3 * (i + 1) + j + 1, 3 * (i + 1) + j + 2, 3 * i + j + 2
            rows.append(f"f {a}/{a} {b}/{b} {c}/{c}")
            rows.append(f"f {a}/{a} {c}/{c} {d}/{d}")
    path.write_text("\n".join(rows) + "\n")
    return path


def test_normals_and_crease_angle_give_the_cli_bytes(tmp_path):
    source = write_bent_strip_obj(tmp_path / "strip.obj")
    outputs = {}
    for normals, crease in (("flat", 60.0), ("smooth", 60.0), ("smooth", 20.0)):
        cli = tmp_path / f"cli-{normals}-{crease:.0f}.glb"
        subprocess.run([CLI, "bake", str(source), "-o", str(cli), "--normals", normals, "--crease-angle", f"{crease:g}",
                        "--quiet"], check=True)
        ours = tmp_path / f"py-{normals}-{crease:.0f}.glb"
        libtangent.bake(source, ours, normals=normals, crease_angle=crease)
        assert ours.read_bytes() == cli.read_bytes(), (normals, crease)
        outputs[(normals, crease)] = ours.read_bytes()
    # The options reach the bake: flat, smooth and smooth with a crease under the fold differ.
    assert len(set(outputs.values())) == 3
    with pytest.raises(ValueError, match="normals"):
        libtangent.bake(source, tmp_path / "x.glb", normals="soft")
    with pytest.raises(ValueError, match="crease_angle"):
        libtangent.bake(source, tmp_path / "x.glb", normals="smooth", crease_angle=200)


def test_keep_external_gives_the_cli_bytes_and_the_default_embeds(tmp_path):
    for keep in (False, True):
        cli, ours = tmp_path / f"cli-{keep}" / "out.glb", tmp_path / f"py-{keep}" / "out.glb"
        cli.parent.mkdir()
        ours.parent.mkdir()
        subprocess.run([CLI, "bake", str(DEMO / "demo.gltf"), "-o", str(cli), "--quiet", *(["--keep-external"] if keep else [])],
                       check=True)
        libtangent.bake(DEMO / "demo.gltf", ours, keep_external=keep)
        assert ours.read_bytes() == cli.read_bytes(), keep
        beside = sorted(p.name for p in ours.parent.iterdir() if p.name != "out.glb")
        assert beside == sorted(p.name for p in cli.parent.iterdir() if p.name != "out.glb")
        assert bool(beside) == keep  # embedded by default: nothing beside the .glb


def test_bake_tree_takes_the_cli_options_too(tmp_path):
    tree = tmp_path / "tree"
    tree.mkdir()
    write_bent_strip_obj(tree / "strip.obj")
    subprocess.run([CLI, "bake", str(tree), "--recursive", "--out-dir", str(tmp_path / "cli"), "--normals", "smooth",
                    "--tangent-format", "short", "--quiet"], check=True)
    entries = libtangent.bake_tree(tree, tmp_path / "py", normals="smooth", tangent_format="short")
    assert [e["status"] for e in entries] == ["ok"]
    cli_out, py_out = sorted((tmp_path / "cli").rglob("*.gl*")), sorted((tmp_path / "py").rglob("*.gl*"))
    assert [p.name for p in cli_out] == [p.name for p in py_out] and cli_out
    for a, b in zip(cli_out, py_out):
        assert a.read_bytes() == b.read_bytes(), a.name


def test_check_equals_the_cli_json(tmp_path):
    output = tmp_path / "out.glb"
    libtangent.bake(DEMO / "demo.gltf", output)
    done = subprocess.run([CLI, "check", str(output), "--format", "json"], capture_output=True, check=True)
    assert libtangent.check(output) == json.loads(done.stdout)["files"][0]
    # Findings are returned, not raised: the demo as committed has no TANGENT, which `present` reports.
    unbaked = libtangent.check(DEMO / "demo.gltf")
    assert unbaked["status"] == "findings"
    assert unbaked["primitives"][0]["findings"][0]["check"] == "present"


def test_check_tree_equals_the_cli_over_a_folder(tmp_path):
    tree = tmp_path / "tree"
    (tree / "nested").mkdir(parents=True)
    libtangent.bake(DEMO / "demo.gltf", tree / "nested" / "baked.glb")
    for name in ("demo.gltf", "demo.bin"):
        shutil.copy(DEMO / name, tree / name)
    (tree / "broken.glb").write_bytes(b"glTF\x02\x00\x00\x00")
    files = libtangent.check_tree(tree, allow_missing=False)
    done = subprocess.run([CLI, "check", str(tree), "--recursive", "--format", "json"], capture_output=True)
    assert done.returncode == 2  # an unreadable file
    assert files == json.loads(done.stdout)["files"]
    assert [pathlib.Path(f["file"]).name for f in files] == ["broken.glb", "demo.gltf", "baked.glb"]
    assert [f["status"] for f in files] == ["error", "findings", "clean"]
    with pytest.raises(TypeError, match="unexpected keyword argument 'recursive'"):
        libtangent.check_tree(tree, recursive=True)


def test_check_options_match_the_cli(tmp_path):
    unbaked = DEMO / "demo.gltf"  # no TANGENT: `present` fails unless missing tangents are allowed
    assert libtangent.check(unbaked, allow_missing=True)["status"] == "clean"
    assert libtangent.check(unbaked, ignore=["present"])["primitives"][0]["ignored"] == ["present"]
    only = libtangent.check(unbaked, only=["unit", "w"])
    assert only["status"] == "clean" and only["primitives"][0]["ignored"][0] == "present"
    done = subprocess.run([CLI, "check", str(unbaked), "--format", "json", "--only", "unit,w"], capture_output=True)
    assert only == json.loads(done.stdout)["files"][0]
    output = tmp_path / "short.glb"
    assert libtangent.bake(unbaked, output, tangent_format="short")["primitives"][0]["tangentFormat"] == "short"
    checked = libtangent.check(output, orthogonal_tolerance=0.5, reference_tolerance=2)
    assert checked["status"] == "clean"
    limits = checked["primitives"][0]["limits"]
    assert limits["tangentComponent"] == "normalized SHORT" and limits["normalComponent"] == "float"
    # docs/check.md: SHORT tangents are accepted down to 10 significant bits, a component off by
    # 0.5/511 + 0.5/32767, the vector by sqrt(3) times that, its direction by asin of it. The
    # float NORMAL adds no angle, and the demo's float positions and UVs no allowance.
    vector_error = math.sqrt(3) * (0.5 / 511 + 0.5 / 32767)
    direction = math.degrees(math.asin(vector_error))
    assert limits["unitDeviation"] == pytest.approx(vector_error, rel=1e-12)
    assert limits["referenceAllowanceMaxDegrees"] == 0
    assert limits["orthogonalDegrees"] == pytest.approx(0.5 + direction, rel=1e-12)
    assert limits["referenceDegrees"] == pytest.approx(2 + direction, rel=1e-12)
    with pytest.raises(ValueError, match="only: 'units' is not one of present, format"):
        libtangent.check(unbaked, only=["units"])
    with pytest.raises(ValueError, match="tangent_format"):
        libtangent.bake(unbaked, tmp_path / "x.glb", tangent_format="half")


def test_refused_files_raise_the_cli_message(tmp_path):
    broken = tmp_path / "broken.gltf"
    broken.write_text('{"asset": {"version": "2.0"}, "buffers": [{"uri": "../../../../etc/passwd", "byteLength": 4}]}')
    done = subprocess.run([CLI, "bake", str(broken), "-o", str(tmp_path / "x.glb")], capture_output=True, text=True)
    assert done.returncode == 1
    with pytest.raises(libtangent.InputError) as caught:
        libtangent.bake(broken, tmp_path / "x.glb")
    assert done.stderr.strip() == "error: " + str(caught.value)
    assert "leaves the asset root" in str(caught.value)
    assert isinstance(caught.value, libtangent.Error) and not (tmp_path / "x.glb").exists()
    with pytest.raises(libtangent.InputError, match="no such file"):
        libtangent.check(tmp_path / "missing.glb")


def test_asset_root_widens_what_a_file_may_read(tmp_path):
    scene = tmp_path / "asset" / "scene"
    scene.mkdir(parents=True)
    shutil.copy(DEMO / "bumps_normal.png", tmp_path / "asset")
    doc = json.loads((DEMO / "demo.gltf").read_text())
    doc["images"][0]["uri"] = "../bumps_normal.png"
    shutil.copy(DEMO / "demo.bin", scene)
    (scene / "demo.gltf").write_text(json.dumps(doc))
    with pytest.raises(libtangent.InputError, match="asset root"):
        libtangent.bake(scene / "demo.gltf", tmp_path / "out.glb")
    assert libtangent.bake(scene / "demo.gltf", tmp_path / "asset" / "out.glb", asset_root=tmp_path / "asset")["status"] == "ok"


P = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32)
N = np.array([[0, 0, 1]] * 3, np.float32)
UV = np.array([[0, 0], [1, 0], [0, 1]], np.float32)


@pytest.mark.parametrize("change, phrase", [
    (dict(positions=P[:, :2]), "positions: must have shape"),
    (dict(positions=np.array(["a", "b", "c"])), "positions: must hold real numbers"),
    (dict(normals=N[:2]), "normals: 2 normals for 3 positions"),
    (dict(uvs=UV.astype(np.complex64)), "uvs: must hold real numbers"),
    (dict(uvs=UV[:, :1]), "uvs: must have shape"),
    (dict(indices=[0, 1]), "indices: must have shape"),
    (dict(indices=[0, 1, -1]), "indices: has a negative index"),
    (dict(indices=np.array([0, 1, 2**40])), "indices: has an index beyond"),
    (dict(indices=[0, 1, 5]), "is out of range"),
    (dict(indices=[0.0, 1.0, 2.0]), "indices: must hold integers"),
    (dict(method="bogus"), "method: 'bogus' is not"),
    (dict(weighting="heavy"), "weighting: 'heavy' is not"),
    (dict(threads=-1), "threads: -1"),
    (dict(uv_origin="middle"), "uv_origin: 'middle' is not"),
])
def test_bad_arguments_raise_value_error_naming_the_argument(change, phrase):
    arguments = dict(positions=P, normals=N, uvs=UV, indices=[0, 1, 2])
    arguments.update(change)
    with pytest.raises(ValueError, match=phrase):
        libtangent.compute_tangents(**arguments)


def test_bad_options_of_bake_and_check(tmp_path):
    with pytest.raises(ValueError, match="method"):
        libtangent.bake(DEMO / "demo.gltf", tmp_path / "o.glb", method="fast")
    with pytest.raises(ValueError, match="tolerance"):
        libtangent.check(DEMO / "demo.gltf", tolerance=0)
    with pytest.raises(ValueError, match="method"):
        libtangent.check(DEMO / "demo.gltf", method="flat")


def test_the_gil_is_released_while_the_core_runs():
    arrays = uv_sphere(1000, 600)  # 1.2e6 triangles: a few hundred ms on one thread
    counter = [0]
    stop = threading.Event()

    def spin():
        while not stop.is_set():
            counter[0] += 1

    worker = threading.Thread(target=spin)
    worker.start()
    # The spinning thread's rate while this one sleeps (GIL free).
    time.sleep(0.02)
    before, started = counter[0], time.perf_counter()
    time.sleep(0.2)
    free_rate = (counter[0] - before) / (time.perf_counter() - started)
    # Calls back to back until 0.3 s have passed: one call's length depends on the machine
    # (75 ms on a fast CI runner), and the measure needs calls long against the interpreter's
    # 5 ms switch interval, not a long single call.
    calls, spent, during = 0, 0.0, 0
    while spent < 0.3:
        before, started = counter[0], time.perf_counter()
        libtangent.compute_tangents(*arrays, threads=1)
        during += counter[0] - before
        spent += time.perf_counter() - started
        calls += 1
    stop.set()
    worker.join()
    elapsed = spent
    # Holding the GIL, the spinning thread could run only around each call's edges (the
    # interpreter's 5 ms switch interval), a few percent of the call; released, it keeps
    # most of its free rate for the whole call (a quarter allows for a busy machine).
    assert spent / calls > 0.02, (spent, calls)  # each call long against the switch interval
    assert during > 0.25 * free_rate * elapsed, (during, free_rate, elapsed, calls)


def test_help_reads_like_the_cli():
    assert "as `tangent bake INPUT -o OUTPUT` does" in libtangent.bake.__doc__
    for option in ("method", "weighting", "threads", "all", "overwrite", "asset_root"):
        assert option + ":" in libtangent.bake.__doc__
    stub = pathlib.Path(libtangent.__file__).with_name("__init__.pyi")
    assert "def compute_tangents(" in stub.read_text()


SHARED = SOURCE.parent / "shared" / "assets"


@pytest.mark.parametrize("name", ["NormalTangentTest.glb", "NormalTangentMirrorTest.glb"])
def test_shared_assets_bake_to_the_cli_bytes(tmp_path, name):
    asset = SHARED / name
    if not asset.is_file():
        skip_or_fail(f"{asset} is absent: the shared sample assets are not compared")
    output = tmp_path / "out.glb"
    expected = cli_bake_report(tmp_path, asset, output)
    cli_bytes = output.read_bytes()
    output.unlink()
    assert libtangent.bake(asset, output) == expected
    assert output.read_bytes() == cli_bytes


def test_check_result_carries_warnings(tmp_path):
    """A warning (NORMAL stored at half length, normalized as readers do) is in check's dict,
    as in the CLI's JSON, and is no finding."""
    positions = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]
    normals = [0, 0, 0.5] * 4
    uvs = [0, 1, 1, 1, 1, 0, 0, 0]
    tangents = [1, 0, 0, 1] * 4
    data = np.array(positions + normals + uvs + tangents, dtype="<f4").tobytes() + np.array([0, 1, 2, 0, 2, 3], dtype="<u2").tobytes()
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 192}, {"buffer": 0, "byteOffset": 192, "byteLength": 12}]
    accessors = [
        {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 0, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 0, "byteOffset": 96, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 0, "byteOffset": 128, "componentType": 5126, "count": 4, "type": "VEC4"},
        {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
    ]
    document = {
        "asset": {"version": "2.0"},
        "buffers": [{"uri": "quad.bin", "byteLength": len(data)}],
        "bufferViews": views,
        "accessors": accessors,
        "materials": [{"normalTexture": {"index": 0}}],
        "textures": [{"source": 0}],
        "images": [{"uri": "normal.png"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "TANGENT": 3}, "indices": 4, "material": 0}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    (tmp_path / "quad.bin").write_bytes(data)
    path = tmp_path / "quad.gltf"
    path.write_text(json.dumps(document))
    result = libtangent.check(path)
    assert result["status"] == "clean"
    primitive = result["primitives"][0]
    assert primitive["findings"] == []
    assert len(primitive["warnings"]) == 1
    assert primitive["warnings"][0].startswith("NORMAL is not unit length: worst 0.5,")
    done = subprocess.run([CLI, "check", str(path), "--format", "json"], capture_output=True, check=True)
    assert result == json.loads(done.stdout)["files"][0]


def test_check_reference_names_the_generator(tmp_path):
    """reference= measures `reference` against a chosen generator, as the CLI's --reference."""
    output = tmp_path / "out.glb"
    libtangent.bake(DEMO / "demo.gltf", output, method="lengyel", weighting="area")
    result = libtangent.check(output, reference="lengyel/area")
    assert result["status"] == "clean"
    done = subprocess.run([CLI, "check", str(output), "--format", "json", "--reference", "lengyel/area"], capture_output=True, check=True)
    report = json.loads(done.stdout)
    assert report["settings"]["reference"] == "lengyel/area"
    assert result == report["files"][0]
    with pytest.raises(ValueError, match="reference"):
        libtangent.check(output, reference="lengyel/volume")


def test_shared_assets_check_warns_on_low_coverage(tmp_path):
    """After gltfpack -vt 8 `reference` compares few corners of NormalTangentTest: check's dict
    carries the coverage warning the CLI's JSON has, with the JSON's counts; min_coverage=0 turns
    it off (docs/check.md, "Coverage")."""
    asset = SHARED / "NormalTangentTest.glb"
    if not asset.is_file():
        skip_or_fail(f"{asset} is absent: the coverage warning is not tested")
    if shutil.which("gltfpack") is None:
        skip_or_fail("gltfpack is not installed (scripts/install-deps.sh): the coverage warning is not tested")
    baked, packed = tmp_path / "baked.glb", tmp_path / "packed.glb"
    libtangent.bake(asset, baked)
    subprocess.run(["gltfpack", "-i", str(baked), "-o", str(packed), "-vt", "8"], capture_output=True, check=True)
    result = libtangent.check(packed)
    assert result["status"] == "clean"
    done = subprocess.run([CLI, "check", str(packed), "--format", "json"], capture_output=True, check=True)
    assert result == json.loads(done.stdout)["files"][0]
    primitive = result["primitives"][0]
    total = 3 * primitive["triangles"]
    compared = total - primitive["referenceUnresolvedCorners"] - primitive["referenceUndefinedCorners"]
    assert compared < total / 2
    assert any(w.startswith(f"reference compared only {compared} of {total} corners (") for w in primitive["warnings"]), primitive["warnings"]
    quiet = libtangent.check(packed, min_coverage=0)
    assert not any(" compared only " in w for w in quiet["primitives"][0]["warnings"])
    assert not any(" compared only " in w for w in libtangent.check(baked)["primitives"][0]["warnings"])
    with pytest.raises(ValueError):
        libtangent.check(packed, min_coverage=1.5)


def test_bake_beside_an_empty_glb_ends_and_implied_work_is_refused_by_name(tmp_path):
    # An empty .glb beside a .gltf output (what a failed `bake -o - > out.glb` leaves) once made
    # the search for the .bin's name run forever; run in a thread so a hang fails the test.
    out = tmp_path / "out"
    out.mkdir()
    (out / "empty.glb").write_bytes(b"")
    result = {}
    worker = threading.Thread(target=lambda: result.update(report=libtangent.bake(DEMO / "cube.gltf", out / "o.gltf")),
                              daemon=True)
    worker.start()
    worker.join(60)
    assert not worker.is_alive(), "bake beside an empty .glb did not return"
    assert result["report"] and (out / "o.gltf").exists()
    # Indices without a bufferView implying 10^8 triangles: refused naming the accessor.
    doc = json.loads((DEMO / "cube.gltf").read_text())
    index = doc["meshes"][0]["primitives"][0]["indices"]
    doc["accessors"][index].pop("bufferView")
    doc["accessors"][index].pop("byteOffset", None)
    doc["accessors"][index]["count"] = 3 * 10**8
    shutil.copy(DEMO / "cube.bin", tmp_path / "cube.bin")
    zeros = tmp_path / "zeros.gltf"
    zeros.write_text(json.dumps(doc))
    with pytest.raises(libtangent.InputError, match=rf"zeros\.gltf: /accessors/{index}: has no bufferView"):
        libtangent.bake(zeros, tmp_path / "zeros-out.glb")
