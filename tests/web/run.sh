#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# ctest web.viewer: builds the web viewer (scripts/web.sh; build-web/ is kept between runs, so
# only what changed compiles) and compares it in headless Chromium with the desktop viewer
# (tests/web/web_viewer_test.py), then uses the page's controls (tests/web/page_controls_test.py).
# Skips (77) where Chromium or emscripten is missing or ../shared/assets is absent; under CI=true
# those fail instead.
# Usage: tests/web/run.sh BUILD_DIR XVFB_RUN
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$1 xvfb=$2
skip() {
  if [ "${CI:-}" = true ]; then echo "FAIL (CI=true): $1"; exit 1; fi
  echo "SKIP: $1"; exit 77
}
command -v chromium >/dev/null || skip "chromium is not installed (scripts/install-deps.sh installs Debian's chromium)"
command -v em++ >/dev/null || skip "emscripten is not installed (scripts/install-deps.sh installs it)"
[ -d "$root/../shared/assets" ] || skip "../shared/assets is absent: the web viewer's comparison needs the shared assets"
start=$(date +%s)
TANGENT_JOBS=${TANGENT_JOBS:-2} "$root/scripts/web.sh"
echo "web build: $(( $(date +%s) - start )) s"
# scripts/web.sh --serve PORT (the README's command) serves the page on 127.0.0.1 and says where.
port=$(( 20000 + RANDOM % 20000 ))
log=$(mktemp)
"$root/scripts/web.sh" --serve "$port" >"$log" 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null || true; rm -f "$log"' EXIT
for _ in $(seq 100); do
  grep -q "http://127.0.0.1:$port/" "$log" && /usr/bin/python3 -c "import urllib.request,sys; sys.exit(b'tangent-view.js' not in urllib.request.urlopen(sys.argv[1]).read())" "http://127.0.0.1:$port/index.html" 2>/dev/null && break
  sleep 0.2
done
/usr/bin/python3 -c "import urllib.request,sys; urllib.request.urlopen(sys.argv[1]).read()" "http://127.0.0.1:$port/index.html" \
  || { echo "FAIL: scripts/web.sh --serve $port does not serve index.html"; cat "$log"; exit 1; }
echo "scripts/web.sh --serve: $(grep -o 'http://127.0.0.1:[0-9]*/[^ ]*' "$log" | head -1) serves the page"
kill "$server"; wait "$server" 2>/dev/null || true
status=0
/usr/bin/python3 "$here/web_viewer_test.py" --build-web "$root/build-web" --tangent-view "$build/bin/tangent-view" \
  --tangent "$build/bin/tangent" --xvfb-run "$xvfb" --assets "$root/../shared/assets" --demo "$root/data/demo" --out "$build/tests/web" \
  || status=1
# The page's controls (a finding clicked, the animation timeline, a second file to compare) on generated assets.
/usr/bin/python3 "$here/page_controls_test.py" --build-web "$root/build-web" --tangent-view "$build/bin/tangent-view" \
  --tangent "$build/bin/tangent" --make-data "$build/bin/tangent-make-data" --xvfb-run "$xvfb" --out "$build/tests/web-controls" \
  || status=1
exit $status
