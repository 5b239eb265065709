# SPDX-License-Identifier: MIT
"""The one option table (libtangent.option_table(), made from tangent/option_table.hpp) against
every front end that takes options: `tangent bake --help` and `tangent check --help`, Python's
signatures and stubs (__init__.pyi), the npm package's optionChoices and index.d.ts. A front
end that gains, loses or renames an option, or changes a choice or default, fails here; and
Python's options give the command line's bytes and messages."""
import ast
import inspect
import os
import pathlib
import re
import subprocess

import pytest

import libtangent

SOURCE = pathlib.Path(os.environ.get("TANGENT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = os.environ.get("TANGENT_CLI")
TABLE = libtangent.option_table()
FUNCTIONS = {"compute_tangents": libtangent.compute_tangents, "bake": libtangent.bake,
             "bake_tree": libtangent.bake_tree, "check": libtangent.check, "check_tree": libtangent.check_tree}
COMMAND_OF = {"check_tree": "check"}  # check_tree() takes check()'s options
DEMO = SOURCE / "data" / "demo" / "demo.gltf"


def rows(command, front_end):
    return [row for row in TABLE if command in row["commands"] and front_end in row["front_ends"]]


def help_options(command):
    """The long options `tangent COMMAND --help` lists, with their value names."""
    text = subprocess.run([CLI, command, "--help"], capture_output=True, text=True, check=True).stdout
    found = {}
    for match in re.finditer(r"^  (?:-\w, )?--([a-z-]+)(?: (\S+))?", text, re.M):
        found[match.group(1)] = match.group(2) or ""
    return found


@pytest.fixture(autouse=True)
def need_cli(request):
    if CLI is None and "cli" in request.node.name:
        pytest.skip("TANGENT_CLI is not set (CTest sets it)")


def test_the_table_is_well_formed():
    seen = set()
    for row in TABLE:
        assert row["commands"] and row["front_ends"] and row["help"], row
        for command in row["commands"]:
            assert (row["name"], command) not in seen, f"{row['name']} twice in {command}"
            seen.add((row["name"], command))
        if row["kind"] == "choice":
            assert row["default"] in row["choices"], row
        assert re.fullmatch(r"[a-z][a-z-]*[a-z]", row["name"]), row["name"]


@pytest.mark.parametrize("command, commands", [("bake", ("bake", "bake_tree")), ("check", ("check",))])
def test_cli_help_lists_the_tables_options(command, commands):
    expected = {row["name"]: row["value_name"] for name in commands for row in rows(name, "cli")}
    assert help_options(command) == {**expected, "help": ""}


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_python_signatures_are_the_tables(name):
    parameters = inspect.signature(FUNCTIONS[name]).parameters.values()
    keywords = {p.name: p.default for p in parameters if p.kind == inspect.Parameter.KEYWORD_ONLY}
    assert keywords == {row["python"]: row["default"] for row in rows(COMMAND_OF.get(name, name), "python")}
    for row in rows(COMMAND_OF.get(name, name), "python"):
        assert row["python"] + ":" in FUNCTIONS[name].__doc__, (name, row["python"])


def stub_annotation(row):
    if row["kind"] == "flag":
        return "bool"
    if row["kind"] == "choice":
        return "Literal[" + ", ".join(repr(choice) for choice in row["choices"]) + "]"
    if row["kind"] == "integer":
        return "int"
    if row["kind"] == "number":
        return "float" if row["default"] is not None else "Optional[float]"
    if row["kind"] == "path":
        return "Optional[PathLike]"
    if row["kind"] == "list":
        return "Optional[Sequence[str]]"
    return "Optional[str]"


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_stubs_are_the_tables(name):
    tree = ast.parse((SOURCE / "python" / "libtangent" / "__init__.pyi").read_text())
    [function] = [node for node in tree.body if isinstance(node, ast.FunctionDef) and node.name == name]
    stubbed = {arg.arg: (ast.unparse(arg.annotation), ast.literal_eval(default))
               for arg, default in zip(function.args.kwonlyargs, function.args.kw_defaults)}
    expected = {row["python"]: (stub_annotation(row), row["default"]) for row in rows(COMMAND_OF.get(name, name), "python")}
    lines = "\n".join(f"    {key}: {annotation} = {default!r}," for key, (annotation, default) in expected.items())
    assert stubbed == expected, f"__init__.pyi's {name}() should take, after `*,`:\n{lines}"


def test_npm_choices_and_types_are_the_tables():
    package = SOURCE / "wasm" / "package"
    script = (package / "index.mjs").read_text()
    block = re.search(r"export const optionChoices = Object\.freeze\(\{(.*?)\n\}\);", script, re.S).group(1)
    choices = {key: re.findall(r"'([^']*)'", values) for key, values in re.findall(r"(\w+): Object\.freeze\(\[([^\]]*)\]\)", block)}
    npm_rows = rows("compute_tangents", "npm")
    # The default first: index.mjs takes choices[0] for an option left out.
    assert choices == {row["npm"]: [row["default"]] + [c for c in row["choices"] if c != row["default"]] for row in npm_rows}
    types = (package / "index.d.ts").read_text()
    aliases = {name: re.findall(r"'([^']*)'", union) for name, union in re.findall(r"export type (\w+) = ([^;]*);", types)}
    for row in npm_rows:
        declared = re.findall(rf"^\s+{row['npm']}\?: (\w+);", types, re.M)
        assert declared, f"index.d.ts declares no option {row['npm']}"
        for alias in declared:
            assert sorted(aliases[alias]) == sorted(row["choices"]), (row["npm"], alias)
        assert re.search(rf"readonly {row['npm']}: readonly \w+\[\];", types), f"optionChoices.{row['npm']} is not typed"


def test_python_errors_are_the_cli_words_cli(tmp_path):
    cases = [("normals", "soft"), ("tangent_format", "half"), ("crease_angle", 200.0), ("threads", 300)]
    for name, value in cases:
        with pytest.raises(ValueError) as raised:
            libtangent.bake(DEMO, tmp_path / "x.glb", **{name: value})
        python_words = str(raised.value).split(f"{name}: ", 1)[1]
        text = f"{value:g}" if isinstance(value, float) else str(value)
        done = subprocess.run([CLI, "bake", str(DEMO), str(tmp_path / "x.glb"), "--" + name.replace("_", "-"), text],
                              capture_output=True, text=True)
        assert done.returncode == 2
        cli_words = done.stderr.split(": ", 2)[2].rsplit(" (see tangent bake --help)", 1)[0]
        assert python_words.replace("200.0", "200") == cli_words, (name, python_words, cli_words)
    with pytest.raises(TypeError, match="unexpected keyword argument 'normal'"):
        libtangent.bake(DEMO, tmp_path / "x.glb", normal="flat")


def test_every_bake_option_gives_the_cli_bytes_cli(tmp_path):
    """Each of bake's options that changes the output, set to each of its other values, in
    Python and on the command line: the same bytes."""
    source = tmp_path / "in.glb"
    subprocess.run([CLI, "bake", str(DEMO), str(source), "--quiet"], check=True)  # a .glb with TANGENT, so overwrite matters
    values = []
    for row in rows("bake", "python"):
        if "cli" not in row["front_ends"] or row["name"] in ("threads", "asset-root"):
            continue
        if row["kind"] == "flag":
            values.append((row, True))
        elif row["kind"] == "choice":
            values += [(row, choice) for choice in row["choices"] if choice != row["default"]]
        elif row["kind"] == "number":
            values.append((row, row["max"] / 4))
    assert {row["python"] for row, _ in values} >= {"method", "tangent_format", "normals", "overwrite", "all", "keep_external"}
    for row, value in values:
        extra = {"normals": "smooth"} if row["python"] == "crease_angle" else {}
        ours, theirs = tmp_path / f"py-{row['name']}-{value}" / "o.glb", tmp_path / f"cli-{row['name']}-{value}" / "o.glb"
        ours.parent.mkdir()
        theirs.parent.mkdir()
        libtangent.bake(source, ours, **{row["python"]: value}, **extra)
        args = ["--" + row["name"]] + ([] if value is True else [f"{value:g}" if isinstance(value, float) else value])
        args += ["--normals", "smooth"] if extra else []
        subprocess.run([CLI, "bake", str(source), "-o", str(theirs), "--quiet", *args], check=True)
        assert ours.read_bytes() == theirs.read_bytes(), (row["name"], value)


def test_manifest_options_are_bake_trees(tmp_path):
    (tmp_path / "in").mkdir()
    (tmp_path / "in" / "a.gltf").write_bytes(DEMO.read_bytes())
    for name in ("demo.bin",):
        (tmp_path / "in" / name).write_bytes((DEMO.parent / name).read_bytes())
    import json
    for options in ({}, {"method": "lengyel", "weighting": "area", "normals": "smooth", "crease_angle": 30.0}):
        out = tmp_path / f"out-{len(options)}"
        libtangent.bake_tree(tmp_path / "in", out, **options)
        manifest = json.loads((out / "tangent-manifest.json").read_text())
        assert manifest["options"] == libtangent.manifest_options(**options)
