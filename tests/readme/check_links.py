#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Every relative link and image in the README and the docs pages points at a file that
exists (anchors inside a page are left out). Usage: check_links.py REPOSITORY_ROOT"""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1])
documents = [root / "README.md"] + sorted((root / "docs").glob("*.md"))
broken = []
for document in documents:
    text = document.read_text(encoding="utf-8")
    text = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)  # code is not links
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+:", target) or target.startswith("#"):
            continue
        path = (document.parent / target.split("#")[0]).resolve()
        if not path.exists():
            broken.append(f"{document.relative_to(root)}: {target}")
print(f"{len(documents)} documents; {len(broken)} broken links")
for line in broken:
    print("BROKEN " + line)
sys.exit(1 if broken else 0)
