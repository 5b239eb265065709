// Kernel phases with Google Benchmark: the whole library call (build the half-edge mesh,
// compute, copy per corner) and its two main phases, on UV spheres of ~1e5..4e6 triangles.
// scripts/bench.sh runs it beside the peers.
#include <benchmark/benchmark.h>

#include <map>

#include "analytic_surfaces.hpp"
#include "tangent/halfedge_mesh.hpp"

namespace {

const tangent::bench::AnalyticMesh& sphere(std::size_t triangles) {
  static std::map<std::size_t, tangent::bench::AnalyticMesh> cache;
  auto it = cache.find(triangles);
  if (it == cache.end()) it = cache.emplace(triangles, tangent::bench::makeSurface("sphere", triangles)).first;
  return it->second;
}

tangent::Options options(const benchmark::State& state) {
  tangent::Options o;
  o.method = static_cast<tangent::Method>(state.range(1));
  o.threads = static_cast<unsigned>(state.range(2));
  return o;
}

void LibraryCall(benchmark::State& state) {
  const auto& mesh = sphere(static_cast<std::size_t>(state.range(0)));
  std::vector<float> out(mesh.indices.size() * 4);
  for (auto _ : state) {
    tangent::computeCornerTangents(mesh.arrays(), out, options(state));
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["triangles"] = static_cast<double>(mesh.triangles());
}

void BuildMesh(benchmark::State& state) {
  const auto& mesh = sphere(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    tangent::CornerMesh cornerMesh = tangent::buildCornerMesh(mesh.arrays());
    benchmark::DoNotOptimize(cornerMesh.mesh.n_faces());
  }
}

void Compute(benchmark::State& state) {
  const auto& mesh = sphere(static_cast<std::size_t>(state.range(0)));
  tangent::CornerMesh cornerMesh = tangent::buildCornerMesh(mesh.arrays());
  for (auto _ : state) benchmark::DoNotOptimize(tangent::computeTangents(cornerMesh, options(state)).corners);
}

constexpr int kMikk = static_cast<int>(tangent::Method::mikktspace);
constexpr int kLengyel = static_cast<int>(tangent::Method::lengyel);

void Sizes(benchmark::internal::Benchmark* b) {
  for (long triangles : {100000L, 1000000L, 4000000L})
    for (long method : {kMikk, kLengyel})
      for (long threads : {1L, 2L}) b->Args({triangles, method, threads});
  b->ArgNames({"triangles", "method", "threads"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

}  // namespace

BENCHMARK(LibraryCall)->Apply(Sizes);
BENCHMARK(Compute)->Apply(Sizes);
BENCHMARK(BuildMesh)->Arg(100000)->Arg(1000000)->Arg(4000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
