#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# licence_test.sh SOURCE_DIR: the project is MIT-licensed (LICENSE) and every source file of
# ours (C++, C, GLSL, shell, Python, CMake, JavaScript/TypeScript) says so in an SPDX line
# within its first three lines. Build trees, build outputs (dist/: emscripten's and esbuild's)
# and installed npm modules are not ours.
set -euo pipefail
src=${1:?usage: licence_test.sh SOURCE_DIR}
grep -q '^MIT License$' "$src/LICENSE" || { echo "$src/LICENSE: not the MIT licence"; exit 1; }
# One awk over every file: the names of those without the line in their first three.
mapfile -t missing < <(find "$src" \( -name 'build*' -o -name dist -o -name node_modules -o -name .git -o -name '.devcarry' -o -name .venv \) -prune -o -type f \
           \( -name '*.cpp' -o -name '*.hpp' -o -name '*.c' -o -name '*.h' -o -name '*.glsl' -o -name '*.vert' \
              -o -name '*.frag' -o -name '*.sh' -o -name '*.py' -o -name '*.pyi' -o -name '*.cmake' -o -name '*.cmake.in' \
              -o -name CMakeLists.txt -o -name '*.mjs' -o -name '*.js' -o -name '*.ts' \) -print0 |
  xargs -0 awk 'FNR == 1 { if (NR > 1 && !found) print previous; found = 0; previous = FILENAME }
                FNR <= 3 && /SPDX-License-Identifier: MIT/ { found = 1 }
                END { if (NR > 0 && !found) print previous }')
for f in "${missing[@]}"; do echo "no SPDX-License-Identifier line in the first 3 lines: ${f#"$src"/}"; done
missing=${#missing[@]}
if [ "$missing" -ne 0 ]; then
  echo "$missing source file(s) without the licence line"
  exit 1
fi
echo "LICENSE is MIT and every source file carries the SPDX line"
