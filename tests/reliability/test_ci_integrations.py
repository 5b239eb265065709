# SPDX-License-Identifier: MIT
"""The CI integrations the repository carries, run here as their hosts would run them: the
GitHub composite action (action.yml: its run: steps in order, with the inputs substituted as
GitHub substitutes them; the upload to code scanning cannot reach GitHub and is checked for what
it would upload) and the pre-commit hook (.pre-commit-hooks.yaml: its entry on the files its
pattern selects), on a small repository of clean and failing assets."""
import json
import os
import pathlib
import re
import shlex
import subprocess

from conftest import skip_or_fail
from test_outputs import CLI, glb_bytes, grid, tangent, write

ROOT = pathlib.Path(__file__).resolve().parents[2]

try:
    import yaml  # Debian's python3-yaml (scripts/install-deps.sh)
except ImportError:  # pragma: no cover - a machine without it
    yaml = None


def load_yaml(name):
    if yaml is None:
        skip_or_fail("python3-yaml is not installed (scripts/install-deps.sh installs it)")
    return yaml.safe_load((ROOT / name).read_text(encoding="utf-8"))


def make_repository(tmp_path):
    """repo/ with a clean asset (baked), a failing one (no TANGENT) and a file that is no asset."""
    repo = tmp_path / "repo"
    doc, blob = grid(5)
    raw = write(tmp_path / "raw.glb", glb_bytes(doc, blob))
    (repo / "assets" / "ok").mkdir(parents=True)
    assert tangent("bake", raw, "-o", repo / "assets" / "ok" / "crate.glb").returncode == 0
    assert tangent("bake", raw, "-o", repo / "assets" / "ok" / "barrel.gltf").returncode == 0
    (repo / "assets" / "ok" / "barrel.gltf").rename(repo / "assets" / "ok" / "Barrel.GLTF")  # the hook's pattern ignores case
    write(repo / "assets" / "bad" / "missing.glb", raw.read_bytes())
    write(repo / "docs" / "notes.txt", b"no asset")
    return repo


# --- the GitHub action --------------------------------------------------------------------

EXPRESSION = re.compile(r"\$\{\{\s*(.*?)\s*\}\}")


class Context:
    """What the action's expressions read: its inputs and earlier steps' outputs."""

    def __init__(self, inputs):
        self.inputs, self.outputs = inputs, {}

    def value(self, name):
        if m := re.fullmatch(r"inputs\.([\w-]+)", name):
            return self.inputs[m.group(1)]
        if m := re.fullmatch(r"steps\.([\w-]+)\.outputs\.([\w-]+)", name):
            return self.outputs.get(m.group(1), {}).get(m.group(2), "")
        raise AssertionError(f"action.yml uses an expression this test does not know: {name}")

    def substitute(self, text):
        return EXPRESSION.sub(lambda m: self.value(m.group(1)), str(text))

    def condition(self, text):
        """`A == 'B' && C == 'D'`: the only form of `if:` the action uses."""
        text = EXPRESSION.sub(lambda m: m.group(1), str(text))
        result = True
        for term in text.split("&&"):
            m = re.fullmatch(r"\s*([\w.-]+)\s*==\s*'([^']*)'\s*", term)
            assert m, f"action.yml has a condition this test does not know: {text}"
            result = result and self.value(m.group(1)) == m.group(2)
        return result


def run_action(repo, tmp_path, **given):
    """Runs action.yml's steps as a runner would, from the repository's root: returns the exit
    code of the first step that failed (0: none), the step outputs and the uploads it would make."""
    action = load_yaml("action.yml")
    assert action["runs"]["using"] == "composite"
    inputs = {name: str(spec.get("default", "")) for name, spec in action["inputs"].items()}
    assert set(given) <= set(inputs), given
    inputs.update(given)
    context = Context(inputs)
    uploads = []
    for number, step in enumerate(action["runs"]["steps"]):
        if "if" in step and not context.condition(step["if"]):
            continue
        if "uses" in step:
            assert step["uses"].startswith("github/codeql-action/upload-sarif@"), step["uses"]
            uploads.append({key: context.substitute(value) for key, value in step["with"].items()})
            continue
        assert step["shell"] == "bash", step
        output_file = tmp_path / f"github-output-{number}"
        output_file.write_text("")
        env = dict(os.environ, GITHUB_OUTPUT=str(output_file), GITHUB_WORKSPACE=str(repo))
        env.update({key: context.substitute(value) for key, value in step.get("env", {}).items()})
        # GitHub runs `shell: bash` as `bash --noprofile --norc -eo pipefail FILE`.
        script = tmp_path / f"step-{number}.sh"
        script.write_text(step["run"])
        done = subprocess.run(["bash", "--noprofile", "--norc", "-eo", "pipefail", str(script)], cwd=repo, env=env,
                              capture_output=True, timeout=300)
        assert b"runtime error:" not in done.stderr and b"AddressSanitizer" not in done.stderr, done.stderr
        if "id" in step:
            context.outputs[step["id"]] = dict(line.split("=", 1) for line in output_file.read_text().splitlines())
        if done.returncode != 0:
            return done.returncode, context.outputs, uploads
    return 0, context.outputs, uploads


def sarif_results(path):
    log = json.loads(pathlib.Path(path).read_text(encoding="utf-8"))
    assert log["version"] == "2.1.0"
    return [(r["ruleId"], r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]) for r in log["runs"][0]["results"]]


def test_the_action_writes_sarif_with_the_findings_uploads_it_and_fails_the_job(tmp_path):
    repo = make_repository(tmp_path)
    code, outputs, uploads = run_action(repo, tmp_path, paths="assets", tangent=CLI)
    assert code == 1  # findings fail the job, after the upload
    assert outputs["check"]["exit-code"] == "1" and outputs["check"]["written"] == "true"
    sarif = repo / "tangent-check.sarif"
    assert [u["sarif_file"] for u in uploads] == ["tangent-check.sarif"], uploads
    results = sarif_results(sarif)
    assert results == [("present", "assets/bad/missing.glb")], results  # paths from the repository root


def test_the_action_inputs_reach_tangent_check(tmp_path):
    repo = make_repository(tmp_path)
    # Findings that do not fail the job; the report where it is asked for.
    code, outputs, uploads = run_action(repo, tmp_path, paths="assets", tangent=CLI, sarif="reports/t.sarif",
                                        **{"fail-on-findings": "false", "upload": "false"})
    assert code == 0 and outputs["check"]["exit-code"] == "1" and uploads == []
    assert sarif_results(repo / "reports" / "t.sarif") == [("present", "assets/bad/missing.glb")]
    # Several paths, one a file; options passed through (--allow-missing: no finding left).
    code, outputs, _ = run_action(repo, tmp_path, paths="assets/ok\nassets/bad/missing.glb", tangent=CLI,
                                  args="--allow-missing --tolerance 2")
    assert code == 0 and outputs["check"]["exit-code"] == "0"
    log = json.loads((repo / "tangent-check.sarif").read_text())
    assert log["runs"][0]["results"] == [] and log["runs"][0]["invocations"][0]["executionSuccessful"] is True
    settings = log["runs"][0]["invocations"][0]["properties"]["settings"]
    assert settings["allowMissing"] is True, settings
    # One path a line: a folder whose name holds a space is one path (and an empty line none).
    (repo / "assets" / "ok").rename(repo / "assets" / "ok props")
    write(repo / "assets" / "ok props" / "also missing.glb", (repo / "assets" / "bad" / "missing.glb").read_bytes())
    code, outputs, _ = run_action(repo, tmp_path, paths="assets/ok props\n\nassets/bad/missing.glb\n", tangent=CLI,
                                  **{"fail-on-findings": "false"})
    assert code == 0 and outputs["check"]["exit-code"] == "1", outputs
    assert sorted(sarif_results(repo / "tangent-check.sarif")) == [("present", "assets/bad/missing.glb"),
                                                                    ("present", "assets/ok%20props/also%20missing.glb")]  # SARIF URIs are percent-encoded
    # A broken file fails the job whatever fail-on-findings says; the SARIF still goes up.
    write(repo / "assets" / "broken.glb", b"glTF")
    code, outputs, uploads = run_action(repo, tmp_path, paths="assets", tangent=CLI, **{"fail-on-findings": "false"})
    assert code == 2 and outputs["check"]["exit-code"] == "2" and len(uploads) == 1
    log = json.loads((repo / "tangent-check.sarif").read_text())
    notifications = log["runs"][0]["invocations"][0]["toolExecutionNotifications"]
    assert [n["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] for n in notifications] == ["assets/broken.glb"]


# --- the pre-commit hook ------------------------------------------------------------------

def test_the_pre_commit_hook_checks_the_assets_it_is_given(tmp_path):
    repo = make_repository(tmp_path)
    (hook,) = [h for h in load_yaml(".pre-commit-hooks.yaml") if h["id"] == "tangent-check"]
    assert hook["entry"] == "tangent check" and hook["language"] == "system"
    staged = ["assets/ok/crate.glb", "assets/ok/Barrel.GLTF", "assets/bad/missing.glb", "docs/notes.txt"]
    # pre-commit selects files with re.search(files, name), then runs ENTRY ARGS... FILES...
    selected = [name for name in staged if re.search(hook["files"], name)]
    assert selected == staged[:3], selected
    env = dict(os.environ, PATH=os.path.dirname(os.path.abspath(CLI)) + os.pathsep + os.environ["PATH"])

    def run_hook(files):
        return subprocess.run(shlex.split(hook["entry"]) + hook.get("args", []) + files, cwd=repo, env=env,
                              capture_output=True, timeout=300)

    done = run_hook(selected)
    assert done.returncode == 1, done.stderr  # a finding fails the commit
    assert b"assets/bad/missing.glb" in done.stdout and b"FAIL present" in done.stdout, done.stdout
    assert b"3 file(s)" in done.stdout
    done = run_hook(selected[:2])
    assert done.returncode == 0, done.stdout
