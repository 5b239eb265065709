#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Runs the README's ```python blocks as written, in order, in one namespace, and the ```sh
blocks of its "## Python" section with bash, all from the repository root (the README's paths
are relative to it). The sh blocks run as on a fresh Debian machine: /usr/bin first on PATH
(Debian's python3, the one with numpy and dask), and with DESTDIR set to a temporary folder
so that the install command installs there instead of into the system.
Usage: run_python_blocks.py README"""
import os
import re
import subprocess
import sys
import tempfile

readme = sys.argv[1]
text = open(readme, encoding="utf-8").read()
blocks = re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)
if not blocks:
    sys.exit(f"{readme}: no python blocks")
os.chdir(os.path.dirname(os.path.abspath(readme)))
os.makedirs("build/python-demo", exist_ok=True)
namespace = {}
for number, block in enumerate(blocks, 1):
    print(f"--- README python block {number}")
    exec(compile(block, f"README.md python block {number}", "exec"), namespace)
print(f"{len(blocks)} README python blocks ran")

section = re.search(r"^## Python\n(.*?)^## ", text, flags=re.S | re.M)
shell_blocks = re.findall(r"^```sh\n(.*?)^```", section.group(1), flags=re.S | re.M) if section else []
if not shell_blocks:
    sys.exit(f"{readme}: the Python section has no sh blocks")
with tempfile.TemporaryDirectory(prefix="libtangent-readme-") as destdir:
    env = dict(os.environ, DESTDIR=destdir, PATH="/usr/bin:" + os.environ.get("PATH", ""))
    for number, block in enumerate(shell_blocks, 1):
        print(f"--- README Python section sh block {number}:\n{block}", flush=True)
        subprocess.run(["bash", "-euo", "pipefail", "-c", block], env=env, check=True)
    installed = [os.path.join(root, name) for root, _, names in os.walk(destdir) for name in names]
    if not any(name.endswith(".so") and "libtangent" in name for name in installed):
        sys.exit(f"the install block installed no module: {installed}")
print(f"{len(shell_blocks)} README Python sh blocks ran")
