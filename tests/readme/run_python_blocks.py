#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Runs the ```python blocks of each file given (the README, docs/python.md) as written, in
order, one namespace per file, and the ```sh blocks about Python (the README's "## Python"
section, or the whole of a page whose title is "# Python") with bash, all from the repository
root (the documents' paths are relative to it). The sh blocks run as on a fresh Debian machine:
/usr/bin first on PATH (Debian's python3, the one with numpy and dask), and with DESTDIR set
to a temporary folder so that the install command installs there instead of into the system.
(The ```bash blocks, the pip install into a venv, are run by tests/packaging/pip_test.py.)
Usage: run_python_blocks.py FILE.md..."""
import os
import re
import subprocess
import sys
import tempfile

documents = [os.path.abspath(d) for d in sys.argv[1:]]
if not documents:
    sys.exit(__doc__)
root = os.path.dirname(documents[0])  # the README's folder: the repository root
os.chdir(root)
os.makedirs("build/python-demo", exist_ok=True)
shell_blocks = []
for document in documents:
    name = os.path.relpath(document, root)
    text = open(document, encoding="utf-8").read()
    blocks = re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)
    if not blocks:
        sys.exit(f"{name}: no python blocks")
    namespace = {}
    for number, block in enumerate(blocks, 1):
        print(f"--- {name} python block {number}", flush=True)
        exec(compile(block, f"{name} python block {number}", "exec"), namespace)
    print(f"{len(blocks)} {name} python blocks ran")
    section = re.search(r"^## Python\n(.*?)(?=^## |\Z)", text, flags=re.S | re.M)
    about_python = section.group(1) if section else text if text.startswith("# Python\n") else ""
    shell_blocks += [(name, block) for block in re.findall(r"^```sh\n(.*?)^```", about_python, flags=re.S | re.M)]
if not shell_blocks:
    sys.exit("no sh block about Python in " + ", ".join(documents))
with tempfile.TemporaryDirectory(prefix="libtangent-readme-") as destdir:
    env = dict(os.environ, DESTDIR=destdir, PATH="/usr/bin:" + os.environ.get("PATH", ""))
    for number, (name, block) in enumerate(shell_blocks, 1):
        print(f"--- {name} sh block {number}:\n{block}", flush=True)
        subprocess.run(["bash", "-euo", "pipefail", "-c", block], env=env, check=True)
    installed = [os.path.join(r, n) for r, _, names in os.walk(destdir) for n in names]
    if not any(n.endswith(".so") and "libtangent" in n for n in installed):
        sys.exit(f"the install block installed no module: {installed}")
print(f"{len(shell_blocks)} sh blocks about Python ran")
