#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Renders the README's picture of the web viewer (docs/web-viewer.png): scripts/web.sh's page in
# headless Chromium with the demo scene (data/demo/scene.gltf, its .bin and textures fetched by
# the page), the lit view.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/web.sh >/dev/null
/usr/bin/python3 tests/web/page_screenshot.py build-web data/demo scene.gltf docs/web-viewer.png lit
