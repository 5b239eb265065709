# SPDX-License-Identifier: MIT
"""Usage errors of `tangent bake` say what is wrong, not what a different mistake would need."""
import os

from test_outputs import glb_bytes, grid, tangent, write


def test_options_after_double_dash_are_named_as_inputs(tmp_path):
    doc, blob = grid(4)
    write(tmp_path / "-o.glb", glb_bytes(doc, blob))
    os.chdir(tmp_path)
    done = tangent("bake", "--", "-o.glb", "-o", "out.glb")
    assert done.returncode == 2, done.stderr
    assert b"'-o' comes after '--'" in done.stderr, done.stderr
    assert not (tmp_path / "out.glb").exists()
    # Before "--" the same -o is an option, and the bake runs.
    assert tangent("bake", "-o", "out.glb", "--", "-o.glb").returncode == 0


def test_a_folder_without_recursive_is_named_as_a_folder(tmp_path):
    doc, blob = grid(4)
    write(tmp_path / "tree" / "a.glb", glb_bytes(doc, blob))
    for args in (("bake", tmp_path / "tree", tmp_path / "out"), ("bake", tmp_path / "tree", "--out-dir", tmp_path / "out")):
        done = tangent(*args)
        assert done.returncode == 2, done.stderr
        assert b"is a folder" in done.stderr and b"--recursive" in done.stderr, done.stderr
        assert b"must end in" not in done.stderr


def test_both_outputs_and_no_output_say_which(tmp_path):
    doc, blob = grid(4)
    asset = write(tmp_path / "a.glb", glb_bytes(doc, blob))
    both = tangent("bake", asset, "-o", tmp_path / "o.glb", "--out-dir", tmp_path / "d")
    assert both.returncode == 2 and b"not both" in both.stderr, both.stderr
    none = tangent("bake", asset)
    assert none.returncode == 2 and b"no output" in none.stderr, none.stderr
