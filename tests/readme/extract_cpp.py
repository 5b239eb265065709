#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes one C++ program from the ```cpp blocks of the README and the docs pages given, each
file's blocks in order inside a scope of their own in one main(), which first makes the arrays
the blocks use (a unit quad) and after each file's blocks checks what they computed. The
documented C++ then builds and runs as a test: a block that no longer compiles or runs fails.
Usage: extract_cpp.py OUTPUT.cpp FILE.md..."""
import os
import re
import sys

output, documents = sys.argv[1], sys.argv[2:]
if not documents:
    sys.exit(__doc__)
includes, scopes = [], []
for document in documents:
    blocks = re.findall(r"^```cpp\n(.*?)^```", open(document, encoding="utf-8").read(), flags=re.S | re.M)
    if not blocks:
        sys.exit(f"{document}: no ```cpp block")
    name = os.path.basename(document)
    body = []
    for block in blocks:
        for line in block.splitlines():
            (includes if line.startswith("#include") else body).append(line)
    scopes += [f"  {{  // {name}: {len(blocks)} block(s)"]
    scopes += ["    " + line for line in body]
    scopes += [
        "    // What the blocks computed: one unit tangent along +x per corner, w = -1 (glTF).",
        "    for (std::size_t c = 0; c < indices.size(); ++c) {",
        "      const float* t = &tangents[4 * c];",
        "      if (std::abs(t[0] - 1) > 1e-6f || std::abs(t[1]) > 1e-6f || std::abs(t[2]) > 1e-6f || t[3] != -1.0f) {",
        f"        std::printf(\"{name}: corner %zu: %g %g %g %g\\n\", c, t[0], t[1], t[2], t[3]);",
        "        return 1;",
        "      }",
        "    }",
        f"    std::printf(\"{name} C++ blocks: %zu corners, %llu split vertices\\n\", indices.size(),",
        "                static_cast<unsigned long long>(report.splitVertices));",
        "    if (report.corners != indices.size()) return 1;",
        "  }"]
program = "\n".join(
    ["// Generated from " + ", ".join(documents) + " by tests/readme/extract_cpp.py: do not edit.",
     "#include <cmath>", "#include <cstdint>", "#include <cstdio>", "#include <vector>"]
    + sorted(set(includes), key=includes.index)
    + ["int main() {",
       "  // A unit quad in the xy plane, UVs = xy: the documents' arrays.",
       "  std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};",
       "  std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};",
       "  std::vector<float> uvs = {0, 0, 1, 0, 1, 1, 0, 1};",
       "  std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};"]
    + scopes
    + ["  return 0;", "}", ""])
open(output, "w", encoding="utf-8").write(program)
