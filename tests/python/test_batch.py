# SPDX-License-Identifier: MIT
"""Batch baking of folder trees: `tangent bake --recursive`, libtangent.bake_tree and the Dask
example (examples/bake_dask.py) on a LocalCluster of 2 workers."""
import json
import os
import pathlib
import shutil
import stat
import subprocess
import sys

import pytest

import libtangent
from conftest import skip_or_fail

CLI = os.environ["TANGENT_CLI"]
SOURCE = pathlib.Path(os.environ["TANGENT_SOURCE_DIR"])
DEMO = SOURCE / "data" / "demo"
BROKEN = {
    "broken/cycle.gltf": '{"asset": {"version": "2.0"}, "nodes": [{"children": [0]}]}',
    "broken/escape.gltf": '{"asset": {"version": "2.0"}, "buffers": [{"uri": "../../../../etc/passwd", "byteLength": 4}]}',
    "broken/not_json.gltf": '{"asset": ',
    "broken/bad_index.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 9/1\n",
}


def make_tree(root, copies=6):
    """copies x the demo folder's six glTF files, plus four broken files: 40 inputs."""
    for k in range(copies):
        shutil.copytree(DEMO, root / f"set{k}")
    for name, text in BROKEN.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)
    return root


def tree_bytes(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def test_cli_recursive_and_python_bake_tree_agree_and_skip_unchanged(tmp_path):
    tree = make_tree(tmp_path / "in", copies=2)
    inputs = libtangent.find_inputs(tree)
    assert len(inputs) == 2 * 6 + 4
    done = subprocess.run([CLI, "bake", str(tree), "--recursive", "--out-dir", str(tmp_path / "cli"),
                           "--report", str(tmp_path / "cli.json")], capture_output=True, text=True)
    assert done.returncode == 1, done.stderr  # the broken files
    for name in BROKEN:
        assert name in done.stderr.replace(str(tree) + "/", "")
    entries = libtangent.bake_tree(tree, tmp_path / "py")
    cli_entries = json.loads((tmp_path / "cli.json").read_text())
    assert [e["status"] for e in entries] == [e["status"] for e in cli_entries]
    assert sum(e["status"] == "failed" for e in entries) == len(BROKEN)
    cli_tree, py_tree = tree_bytes(tmp_path / "cli"), tree_bytes(tmp_path / "py")
    assert cli_tree == py_tree  # outputs and manifest, byte for byte
    # A second run skips everything; changing one buffer rebakes exactly the file using it.
    again = libtangent.bake_tree(tree, tmp_path / "py")
    assert all(e["unchanged"] for e in again)
    with open(tree / "set1" / "torus.bin", "r+b") as f:
        f.seek(100)
        f.write(b"\x01")
    third = libtangent.bake_tree(tree, tmp_path / "py")
    rebaked = [pathlib.Path(e["input"]).relative_to(tree).as_posix() for e in third if not e["unchanged"]]
    assert rebaked == ["set1/torus.gltf"]
    assert not libtangent.bake_tree(tree, tmp_path / "py", force=True)[0]["unchanged"]


def test_dask_example_on_a_local_cluster(tmp_path):
    try:
        import distributed  # noqa: F401
    except ImportError:
        skip_or_fail("Debian's python3-distributed is not installed")
    tree = make_tree(tmp_path / "in")
    assert len(libtangent.find_inputs(tree)) == 40
    subprocess.run([CLI, "bake", str(tree), "--recursive", "--out-dir", str(tmp_path / "cli"), "-q"], capture_output=True)
    example = SOURCE / "examples" / "bake_dask.py"
    env = dict(os.environ)
    run = [sys.executable, str(example), str(tree), str(tmp_path / "dask"), "--workers", "2",
           "--report", str(tmp_path / "dask.json")]
    done = subprocess.run(run, capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 1, done.stdout + done.stderr
    assert "36 baked, 0 unchanged, 4 failed" in done.stdout, done.stdout + done.stderr
    report = json.loads((tmp_path / "dask.json").read_text())
    failed = sorted(pathlib.Path(e["input"]).relative_to(tree).as_posix() for e in report if e["status"] == "failed")
    assert failed == sorted(BROKEN)
    # Every good file byte-identical to the CLI's, and the manifest the CLI's as well.
    assert tree_bytes(tmp_path / "dask") == tree_bytes(tmp_path / "cli")
    # The manifest makes a second run skip everything.
    done = subprocess.run(run, capture_output=True, text=True, env=env, timeout=300)
    assert "0 baked, 40 unchanged, 4 failed" in done.stdout, done.stdout + done.stderr


def test_write_file_writes_as_every_libtangent_writer(tmp_path):
    """libtangent.write_file, which the Dask example writes its manifest and report with: whole
    files, a link followed only to a name of its extension, no FIFO, folder or victim replaced."""
    out = tmp_path / "a.json"
    libtangent.write_file(out, b'{"x": 1}\n')
    assert out.read_bytes() == b'{"x": 1}\n'
    libtangent.write_file(str(out), b"{}\n")  # a str path too; replaced whole
    assert out.read_bytes() == b"{}\n"
    victim = tmp_path / "victim.txt"
    victim.write_text("victim")
    (tmp_path / "link.json").symlink_to(victim)
    with pytest.raises(libtangent.Error, match=r"link.json: is a symbolic link to .*victim.txt, which does not end in .json"):
        libtangent.write_file(tmp_path / "link.json", b"{}")
    assert victim.read_text() == "victim" and (tmp_path / "link.json").is_symlink()
    (tmp_path / "store.json").write_text("old")
    (tmp_path / "same.json").symlink_to("store.json")
    libtangent.write_file(tmp_path / "same.json", b"new")
    assert (tmp_path / "store.json").read_text() == "new" and (tmp_path / "same.json").is_symlink()
    os.mkfifo(tmp_path / "fifo.json")
    with pytest.raises(libtangent.Error, match=r"fifo.json: a FIFO that nobody reads; not written"):
        libtangent.write_file(tmp_path / "fifo.json", b"{}")
    assert stat.S_ISFIFO(os.lstat(tmp_path / "fifo.json").st_mode)
    (tmp_path / "folder.json").mkdir()
    with pytest.raises(libtangent.Error, match=r"folder.json: is a folder; not written"):
        libtangent.write_file(tmp_path / "folder.json", b"{}")
    with pytest.raises(libtangent.Error, match=r"missing/b.json"):
        libtangent.write_file(tmp_path / "missing" / "b.json", b"{}")
    assert not [p for p in tmp_path.iterdir() if ".tmp-" in p.name]


def test_dask_example_writes_its_manifest_and_report_as_the_cli_does(tmp_path):
    """The example wrote its report with Path.write_text (through any link, into a FIFO, not
    atomically) and its manifest through a fixed temporary name: now both by write_file."""
    try:
        import distributed  # noqa: F401
    except ImportError:
        skip_or_fail("Debian's python3-distributed is not installed")
    tree = tmp_path / "in"
    tree.mkdir()
    shutil.copy(DEMO / "cube.gltf", tree)
    shutil.copy(DEMO / "cube.bin", tree)
    victim = tmp_path / "victim.txt"
    victim.write_text("victim")
    (tmp_path / "report.json").symlink_to(victim)
    example = SOURCE / "examples" / "bake_dask.py"
    run = [sys.executable, str(example), str(tree), str(tmp_path / "out"), "--workers", "1",
           "--report", str(tmp_path / "report.json")]
    done = subprocess.run(run, capture_output=True, text=True, timeout=300)
    assert done.returncode == 1, done.stdout + done.stderr
    assert "report.json: is a symbolic link to" in done.stderr, done.stderr
    assert victim.read_text() == "victim"
    assert json.loads((tmp_path / "out" / "tangent-manifest.json").read_text())["files"]["cube.gltf"]["ok"]
    # The manifest's name a FIFO: not read (the run does not hang), not replaced, said.
    (tmp_path / "out" / "tangent-manifest.json").unlink()
    os.mkfifo(tmp_path / "out" / "tangent-manifest.json")
    done = subprocess.run(run[:-2], capture_output=True, text=True, timeout=300)
    assert done.returncode == 1, done.stdout + done.stderr
    assert "tangent-manifest.json: a FIFO that nobody reads" in done.stderr, done.stderr
    assert stat.S_ISFIFO(os.lstat(tmp_path / "out" / "tangent-manifest.json").st_mode)
