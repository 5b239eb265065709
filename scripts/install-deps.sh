#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs every Debian 12 package the project needs to build, run and test. Idempotent:
# when everything is present it does nothing (no apt-get update).
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config git ccache
  libopenmesh-dev libglm-dev libtinygltf-dev nlohmann-json3-dev libopenimageio-dev
  libgtest-dev libgmock-dev libbenchmark-dev libtbb-dev linux-perf valgrind
  libdraco-dev libmeshoptimizer-dev gltfpack libxml2-utils dpkg-dev file
  assimp-testmodels python3 gnuplot-nox clang bc emscripten chromium
  pybind11-dev python3-dev python3-numpy python3-pytest python3-yaml python3-distributed python3-dask
  python3-venv python3-setuptools python3-wheel python3-build mypy
  libglfw3-dev libepoxy-dev libimgui-dev libfreetype-dev libstb-dev xvfb xauth libgl1-mesa-dri xdotool x11-apps
)
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
# Node.js runs the reference tools (Khronos validator, reference MikkTSpace); keep any
# node the machine already has, else take Debian's.
command -v node >/dev/null && command -v npm >/dev/null || missing+=(nodejs npm)
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
