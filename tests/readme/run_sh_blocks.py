#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Runs the ```sh blocks of the README's usage sections (Bake, Check in CI, View) as written,
in order, with bash from the repository root, where the README's paths start (build/bin is
the build that scripts/test.sh makes). A block that fails fails the test.
Usage: run_sh_blocks.py README.md SECTION..."""
import os
import re
import subprocess
import sys

readme, sections = os.path.abspath(sys.argv[1]), sys.argv[2:]
text = open(readme, encoding="utf-8").read()
os.chdir(os.path.dirname(readme))
os.makedirs("build/readme", exist_ok=True)
ran = 0
for name in sections:
    match = re.search(rf"^## {re.escape(name)}\n(.*?)(?=^## |\Z)", text, flags=re.S | re.M)
    if not match:
        sys.exit(f"README.md has no section '## {name}'")
    blocks = re.findall(r"^```sh\n(.*?)^```", match.group(1), flags=re.S | re.M)
    if not blocks:
        sys.exit(f"README.md section '{name}' has no sh block")
    for block in blocks:
        print(f"--- README '{name}':\n{block}", flush=True)
        subprocess.run(["bash", "-euo", "pipefail", "-c", block], check=True)
        ran += 1
print(f"{ran} README sh blocks ran")
