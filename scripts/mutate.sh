#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Mutation check (not part of CI): applies small deliberate bugs to the core and the glTF
# layer, one at a time, to a copy of the source tree, rebuilds it and runs the tests that
# should notice; prints which tests caught each mutation and which mutations survived.
#
#   scripts/mutate.sh [NAME...]       every mutation, or only those named
#   TANGENT_MUTATE_DIR=/tmp/x          where the copy and its build live (kept between runs,
#                                      so that later runs and each mutation rebuild
#                                      incrementally; default /tmp/libtangent-mutate)
#
# The working tree is never written: the tracked and untracked (not ignored) files are copied
# to $TANGENT_MUTATE_DIR/src, ../shared is linked beside it and tests/node/node_modules into
# it. Each mutation is an exact text replacement that must match exactly once, or it is
# reported as stale and not counted: update it when the code it targets changes. The goal: every mutation caught by at
# least two tests, one of them independent of the library's own code (the reference C or npm
# MikkTSpace, the Khronos validator, values computed by hand in the test, tangents an
# exporter wrote): those are marked with *. The last line is the score: mutations caught
# (killed) out of those that build. The copy's mutated file is restored however the run ends.
# Not part of CI (one build and test run per mutation): run it nightly or by hand.
set -euo pipefail
source_dir=$(cd "$(dirname "$0")/.." && pwd)
work=${TANGENT_MUTATE_DIR:-/tmp/libtangent-mutate}
copy=$work/src build=$work/build
python=/usr/bin/python3

# Independent of the library's own code (see above).
independent='^(ReferenceC\.|MikkTSpaceReference\.|validator\.|SharedAssets\.MirrorTestHandedness|MeshFiles\.|Core\.(QuadExactFrame|TopLeftUvOriginNegatesWOnly|MirroredQuadsSplitSharedVertices|Cube24ExactFrames|EachWeightingGivesItsHandComputedFrame|TorusTangentFollowsU)$|Bake\.(MirroredColumnsSplitAndIndicesWiden|NormalTextureUvSetAndTextureTransformChooseTheFrame)$|Cli\.BakeWritesReportAndLeavesInputAlone$|(Boundaries/IndexBoundary|WeldIdentity|SplitOrder|ComponentTypes/CheckLimit|CheckLimits|Containment|MorphTangents)[./])'
# The tests each kind of mutation runs (CTest -R); tests/boundary_test.cpp's in both.
boundary_tests='^(Boundaries/IndexBoundary|WeldIdentity|SplitOrder|ComponentTypes/CheckLimit|CheckLimits|Containment|MorphTangents)[./]'
core_tests='^(Core|CoreNames|MikkTSpace|MikkTSpaceReference|Workspace|ReferenceC|Stress|StressReport|Check|CheckNegative|SharedAssets|MeshFiles)\.|^Methods/|^validator\.|'"$boundary_tests"
gltf_tests='^(Bake|BakeErrors|MeshFiles|Check|CheckNegative|Cli|SharedAssets)\.|RoundTrip|^MikkTSpaceReference\.(ObjInputThroughBake|SharedAssets)$|^validator\.|'"$boundary_tests"

names=() files=() tests=() olds=() news=()
# mutation NAME FILE TESTS OLD NEW: OLD must occur exactly once in FILE.
mutation() { names+=("$1"); files+=("$2"); tests+=("$3"); olds+=("$4"); news+=("$5"); }
mutation w-sign libtangent/core/src/mikktspace/grouping.cpp "$core_tests" \
  'const float w = orientation > 0 ? 1.0f : -1.0f;' \
  'const float w = orientation > 0 ? -1.0f : 1.0f;'
mutation w-convention-in-bake libtangent/gltf/src/bake/compute.cpp "$gltf_tests" \
  'options.uvOrigin = kGltfUvOrigin;' \
  'options.uvOrigin = UvOrigin::bottomLeft;'
mutation weighting-mikktspace-area libtangent/core/src/mikktspace/grouping.cpp "$core_tests" \
  'angle = std::max(angle, 1e-12);' \
  'const std::uint32_t c = list[member(scratch.items[i])];
      angle = std::max(0.5 * length(cross(a_.position(a_.indices[previousCorner(c)]) - here, a_.position(a_.indices[nextCorner(c)]) - here)), 1e-12);'
mutation weighting-lengyel-area libtangent/core/src/lengyel.cpp "$core_tests" \
  'case Weighting::angle: data.cornerWeights[corner] = cornerAngle(positions, k); break;' \
  'case Weighting::angle: data.cornerWeights[corner] = triangle.area; break;'
mutation projection-mikktspace libtangent/core/src/mikktspace/grouping.cpp "$core_tests" \
  'const F3 referenceS = referenceProjected({frame[0], frame[1], frame[2]}, rawNormal);' \
  'const F3 referenceS{frame[0], frame[1], frame[2]};'
mutation projection-lengyel libtangent/core/src/lengyel_groups.cpp "$core_tests" \
  'group.normal = data.cornerNormals[key.corner];' \
  'group.normal = Vec3(0, 0, 1);  // projected onto +z, not the corner normal'
mutation uv-set libtangent/gltf/src/read/primitive.cpp "$gltf_tests" \
  'const std::string uvName = "TEXCOORD_" + std::to_string(needs.texCoord);
  const int uvAccessor' \
  'const std::string uvName = "TEXCOORD_0";
  const int uvAccessor'
mutation index-widening libtangent/gltf/src/bake/emit.cpp "$gltf_tests" \
  'if (outCount - 1 >= 65535 && indexComponentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)' \
  'if (false)'
mutation attribute-carry libtangent/gltf/src/bake/emit.cpp "$gltf_tests" \
  'if (name != "TANGENT") carried.emplace_back(name, accessorRef.get<int>());' \
  "if (name != \"TANGENT\" && name[0] != '_') carried.emplace_back(name, accessorRef.get<int>());  // custom attributes not gathered"

# The classes of issue 42 (tests/boundary_test.cpp), one mutation each.
mutation index-restart-boundary libtangent/gltf/src/bake/emit.cpp "$gltf_tests" \
  'if (outCount - 1 >= 65535 && indexComponentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)' \
  'if (outCount - 1 > 65535 && indexComponentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)'
mutation weld-by-bits libtangent/core/src/weld.cpp "$core_tests" \
  'if (mesh.positions[3 * a + i] != mesh.positions[3 * b + i] || mesh.normals[3 * a + i] != mesh.normals[3 * b + i])' \
  'if (bitCast<std::uint32_t>(mesh.positions[3 * a + i]) != bitCast<std::uint32_t>(mesh.positions[3 * b + i]) || bitCast<std::uint32_t>(mesh.normals[3 * a + i]) != bitCast<std::uint32_t>(mesh.normals[3 * b + i]))'
mutation split-last-corner-keeps libtangent/core/src/outputs.cpp "$core_tests" \
  'if (entries[j].corner < firstCorner) firstCorner = entries[j].corner, firstAt = j;' \
  'if (entries[j].corner > firstCorner) firstCorner = entries[j].corner, firstAt = j;'
mutation check-rounding-twice-as-loose libtangent/gltf/src/check/tangent_rules.cpp "$gltf_tests" \
  'const double vectorError = std::sqrt(3.0) * rounding.componentError;' \
  'const double vectorError = 2 * std::sqrt(3.0) * rounding.componentError;'
mutation containment-string-prefix libtangent/gltf/src/read/uri.cpp "$gltf_tests" \
  'bool isInside(const fs::path& path, const fs::path& root) {' \
  'bool isInside(const fs::path& path, const fs::path& root) {
  if (const std::string r = root.lexically_normal().string(); true) return path.lexically_normal().string().starts_with(r.ends_with("/") ? r.substr(0, r.size() - 1) : r);'
mutation morph-delta-sign libtangent/gltf/src/bake/compute.cpp "$gltf_tests" \
  'deltas[3 * v + i] = morphed[i] - split.tangents[4 * v + i];' \
  'deltas[3 * v + i] = split.tangents[4 * v + i] - morphed[i];'

mkdir -p "$copy"
ln -sfn "$(cd "$source_dir/.." && pwd)/shared" "$work/shared"
# Copy with the files' own times (tar keeps them), so unchanged files do not rebuild.
(cd "$source_dir" && git ls-files -co --exclude-standard -z | tar --null -T - -cf -) | tar -xf - -C "$copy"
# A file a mutation touched gets its source's older time back from tar, which ninja would take
# for up to date against an object built mutated: those files (listed by restore) are touched.
if [ -f "$work/touched" ]; then
  while read -r touched; do touch "$copy/$touched"; done <"$work/touched"
fi
if [ -d "$source_dir/tests/node/node_modules" ]; then
  ln -sfn "$source_dir/tests/node/node_modules" "$copy/tests/node/node_modules"
fi
if [ ! -f "$build/build.ninja" ]; then
  cmake -S "$copy" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTANGENT_BUILD_VIEWER=OFF \
    -DTANGENT_BUILD_BENCHMARKS=OFF -DTANGENT_BUILD_PYTHON=OFF >/dev/null
fi
targets=(tangent tangent-test-assets tangent_tests tangent_reference_c_tests tangent_boundary_tests)
echo "== unmutated build and tests (all must pass)"
cmake --build "$build" --parallel 2 --target "${targets[@]}" >/dev/null
rm -f "$work/touched"

# apply FILE OLD NEW: replaces the one occurrence of OLD, or fails.
apply() {
  "$python" - "$1" "$2" "$3" <<'EOF' || return 1
import pathlib, sys
path, old, new = pathlib.Path(sys.argv[1]), sys.argv[2], sys.argv[3]
text = path.read_text()
count = text.count(old)
if count != 1:
    sys.exit(f"mutation does not apply: {path} has {count} occurrences of:\n{old}")
path.write_text(text.replace(old, new))
EOF
  touch "$1"
}

# run_tests REGEX: prints the names of the failing tests (none: empty).
run_tests() {
  local log=$work/ctest.log
  ctest --test-dir "$build" -R "$1" -j 2 --timeout 900 >"$log" 2>&1 || true
  grep -E '^[[:space:]]*[0-9]+ - .* \((Failed|Timeout|SEGFAULT|Subprocess aborted|Exception|Child aborted)' "$log" |
    sed -E 's/^[[:space:]]*[0-9]+ - ([^ ]+) .*/\1/' || true
}

baseline=$(run_tests "$core_tests|$gltf_tests")
if [ -n "$baseline" ]; then
  echo "tests fail without any mutation:"; echo "$baseline"; exit 1
fi

# The copy's mutated file goes back to its pristine bytes however the run ends (a failed
# build or test command, set -e, Ctrl-C, kill): the next run then starts from the same sources.
mutated_file=""
restore() {
  if [ -n "$mutated_file" ]; then
    cp -p "$work/pristine" "$copy/$mutated_file"
    touch "$copy/$mutated_file"
    echo "$mutated_file" >>"$work/touched"
    mutated_file=""
  fi
}
trap restore EXIT
trap 'restore; exit 130' INT TERM

selected=("$@")
rows=()
killed=0 survived=0 stillborn=0 stale=0
for i in "${!names[@]}"; do
  name=${names[$i]} file=${files[$i]}
  if [ ${#selected[@]} -gt 0 ] && [[ ! " ${selected[*]} " == *" $name "* ]]; then continue; fi
  echo "== $name ($file)"
  cp -p "$copy/$file" "$work/pristine"
  mutated_file=$file
  if ! apply "$copy/$file" "${olds[$i]}" "${news[$i]}"; then
    restore
    echo "   STALE: the code it targets changed; update the mutation"
    rows+=("$name|stale (does not apply)|0|0|")
    stale=$((stale + 1))
    continue
  fi
  if cmake --build "$build" --parallel 2 --target "${targets[@]}" >"$work/build.log" 2>&1; then
    caught=$(run_tests "${tests[$i]}")
  else
    tail -20 "$work/build.log"
    caught="(does not build)"
  fi
  restore
  count=0 independent_count=0 list=""
  while read -r test; do
    [ -n "$test" ] || continue
    count=$((count + 1))
    mark=""
    if [[ $test =~ $independent ]]; then mark="*"; independent_count=$((independent_count + 1)); fi
    list+="${list:+, }$test$mark"
  done <<<"$caught"
  if [ "$caught" = "(does not build)" ]; then verdict="does not build" stillborn=$((stillborn + 1))
  elif [ "$count" -eq 0 ]; then verdict="SURVIVED" survived=$((survived + 1))
  elif [ "$count" -ge 2 ] && [ "$independent_count" -ge 1 ]; then verdict="caught" killed=$((killed + 1))
  else verdict="caught (thinly)" killed=$((killed + 1))
  fi
  echo "   $verdict: $count tests, $independent_count independent"
  rows+=("$name|$verdict|$count|$independent_count|$list")
done
# Leave the copy's build unmutated for the next run.
cmake --build "$build" --parallel 2 --target "${targets[@]}" >/dev/null
rm -f "$work/touched"

echo
echo "| mutation | result | tests failing | of them independent (*) | tests |"
echo "|---|---|---|---|---|"
for row in "${rows[@]}"; do
  IFS='|' read -r name verdict count independent_count list <<<"$row"
  echo "| $name | $verdict | $count | $independent_count | $list |"
done
echo
# Mutations that do not build are not counted (the compiler caught them, not the tests).
echo "score: $killed killed / $((killed + survived)) mutations ($survived survived, $stillborn did not build, $stale stale)"
