#!/usr/bin/env bash
# Speed and error against run time, with the peers measured in the same run on the same inputs.
#   - tangent bench: error against run time on analytic surfaces (+ CSV/JSON, plot via gnuplot)
#   - tangent-kernel-bench (Google Benchmark): the library call and its phases, 1 and 2 threads
#   - the reference MikkTSpace kernel (npm mikktspace, WebAssembly) on the same spheres
#   - whole-process runs on generated UV spheres of ~1e5, 1e6 and 4e6 triangles: tangent bake,
#     gltf-transform tangents (npm @gltf-transform/cli) and assimp export -cts (Debian
#     assimp-utils), median wall time and peak memory (GNU time)
# Writes docs/benchmarks.md, docs/bench-plot.png and .svg, docs/bench.csv, and the tables
# between the bench markers of README.md.
# Usage: scripts/bench.sh [--quick]   (--quick: small sizes, one run each; CI's smoke test)
set -euo pipefail
cd "$(dirname "$0")/.."
quick=0
[ "${1:-}" = "--quick" ] && quick=1
scripts/install-deps.sh
dpkg-query -W -f='${Status}' assimp-utils 2>/dev/null | grep -q "install ok installed" || \
  { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq assimp-utils time; }
[ -x /usr/bin/time ] || DEBIAN_FRONTEND=noninteractive apt-get install -y -qq time
(cd bench/node && npm ci --no-audit --no-fund --loglevel=error)
scripts/build.sh build >/dev/null
out=build/bench
mkdir -p "$out"
if [ $quick = 1 ]; then segments=(100); runs=1; max=10000; kernel_filter='LibraryCall/triangles:100000/'; else segments=(224 707 1414); runs=3; max=1000000; kernel_filter='.'; fi

echo "== error against run time"
build/bin/tangent bench --max-triangles $max --repeats $runs --out-dir "$out/error" > "$out/error.txt"
tail -n 3 "$out/error.txt"

echo "== kernel (Google Benchmark)"
build/bin/tangent-kernel-bench --benchmark_filter="$kernel_filter" --benchmark_repetitions=$runs \
  --benchmark_report_aggregates_only=$([ $runs -gt 1 ] && echo true || echo false) --benchmark_format=json > "$out/kernel.json"

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
measure() {  # measure LABEL COMMAND...: prints "median_seconds max_rss_kb"
  shift  # the label only documents the call
  local times=() rss=()
  for _ in $(seq $runs); do
    /usr/bin/time -f "%e %M" -o "$out/time.txt" "$@" >/dev/null 2>&1 || { echo "failed: $*" >&2; echo "nan nan"; return; }
    read -r t m < "$out/time.txt"
    times+=("$t"); rss+=("$m")
  done
  echo "$(printf '%s\n' "${times[@]}" | median) $(printf '%s\n' "${rss[@]}" | sort -g | tail -1)"
}

rows=()
for n in "${segments[@]}"; do
  build/bin/tangent-make-data --sphere "$n" "$out/spheres" >/dev/null
  input="$out/spheres/sphere-$n.gltf"
  triangles=$((2 * n * (n - 1)))
  read -r ours ours_kb <<<"$(measure bake build/bin/tangent bake "$input" -o "$out/ours.glb" -q)"
  read -r gt gt_kb <<<"$(measure gltf-transform node bench/node/node_modules/@gltf-transform/cli/bin/cli.js tangents "$input" "$out/gt.glb")"
  read -r as as_kb <<<"$(measure assimp assimp export "$input" "$out/assimp.assbin" -fassbin -cts)"
  kernel_runs=$runs; [ $triangles -gt 2000000 ] && kernel_runs=1  # the reference needs minutes there
  kernel=$(cd bench/node && node mikktspace_kernel.mjs "$triangles" "$kernel_runs")
  rows+=("$triangles $ours $ours_kb $gt $gt_kb $as $as_kb $(sed -n 's/.*"medianMs":\([0-9.]*\).*/\1/p' <<<"$kernel")")
  echo "sphere $n: $triangles triangles, bake ${ours}s (${ours_kb} kB), gltf-transform ${gt}s (${gt_kb} kB), assimp ${as}s (${as_kb} kB), npm mikktspace kernel $(sed -n 's/.*"medianMs":\([0-9.]*\).*/\1/p' <<<"$kernel") ms"
done

# The report.
python3 - "$out" "${rows[@]}" <<'PY'
import json, sys, platform, subprocess, os
out, rows = sys.argv[1], [r.split() for r in sys.argv[2:]]
kernel = json.load(open(os.path.join(out, "kernel.json")))
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), platform.processor())
def k(name):
    found = [b for b in kernel["benchmarks"] if b["name"].startswith(name)]
    for b in found:  # the median of repetitions, else the single run
        if b.get("aggregate_name") == "median":
            return b["real_time"]
    return found[0]["real_time"] if found else float("nan")
lines = ["# Benchmarks", "",
         f"Machine: {cpu}, {os.cpu_count()} hardware threads, {platform.system()} {platform.release()}. "
         "Medians of repeated runs measured by `scripts/bench.sh` in one run; ratios against peers measured in the same run.", "",
         "## Whole process on generated UV spheres (glTF with a normal-mapped material)", "",
         "| triangles | tangent bake s | peak MB | gltf-transform tangents s | peak MB | assimp export -cts s | peak MB | bake speed-up vs gltf-transform | bake memory vs gltf-transform |",
         "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
for t, o, okb, g, gkb, a, akb, km in rows:
    lines.append(f"| {int(t):,} | {float(o):.2f} | {int(okb)/1024:.0f} | {float(g):.2f} | {int(gkb)/1024:.0f} | {float(a):.2f} | {int(akb)/1024:.0f} | "
                 f"{float(g)/float(o):.1f}x | {int(okb)/int(gkb):.2f}x |")
lines += ["", "assimp's glTF 2 exporter drops tangents, so assimp is timed exporting to its own `assbin` format, which keeps them.", "",
          "## Library call against the reference MikkTSpace kernel (npm `mikktspace`, WebAssembly)", "",
          "The library call includes building the OpenMesh mesh and producing the per-corner output; the reference gets de-indexed arrays.", "",
          "| triangles | npm mikktspace ms | library 1 thread ms | speed-up | library 2 threads ms | 2 vs 1 thread (compute phase) |",
          "|---:|---:|---:|---:|---:|---:|"]
for t, *_, km in rows:
    size = {99904: 100000, 998284: 1000000, 3995964: 4000000}.get(int(t), None)
    if size is None:
        size = min((100000, 1000000, 4000000), key=lambda s: abs(s - int(t)))
    one = k(f"LibraryCall/triangles:{size}/method:0/threads:1")
    two = k(f"LibraryCall/triangles:{size}/method:0/threads:2")
    c1, c2 = k(f"Compute/triangles:{size}/method:0/threads:1"), k(f"Compute/triangles:{size}/method:0/threads:2")
    lines.append(f"| {int(t):,} | {float(km):.0f} | {one:.0f} | {float(km)/one:.2f}x | {two:.0f} | {c1/c2:.2f}x |")
lines += ["", "Build phase (OpenMesh half-edge construction):", ""]
for size in (100000, 1000000, 4000000):
    lines.append(f"- {size:,} triangles: {k(f'BuildMesh/{size}'):.0f} ms")
lines += ["", "## Error against run time", "", "![error against run time](bench-plot.png)", "",
          "Mean angular error against the exact tangent on analytic surfaces, per method, one point per resolution "
          "(data: [bench.csv](bench.csv), from `tangent bench`)."]
open("docs/benchmarks.md", "w").write("\n".join(lines) + "\n")
# The README shows the same tables between its bench markers.
readme = open("README.md").read()
begin, end = "<!-- bench:begin -->", "<!-- bench:end -->"
if begin in readme and end in readme:
    tables = "\n".join(l for l in lines[2:] if not l.startswith("## Error against") and "bench-plot" not in l and not l.startswith("Mean angular error"))
    readme = readme[:readme.index(begin) + len(begin)] + "\n" + tables.strip() + "\n" + readme[readme.index(end):]
    open("README.md", "w").write(readme)
PY
cp "$out/error/plot.png" docs/bench-plot.png 2>/dev/null || true
cp "$out/error/plot.svg" docs/bench-plot.svg 2>/dev/null || true
cp "$out/error/bench.csv" docs/bench.csv
echo "wrote docs/benchmarks.md, docs/bench-plot.png, docs/bench-plot.svg, docs/bench.csv"
