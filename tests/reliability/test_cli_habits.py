# SPDX-License-Identifier: MIT
"""The command line as users of glTF-Transform, gltfpack and other Unix tools expect it:
`tangent bake IN OUT`, -V, help that lists every option it accepts, no binary on a terminal."""
import os
import re
import shutil
import subprocess

from conftest import skip_or_fail
from test_outputs import CLI, assert_valid_glb, glb_bytes, grid, tangent, write


def test_bake_in_out_is_the_same_as_dash_o(tmp_path):
    doc, blob = grid(5)
    asset = write(tmp_path / "in.glb", glb_bytes(doc, blob))
    assert tangent("bake", asset, tmp_path / "a.glb").returncode == 0
    assert tangent("bake", asset, "-o", tmp_path / "b.glb").returncode == 0
    assert (tmp_path / "a.glb").read_bytes() == (tmp_path / "b.glb").read_bytes()
    assert_valid_glb(tmp_path / "a.glb")
    done = tangent("bake", asset, tmp_path / "notes.txt")
    assert done.returncode == 2 and b"must end in .glb or .gltf" in done.stderr
    assert not (tmp_path / "notes.txt").exists()


def test_version_flags():
    for flag in ("-V", "--version"):
        done = tangent(flag)
        assert done.returncode == 0 and re.fullmatch(rb"tangent \d+\.\d+\.\d+\n", done.stdout), done.stdout


def test_every_option_in_the_help_is_accepted_and_every_format_listed(tmp_path):
    doc, blob = grid(4)
    asset = write(tmp_path / "in.glb", glb_bytes(doc, blob))
    top = tangent("--help").stdout.decode()
    for fmt in ("text", "json", "junit", "github", "sarif"):
        assert fmt in top.split("check IN...")[1].split("\n")[0], top
        assert tangent("check", asset, "--format", fmt).returncode == 1  # a finding: no TANGENT
    for command in ("bake", "check", "info"):
        text = tangent(command, "--help").stdout.decode()
        options = set(re.findall(r"^\s+(?:-\w, )?(--[a-z-]+)", text, re.M))
        assert len(options) >= 2, text
        for option in options:
            done = tangent(command, option)
            assert b"unknown option" not in done.stderr, (command, option, done.stderr)


def test_binary_output_to_a_terminal_is_refused(tmp_path):
    if shutil.which("script") is None:
        skip_or_fail("script(1) from util-linux is not installed")
    doc, blob = grid(4)
    asset = write(tmp_path / "in.glb", glb_bytes(doc, blob))
    shown = subprocess.run(["script", "-qec", f"'{CLI}' bake '{asset}' -o -", "/dev/null"], capture_output=True, timeout=60)
    assert b"standard output is a terminal" in shown.stdout, shown.stdout
    assert b"glTF" not in shown.stdout  # no GLB header reached the terminal
    # To a pipe it goes.
    done = tangent("bake", asset, "-o", "-")
    assert done.returncode == 0 and done.stdout[:4] == b"glTF"


def test_a_usage_error_is_one_line_that_points_at_the_help(tmp_path):
    doc, blob = grid(4)
    asset = write(tmp_path / "in.glb", glb_bytes(doc, blob))
    mistakes = {
        "bake": [("bake", asset), ("bake", asset, "-o", tmp_path / "o.glb", "--no-such-option"),
                 ("bake", asset, "-o", tmp_path / "o.glb", "--method", "best")],
        "check": [("check",), ("check", asset, "--format", "pdf")],
        "info": [("info",), ("info", asset, "--no-such-option")],
        "bench": [("bench", "--no-such-option")],
        "": [("bakery",)],
    }
    for command, cases in mistakes.items():
        pointer = f"(see tangent {command} --help)".replace("  ", " ").encode()
        for args in cases:
            done = tangent(*args)
            assert done.returncode == 2, (args, done.stderr)
            lines = done.stderr.decode().splitlines()
            assert len(lines) == 1 and lines[0].endswith(pointer.decode()), (args, done.stderr)
            assert lines[0].startswith(f"tangent {command}:".replace(" :", ":")), (args, done.stderr)
        if command:
            shown = tangent(command, "--help")
            assert shown.returncode == 0 and shown.stdout.startswith(f"usage: tangent {command}".encode()), shown.stdout


def test_progress_names_each_file_by_its_path_in_the_tree(tmp_path):
    if shutil.which("script") is None:
        skip_or_fail("script(1) from util-linux is not installed")
    doc, blob = grid(4)
    for folder in ("walls", "floors"):
        write(tmp_path / "tree" / folder / "brick.glb", glb_bytes(doc, blob))
    out = tmp_path / "out"
    shown = subprocess.run(["script", "-qec", f"'{CLI}' bake --recursive '{tmp_path / 'tree'}' --out-dir '{out}' -q", "/dev/null"],
                           capture_output=True, timeout=120)
    # Two files of one name: the progress line tells them apart by their folders in the tree.
    progress = set(re.findall(rb"\[\d/2\] ([^ ]+)  \d+:\d\d", shown.stdout))
    assert progress == set(), "--quiet shows no progress: " + repr(shown.stdout)
    shown = subprocess.run(["script", "-qec", f"'{CLI}' bake --recursive '{tmp_path / 'tree'}' --out-dir '{out}' --force",
                            "/dev/null"], capture_output=True, timeout=120)
    progress = set(re.findall(rb"\[\d/2\] ([^ ]+)  \d+:\d\d", shown.stdout))
    assert progress == {b"walls/brick.glb", b"floors/brick.glb"}, shown.stdout
