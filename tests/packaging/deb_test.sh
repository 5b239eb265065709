#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The Debian package: `cpack -G DEB` from the build tree, its control fields and file list
# (dpkg-deb), then unpacked into a scratch root with `dpkg -x`, where the installed `tangent`
# bakes and the consumer project (tests/consumer) is built against ROOT/usr and run.
#   deb_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
source=$1 build=$2 work=$3
. "$(dirname "$0")/common.sh"
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }

echo "== cpack -G DEB"
(cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/out") >"$work/cpack.log" 2>&1 || { cat "$work/cpack.log"; exit 1; }
debs=("$work"/out/*.deb)
[ ${#debs[@]} -eq 1 ] && [ -f "${debs[0]}" ] || fail "cpack made ${debs[*]}, not one .deb"
deb=${debs[0]}
echo "$(basename "$deb"): $(du -h "$deb" | cut -f1)"

info=$(dpkg-deb --info "$deb")
field() { sed -n "s/^ $1: //p" <<<"$info"; }
[ "$(field Package)" = libtangent-dev ] || fail "Package is '$(field Package)'"
[ "$(field Version)" = "$(cache_value "$build" CMAKE_PROJECT_VERSION)" ] || fail "Version is '$(field Version)'"
[ -n "$(field Maintainer)" ] && [ -n "$(field Description)" ] || fail "no Maintainer or Description"
! grep -q ';' <<<"$info" || fail "a control field holds a CMake list separator (;)"
depends=$(field Depends)
echo "Depends: $depends"
required=(libopenmesh-dev libtbb-dev)
gltf=$(cache_value "$build" TANGENT_BUILD_GLTF)
[ "$gltf" = ON ] && required+=(libtinygltf-dev nlohmann-json3-dev libglm-dev libdraco-dev libmeshoptimizer-dev)
for package in "${required[@]}"; do
  grep -qE "(^|, )$package( |,|$)" <<<"$depends" || fail "Depends lacks $package"
done
# dpkg-shlibdeps added the run-time libraries of the executables (the C++ runtime at least).
grep -qE "(^|, )libstdc\+\+6 " <<<"$depends" || fail "Depends lacks the executables' run-time libraries (libstdc++6)"

contents=$(dpkg-deb --contents "$deb" | awk '{print $NF}')
expected=(./usr/include/tangent/tangent.hpp ./usr/lib/cmake/tangent/tangentConfig.cmake
          ./usr/lib/cmake/tangent/tangentConfigVersion.cmake ./usr/lib/cmake/tangent/tangentCoreTargets.cmake
          ./usr/lib/libtangent_core.a ./usr/share/doc/libtangent-dev/copyright)
[ "$gltf" = ON ] && expected+=(./usr/include/tangent/gltf.hpp ./usr/lib/cmake/tangent/tangentGltfTargets.cmake ./usr/lib/libtangent_gltf.a)
[ "$gltf" = ON ] && [ "$(cache_value "$build" TANGENT_BUILD_TOOLS)" = ON ] && expected+=(./usr/bin/tangent)
for path in "${expected[@]}"; do
  grep -qxF "$path" <<<"$contents" || fail "the package lacks $path"
done
echo "the package holds ${#expected[@]} expected files among $(wc -l <<<"$contents") entries"

root=$work/root
dpkg -x "$deb" "$root"
# The archives are shipped without debug sections (cmake/strip_static_libraries.cmake).
for archive in "$root"/usr/lib/libtangent_*.a; do
  sections=$(objdump -h "$archive")
  ! grep -q '\.debug_info' <<<"$sections" || fail "$(basename "$archive") still has its debug sections"
done
no_build_paths "$root/usr/lib/cmake/tangent" "$(cd "$source" && pwd)" "$(cd "$build" && pwd)"
build_consumer "$source/tests/consumer" "$work/core" "$root/usr" "$build" OFF
if [ "$gltf" = ON ]; then
  build_consumer "$source/tests/consumer" "$work/gltf" "$root/usr" "$build" ON
  if [ -x "$root/usr/bin/tangent" ]; then
    # The packaged command on the consumer's quad: it bakes and its own check passes.
    "$root/usr/bin/tangent" bake "$work/gltf/bake/quad.gltf" -o "$work/quad-tool.glb" --all --quiet
    "$root/usr/bin/tangent" check "$work/quad-tool.glb" --all
  fi
fi
echo "the Debian package unpacked and built against"
