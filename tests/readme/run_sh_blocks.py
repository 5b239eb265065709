#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Runs ```sh blocks of the README and the docs pages as written, in order, with bash from the
repository root, where their paths start (build/bin is the build that scripts/test.sh makes).
An item is FILE (every sh block of it) or FILE#SECTION (the blocks of its "## SECTION"). A
block that fails fails the test.
Usage: run_sh_blocks.py ROOT ITEM..."""
import os
import re
import subprocess
import sys

root, items = sys.argv[1], sys.argv[2:]
if not items:
    sys.exit(__doc__)
os.chdir(root)
os.makedirs("build/readme", exist_ok=True)
os.makedirs("build/docs", exist_ok=True)
ran = 0
for item in items:
    name, _, section = item.partition("#")
    text = open(name, encoding="utf-8").read()
    if section:
        match = re.search(rf"^## {re.escape(section)}\n(.*?)(?=^## |\Z)", text, flags=re.S | re.M)
        if not match:
            sys.exit(f"{name} has no section '## {section}'")
        text = match.group(1)
    blocks = re.findall(r"^```sh\n(.*?)^```", text, flags=re.S | re.M)
    if not blocks:
        sys.exit(f"{item}: no sh block")
    for block in blocks:
        print(f"--- {item}:\n{block}", flush=True)
        subprocess.run(["bash", "-euo", "pipefail", "-c", block], check=True)
        ran += 1
print(f"{ran} sh blocks ran")
