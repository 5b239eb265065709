#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""docs/design.md's claims about where things live, checked against the tree: every file it names
in backquotes (`bake/emit.cpp`, `scene.hpp`) is a tracked file (by path or name), and every code
name it cites (`PrimitiveBaker`, `flatTriangleFrames`, `OutputDocument::finish`) is a word of
the sources. A file moved or a function renamed without the design following fails here, naming
the stale mention. Usage: check_design_names.py SOURCE_DIR"""
import pathlib
import re
import subprocess
import sys

FILE = re.compile(r"[\w./-]+\.(cpp|hpp|h|glsl|vert|frag|md|sh|py|mjs|inc|json|txt)")
CAMEL = re.compile(r"[a-z][a-z0-9]*[A-Z]\w*|[A-Z][a-z0-9]+[A-Z]\w*")
SOURCE = re.compile(r"\.(cpp|hpp|h|inc|glsl|vert|frag|py|mjs|js|cmake|txt|sh)$")


def main(root: pathlib.Path) -> int:
    doc = (root / "docs" / "design.md").read_text()
    files = subprocess.run(["git", "-C", str(root), "ls-files"], capture_output=True, text=True, check=True).stdout.split()
    if not files:
        print("check_design_names: no tracked files (not a git checkout?)", file=sys.stderr)
        return 1
    sources = "\n".join((root / f).read_text(errors="replace") for f in files if SOURCE.search(f) and (root / f).is_file())
    words = set(re.findall(r"\w+", sources))
    stale, checked = [], 0
    for token in sorted(set(re.findall(r"`([^`\n]+)`", doc))):
        t = token.strip()
        if FILE.fullmatch(t):
            checked += 1
            if not any(f == t or f.endswith("/" + t) for f in files):
                stale.append(f"file `{t}`: no tracked file has this path or name")
            continue
        # Code names: a camelCase word, or a qualified name (its own parts, before any call).
        parts = re.split(r"::", t.split("(")[0]) if "::" in t else [t]
        if not all(re.fullmatch(r"\w+", p) for p in parts):
            continue
        cited = [p for p in parts if CAMEL.fullmatch(p)]
        if "::" in t:
            cited = [p for p in parts if p not in ("std", "tangent", "detail")]
        for name in cited:
            checked += 1
            if name not in words:
                stale.append(f"name `{name}` (in `{t}`): not in the sources")
    for line in stale:
        print(f"docs/design.md: {line}")
    print(f"checked {checked} names in docs/design.md, {len(stale)} stale")
    return 1 if stale or checked < 50 else 0


if __name__ == "__main__":
    sys.exit(main(pathlib.Path(sys.argv[1])))
