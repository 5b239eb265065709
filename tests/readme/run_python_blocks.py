#!/usr/bin/env python3
"""Runs the README's ```python blocks as written, in order, in one namespace, from the
repository root (the README's paths are relative to it). Usage: run_python_blocks.py README"""
import os
import re
import sys

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
