# SPDX-License-Identifier: MIT
"""`tangent check DIR --recursive`: the files `bake --recursive` would bake, one report over the
whole tree in every format, the exit code over all files (a broken file named, the rest still
checked), a progress line on a terminal only; and the GitLab code quality report
(`--format codeclimate`) with fingerprints that stay put and never repeat."""
import json
import os
import re
import shutil
import struct
import subprocess
import xml.dom.minidom

from conftest import skip_or_fail
from test_outputs import CLI, glb_bytes, gltf_bytes, grid, tangent, write


# --- assets -------------------------------------------------------------------------------

def split_glb(data):
    json_length, _ = struct.unpack_from("<II", data, 12)
    doc = json.loads(data[20:20 + json_length])
    bin_length, _ = struct.unpack_from("<II", data, 20 + json_length)
    start = 28 + json_length
    return doc, bytearray(data[start:start + bin_length])


def with_w_negated(data):
    """A baked .glb with every tangent's w negated: handedness (and reference) findings."""
    doc, blob = split_glb(data)
    accessor = doc["accessors"][doc["meshes"][0]["primitives"][0]["attributes"]["TANGENT"]]
    view = doc["bufferViews"][accessor["bufferView"]]
    stride = view.get("byteStride", 16)
    for k in range(accessor["count"]):
        at = view.get("byteOffset", 0) + accessor.get("byteOffset", 0) + k * stride + 12
        struct.pack_into("<f", blob, at, -struct.unpack_from("<f", blob, at)[0])
    return glb_bytes(doc, bytes(blob))


def make_tree(tmp_path, broken=True):
    """tree/ with nested folders: clean assets (baked), failing ones (no TANGENT; w negated), a
    truncated .glb, a file that is no asset and a link to a folder outside (not followed, as
    bake --recursive does not follow it). Returns (tree, {path in the tree: expected status})."""
    doc, blob = grid(5)
    raw = glb_bytes(doc, blob)
    source = write(tmp_path / "source" / "raw.glb", raw)
    tree = tmp_path / "tree"
    for name in ("props/crate.glb", "props/deep/barrel.gltf"):
        (tree / name).parent.mkdir(parents=True, exist_ok=True)
        assert tangent("bake", source, "-o", tree / name).returncode == 0
    write(tree / "levels" / "missing.glb", raw)
    write(tree / "levels" / "deep" / "flipped.glb", with_w_negated((tree / "props" / "crate.glb").read_bytes()))
    write(tree / "notes.txt", b"no asset")
    write(tmp_path / "outside" / "elsewhere.glb", raw)
    os.symlink(tmp_path / "outside", tree / "linked")
    expected = {"props/crate.glb": "clean", "props/deep/barrel.gltf": "clean",
                "levels/missing.glb": "findings", "levels/deep/flipped.glb": "findings"}
    if broken:
        write(tree / "levels" / "deep" / "broken.glb", raw[:len(raw) // 2])
        expected["levels/deep/broken.glb"] = "error"
    return tree, expected


def check(tmp_path, *args, cwd=None, env=None):
    """`tangent check` run from `cwd` (default tmp_path), so that the tree is named `tree`."""
    done = subprocess.run([CLI, "check", *map(os.fsdecode, args)], cwd=cwd or tmp_path, env=env, capture_output=True,
                          timeout=300)
    assert b"AddressSanitizer" not in done.stderr and b"runtime error:" not in done.stderr, done.stderr[-4000:]
    return done


def json_report(tmp_path, *args, cwd=None):
    done = check(tmp_path, "tree", "--recursive", "--format", "json", *args, cwd=cwd)
    return done, json.loads(done.stdout)


# --- the files of a tree ------------------------------------------------------------------

def test_a_folder_without_recursive_is_a_usage_error_that_says_to_add_it(tmp_path):
    make_tree(tmp_path)
    for args in (("tree",), ("tree/props/crate.glb", "tree")):
        done = check(tmp_path, *args)
        assert done.returncode == 2 and done.stdout == b"", done.stderr
        lines = done.stderr.decode().splitlines()
        assert len(lines) == 1 and "--recursive" in lines[0] and "tree" in lines[0], lines
        assert lines[0].startswith("tangent check:") and lines[0].endswith("(see tangent check --help)"), lines


def test_the_tree_is_the_files_bake_recursive_bakes(tmp_path):
    tree, expected = make_tree(tmp_path)
    done, report = json_report(tmp_path)
    checked = [f["file"] for f in report["files"]]
    assert checked == sorted(checked) and len(set(checked)) == len(checked), checked
    assert checked == ["tree/" + name for name in sorted(expected)], checked
    # bake --recursive over the same tree names the same inputs, in the same order.
    baked = tangent("bake", tree, "--recursive", "--out-dir", tmp_path / "baked", "--report", tmp_path / "bake.json")
    assert baked.returncode == 1, baked.stderr  # the broken file
    assert [os.path.relpath(entry["input"], tmp_path) for entry in json.loads((tmp_path / "bake.json").read_text())] == checked


def test_one_report_over_the_tree_and_the_exit_code_over_all_files(tmp_path):
    tree, expected = make_tree(tmp_path)
    done, report = json_report(tmp_path)
    assert done.returncode == 2, done.stderr  # an unreadable file outweighs findings
    statuses = {os.path.relpath(f["file"], "tree"): f["status"] for f in report["files"]}
    assert statuses == expected
    assert report["summary"]["files"] == 5 and report["summary"]["unreadable"] == 1
    # The broken file is named, on stderr and in the report, and the others were still checked.
    assert b"tree/levels/deep/broken.glb" in done.stderr, done.stderr
    failing = {os.path.relpath(f["file"], "tree"): {x["check"] for p in f["primitives"] for x in p["findings"]}
               for f in report["files"] if f["status"] == "findings"}
    assert failing["levels/missing.glb"] == {"present"}
    assert "handedness" in failing["levels/deep/flipped.glb"], failing
    # Text: one report, every file once, one summary line.
    text = check(tmp_path, "tree", "--recursive")
    assert text.returncode == 2
    lines = text.stdout.decode().splitlines()
    assert [line for line in lines if not line.startswith(" ")][:-1] == ["tree/" + name for name in sorted(expected)], lines
    assert lines[-1].startswith("5 file(s),") and lines[-1].endswith("1 unreadable"), lines[-1]
    # Without the broken file: 1 (findings); the clean part alone: 0.
    (tree / "levels" / "deep" / "broken.glb").unlink()
    assert check(tmp_path, "tree", "--recursive").returncode == 1
    assert check(tmp_path, "tree/props", "--recursive").returncode == 0


def test_folders_and_files_together_each_file_once(tmp_path):
    make_tree(tmp_path)
    done, report = json_report(tmp_path, "tree/props", "tree/props/crate.glb")
    checked = [f["file"] for f in report["files"]]
    assert len(checked) == len(set(checked)) == 5, checked
    # An empty folder (or one of other files only): nothing to check is an error, exit 2, said
    # on stderr, no report; with --allow-empty a clean (empty) report.
    (tmp_path / "empty").mkdir()
    (tmp_path / "empty" / "notes.txt").write_text("not an asset")
    done = check(tmp_path, "empty", "--recursive", "--format", "json")
    assert done.returncode == 2 and done.stdout == b"", (done.returncode, done.stdout)
    assert b"error: no .gltf" in done.stderr and b"empty" in done.stderr, done.stderr
    done = check(tmp_path, "empty", "--recursive", "--format", "json", "--allow-empty")
    assert done.returncode == 0 and json.loads(done.stdout)["summary"]["files"] == 0
    assert b"no .gltf" in done.stderr and b"error" not in done.stderr, done.stderr


def test_every_format_is_one_valid_report_over_the_tree(tmp_path):
    _, expected = make_tree(tmp_path)
    names = ["tree/" + name for name in sorted(expected)]
    broken = "tree/levels/deep/broken.glb"
    outputs = {}
    for fmt in ("text", "json", "junit", "github", "sarif", "codeclimate", "html"):
        done = check(tmp_path, "tree", "--recursive", "--format", fmt, "-o", f"report.{fmt}",
                     env=dict(os.environ, TANGENT_VIEW=""))  # html: no thumbnails
        assert done.returncode == 2, (fmt, done.stderr)
        assert broken.encode() in done.stderr, (fmt, done.stderr)
        outputs[fmt] = (tmp_path / f"report.{fmt}").read_text(encoding="utf-8")
    junit = xml.dom.minidom.parseString(outputs["junit"])
    suites = junit.getElementsByTagName("testsuite")
    assert [s.getAttribute("file") for s in suites] == names
    assert junit.documentElement.getAttribute("errors") == "1"
    assert [e.parentNode.getAttribute("file") for e in junit.getElementsByTagName("error")] == [broken]
    github = outputs["github"].splitlines()
    assert all(line.startswith("::") for line in github), github
    assert sum(line.startswith(f"::error file={broken},") for line in github) == 1
    assert github[-1].startswith("::notice") and "5 file(s)" in github[-1], github[-1]
    sarif = json.loads(outputs["sarif"])
    run = sarif["runs"][0]
    assert sarif["version"] == "2.1.0" and len(sarif["runs"]) == 1
    assert run["invocations"][0]["executionSuccessful"] is False
    notifications = run["invocations"][0]["toolExecutionNotifications"]
    assert [n["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] for n in notifications] == [broken]
    failing = {r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] for r in run["results"]}
    assert failing == {"tree/levels/missing.glb", "tree/levels/deep/flipped.glb"}
    issues = json.loads(outputs["codeclimate"])
    assert {i["location"]["path"] for i in issues} == failing | {broken}
    for fmt in ("text", "html"):
        assert all(outputs[fmt].count(name) >= 1 for name in names), outputs[fmt][:2000]


# --- GitLab code quality ------------------------------------------------------------------

def test_codeclimate_issues_have_what_gitlab_reads(tmp_path):
    make_tree(tmp_path)
    done = check(tmp_path, "tree", "--recursive", "--format", "codeclimate")
    assert done.returncode == 2
    issues = json.loads(done.stdout)
    assert isinstance(issues, list) and issues
    for issue in issues:
        assert isinstance(issue["description"], str) and issue["description"], issue
        assert re.fullmatch(r"tangent-check/[a-z-]+", issue["check_name"]), issue
        assert re.fullmatch(r"[0-9a-f]{64}", issue["fingerprint"]), issue
        assert issue["severity"] in ("info", "minor", "major", "critical", "blocker"), issue
        location = issue["location"]
        assert not location["path"].startswith(("/", "./")), location
        assert isinstance(location["lines"]["begin"], int) and location["lines"]["begin"] >= 1, location
    by_check = {}
    for issue in issues:
        by_check.setdefault(issue["check_name"], []).append(issue)
    (unreadable,) = by_check["tangent-check/unreadable"]
    assert unreadable["severity"] == "blocker" and unreadable["location"]["path"] == "tree/levels/deep/broken.glb"
    (present,) = by_check["tangent-check/present"]
    assert present["location"]["path"] == "tree/levels/missing.glb" and present["severity"] == "major"
    assert "/meshes/0/primitives/0" in present["description"], present
    assert by_check["tangent-check/handedness"][0]["location"]["path"] == "tree/levels/deep/flipped.glb"


def test_codeclimate_fingerprints_are_stable_across_runs_and_unique_per_finding(tmp_path):
    tree, _ = make_tree(tmp_path)

    def fingerprints(cwd, folder):
        done = check(tmp_path, folder, "--recursive", "--format", "codeclimate", cwd=cwd)
        return {(i["location"]["path"], i["check_name"], i["description"].split(":")[1]): i["fingerprint"]
                for i in json.loads(done.stdout)}, [i["fingerprint"] for i in json.loads(done.stdout)]

    first, listed = fingerprints(tmp_path, "tree")
    assert len(listed) == len(set(listed)) >= 4, listed  # unique per finding, several per file
    assert len({f for (path, _, _), f in first.items() if path == "tree/levels/deep/flipped.glb"}) >= 2
    second, _ = fingerprints(tmp_path, "tree")
    assert second == first
    # The same tree elsewhere, named the same from where it runs: the same fingerprints.
    shutil.copytree(tree, tmp_path / "copy" / "tree", symlinks=True)
    assert fingerprints(tmp_path / "copy", "tree")[0] == first
    # "./tree" is the path "tree/...", as GitLab's paths from the repository root are.
    assert fingerprints(tmp_path, "./tree")[0] == first
    # A finding's fingerprint follows the file, the element and the check, not the counts.
    write(tree / "levels" / "missing.glb", glb_bytes(*grid(7)))
    third, _ = fingerprints(tmp_path, "tree")
    assert third == first


# --- progress -----------------------------------------------------------------------------

def test_progress_names_each_file_in_the_tree_on_a_terminal_only(tmp_path):
    make_tree(tmp_path, broken=False)
    done = check(tmp_path, "tree", "--recursive")
    assert b"\r" not in done.stderr and b"[1/4]" not in done.stderr + done.stdout
    if shutil.which("script") is None:
        skip_or_fail("script(1) from util-linux is not installed")
    shown = subprocess.run(["script", "-qec", f"'{CLI}' check tree --recursive --format json -o report.json", "/dev/null"],
                           cwd=tmp_path, capture_output=True, timeout=120)
    assert shown.returncode == 1, shown.stdout  # script -e: the command's exit code (findings)
    progress = re.findall(rb"\[(\d)/4\] ([^ ]+)  \d+:\d\d", shown.stdout)
    assert [name for _, name in progress] == [b"levels/deep/flipped.glb", b"levels/missing.glb", b"props/crate.glb",
                                              b"props/deep/barrel.gltf"], shown.stdout
    assert [int(k) for k, _ in progress] == [0, 1, 2, 3]
    assert shown.stdout.rstrip(b"\r\n").endswith(b"\r\x1b[K"), shown.stdout[-200:]  # cleared at the end
    assert json.loads((tmp_path / "report.json").read_text())["summary"]["files"] == 4


def test_quiet_check_shows_no_progress_on_a_terminal(tmp_path):
    make_tree(tmp_path, broken=False)
    if shutil.which("script") is None:
        skip_or_fail("script(1) from util-linux is not installed")
    shown = subprocess.run(["script", "-qec", f"'{CLI}' check tree --recursive -q --format json -o report.json", "/dev/null"],
                           cwd=tmp_path, capture_output=True, timeout=120)
    assert shown.returncode == 1, shown.stdout
    assert re.findall(rb"\[\d/4\]", shown.stdout) == [], shown.stdout
    assert json.loads((tmp_path / "report.json").read_text())["summary"]["files"] == 4


def test_code_review_reports_point_at_the_primitives_line_in_a_gltf(tmp_path):
    """GitLab's lines.begin and SARIF's region: the line a .gltf's primitive starts on (the
    .gltf indented, its second primitive lacking TANGENT); a .glb has no lines: 1, no region."""
    doc, blob = grid(4)
    doc["meshes"][0]["primitives"].append(dict(doc["meshes"][0]["primitives"][0]))
    gltf = json.loads(gltf_bytes(doc, blob))
    text = json.dumps(gltf, indent=2)
    lines = text.splitlines()
    starts = [k + 2 for k, line in enumerate(lines) if line.strip() == '"primitives": [']
    expected = starts[0] + len(json.dumps(gltf["meshes"][0]["primitives"][0], indent=2).splitlines())
    assert lines[expected - 1].strip() == "{", lines[expected - 2:expected + 1]
    write(tmp_path / "scene.gltf", text.encode())
    write(tmp_path / "scene.glb", glb_bytes(doc, blob))
    climate = json.loads(check(tmp_path, "scene.gltf", "scene.glb", "--format", "codeclimate").stdout)
    begins = [(i["location"]["path"], i["location"]["lines"]["begin"]) for i in climate if i["check_name"] == "tangent-check/present"]
    assert begins == [("scene.gltf", starts[0]), ("scene.gltf", expected), ("scene.glb", 1), ("scene.glb", 1)], begins
    sarif = json.loads(check(tmp_path, "scene.gltf", "scene.glb", "--format", "sarif").stdout)
    regions = [(r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"], r["locations"][0]["physicalLocation"].get("region"))
               for r in sarif["runs"][0]["results"]]
    assert regions == [("scene.gltf", {"startLine": starts[0]}), ("scene.gltf", {"startLine": expected}),
                       ("scene.glb", None), ("scene.glb", None)], regions


def test_entries_named_like_assets_that_are_not_files_are_said_and_left_out(tmp_path):
    """A FIFO, a link to a device, a dangling link and a link that loops, each named like an
    asset: check and bake --recursive read none of them (a FIFO would block, /dev/zero never
    ends) and say each on stderr, naming it and what it is; the report and the exit code are
    those of the tree's files alone."""
    tree, expected = make_tree(tmp_path, broken=False)
    os.mkfifo(tree / "levels" / "pipe.glb")
    os.symlink(tmp_path / "nowhere.glb", tree / "props" / "dangling.gltf")
    os.symlink("/dev/zero", tree / "props" / "zero.glb")
    os.symlink(tree / "props" / "loop.glb", tree / "props" / "loop.glb")
    os.mkfifo(tree / "levels" / "pipe.txt")  # not named like an asset: nothing to say
    said = ["tree/levels/pipe.glb: left out (a FIFO)", "tree/props/dangling.gltf: left out (a link to nothing)",
            "tree/props/loop.glb: left out (a link that loops)", "tree/props/zero.glb: left out (a link to a device)"]

    def warnings(stderr):
        return [line[len("warning: "):].split(";")[0] for line in stderr.decode().splitlines()
                if line.startswith("warning: ") and "left out" in line]

    done, report = json_report(tmp_path)
    assert done.returncode == 1, done.stderr  # the findings of missing.glb and flipped.glb only
    assert [os.path.relpath(f["file"], "tree") for f in report["files"]] == sorted(expected)
    assert warnings(done.stderr) == said, done.stderr
    baked = tangent("bake", tree, "--recursive", "--out-dir", tmp_path / "baked", "--report", tmp_path / "bake.json")
    assert baked.returncode == 0, baked.stderr
    assert [line.replace(os.fsdecode(tmp_path) + "/", "") for line in warnings(baked.stderr)] == said, baked.stderr
    assert sorted(os.path.relpath(entry["input"], tree) for entry in json.loads((tmp_path / "bake.json").read_text())) == \
        sorted(expected)
    assert not (tmp_path / "baked" / "levels" / "pipe.glb").exists()
