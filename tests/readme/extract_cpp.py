#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes one C++ program from the README's ```cpp blocks, in order, inside one main() that
first makes the arrays the blocks use (a unit quad), and afterwards checks what they computed.
The README's C++ then builds and runs as a test: a block that no longer compiles or runs fails."""
import re
import sys

readme, output = sys.argv[1], sys.argv[2]
blocks = re.findall(r"^```cpp\n(.*?)^```", open(readme, encoding="utf-8").read(), flags=re.S | re.M)
if not blocks:
    sys.exit(f"{readme}: no ```cpp block")
includes, body = [], []
for block in blocks:
    for line in block.splitlines():
        (includes if line.startswith("#include") else body).append(line)
program = "\n".join(
    ["// Generated from " + readme + " by tests/readme/extract_cpp.py: do not edit.",
     "#include <cmath>", "#include <cstdint>", "#include <cstdio>", "#include <vector>"]
    + includes
    + ["int main() {",
       "  // A unit quad in the xy plane, UVs = xy: the README's arrays.",
       "  std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};",
       "  std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};",
       "  std::vector<float> uvs = {0, 0, 1, 0, 1, 1, 0, 1};",
       "  std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};"]
    + ["  " + line for line in body]
    + ["  // What the blocks computed: one unit tangent along +x per corner, w = -1 (glTF).",
       "  for (std::size_t c = 0; c < indices.size(); ++c) {",
       "    const float* t = &tangents[4 * c];",
       "    if (std::abs(t[0] - 1) > 1e-6f || std::abs(t[1]) > 1e-6f || std::abs(t[2]) > 1e-6f || t[3] != -1.0f) {",
       "      std::printf(\"corner %zu: %g %g %g %g\\n\", c, t[0], t[1], t[2], t[3]);",
       "      return 1;",
       "    }",
       "  }",
       "  std::printf(\"README C++ blocks: %zu corners, %llu split vertices\\n\", indices.size(),",
       "              static_cast<unsigned long long>(report.splitVertices));",
       "  return report.corners == indices.size() ? 0 : 1;",
       "}", ""])
open(output, "w", encoding="utf-8").write(program)
