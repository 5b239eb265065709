// SPDX-License-Identifier: MIT
// The library against the strongest peers, on the same arrays in one process (Google
// Benchmark): the plain-array call and the OpenMesh input path at 1, 2 and all threads, the
// reference MikkTSpace in C and meshoptimizer's tangent generator in its MikkTSpace-compatible
// and default modes. Inputs: single-primitive UV spheres of 1e5, 1e6 and 4e6 triangles and the
// largest normal-mapped primitive of each ../shared/assets/*.glb. Every call writes one tangent
// per corner into memory allocated before timing.
//
// Names: IMPLEMENTATION/INPUT, e.g. library/t1/sphere-1e5, openmesh/tall/sphere-1e6,
// mikktspace.c/sphere-4e6, meshopt-compatible/asset:NormalTangentTest. Times are process CPU
// time (all threads) and wall time per call; scripts/bench.sh takes the medians of repetitions.
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <sys/resource.h>
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define TANGENT_HAVE_CALLGRIND 1
#endif

#include <algorithm>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "analytic_surfaces.hpp"
#include "read/asset.hpp"
#include "peers.hpp"
#include "read/primitive.hpp"
#include "tangent/openmesh.hpp"
#include "tangent/shared_vertices.hpp"

namespace {

namespace fs = std::filesystem;

// One indexed triangle list: what every implementation gets.
struct Input {
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint32_t> indices;
  tangent::MeshArrays arrays() const { return {positions, normals, uvs, indices}; }
  std::size_t triangles() const { return indices.size() / 3; }
};

// Inputs are made on first use, so a filtered run builds only what it times.
struct InputSource {
  std::string name;
  std::function<Input()> make;
};

const Input& input(const InputSource& source) {
  static std::map<std::string, std::unique_ptr<Input>> cache;
  auto& slot = cache[source.name];
  if (!slot) slot = std::make_unique<Input>(source.make());
  return *slot;
}

// A UV sphere as ONE primitive: (n+1)^2 shared vertices with normals and UVs, indexed.
InputSource sphere(const std::string& name, std::size_t triangles) {
  return {
      name, [triangles] {
        tangent::bench::AnalyticMesh mesh = tangent::bench::makeSurface("sphere", triangles);
        return Input{std::move(mesh.positions), std::move(mesh.normals), std::move(mesh.uvs), std::move(mesh.indices)};
      }};
}

// The largest normal-mapped primitive of each asset, read by the glTF layer the way bake reads it.
std::vector<InputSource> assetInputs(const fs::path& folder) {
  std::vector<InputSource> sources;
  if (!fs::is_directory(folder)) {
    std::cerr << "kernel bench: " << folder.string() << " not found: asset inputs left out\n";
    return sources;
  }
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().extension() == ".glb") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    try {
      namespace detail = tangent::gltf::detail;
      const detail::Asset asset = detail::loadAsset(file);
      Input largest;
      const auto& meshes = asset.json.value("meshes", nlohmann::ordered_json::array());
      for (std::size_t m = 0; m < meshes.size(); ++m) {
        const auto& primitives = meshes[m].value("primitives", nlohmann::ordered_json::array());
        for (std::size_t p = 0; p < primitives.size(); ++p) {
          const detail::PrimitiveNeeds needs = detail::primitiveNeeds(asset.json, primitives[p], false);
          if (!needs.triangles || !needs.hasNormalTexture) continue;
          detail::PrimitiveGeometry g =
              detail::readGeometry(asset, primitives[p], needs, detail::primitiveLabel(asset.json, int(m), int(p)));
          if (g.corners.size() > largest.indices.size())
            largest = {std::move(g.positions), std::move(g.normals), std::move(g.uvs), std::move(g.corners)};
        }
      }
      if (largest.indices.empty()) {
        std::cerr << "kernel bench: " << file.filename().string() << " has no normal-mapped triangles: left out\n";
        continue;
      }
      auto shared = std::make_shared<Input>(std::move(largest));
      sources.push_back({"asset:" + file.stem().string(), [shared] { return *shared; }});
    } catch (const std::exception& e) {
      std::cerr << "kernel bench: " << file.string() << ": " << e.what() << ": left out\n";
    }
  }
  return sources;
}

tangent::Options options(unsigned threads) {
  tangent::Options o;
  o.method = tangent::Method::mikktspace;
  o.uvOrigin = tangent::UvOrigin::bottomLeft;  // the peers' w convention; the time does not depend on it
  o.threads = threads;
  return o;
}

// The library's plain-array entry point as a pipeline calls it: a TangentWorkspace reused
// across calls, and the vertex split asked for (CornerOutputs{tangents, {}, cornerVertex}).
class LibraryCall {
 public:
  explicit LibraryCall(const Input& in) : tangents_(in.indices.size() * 4), cornerVertex_(in.indices.size()) {}
  tangent::Report operator()(const Input& in, const tangent::Options& o) {
    return tangent::computeCornerTangents(in.arrays(), tangent::CornerOutputs{tangents_, {}, cornerVertex_}, o,
                                          workspace_);
  }
  const float* data() const {
    return tangents_.data();
  }
  static std::string description() {
    return "computeCornerTangents(MeshArrays, CornerOutputs{tangents, {}, cornerVertex}, Options, TangentWorkspace&), "
           "workspace reused";
  }

 private:
  std::vector<float> tangents_;
  std::vector<std::uint32_t> cornerVertex_;
  tangent::TangentWorkspace workspace_;
};

void counters(benchmark::State& state, const Input& in, unsigned threads) {
  state.counters["triangles"] = static_cast<double>(in.triangles());
  state.counters["workers"] = threads;  // not "threads": Google Benchmark's own JSON field
}

unsigned actualThreads(unsigned requested) {
  tangent::Options options;
  options.threads = requested;
  return tangent::threadCount(options);  // the library's own rule for 0
}

// Process CPU time counts the worker threads too; wall time (real_time) is reported beside it.
void reportProcessCpuTime(benchmark::internal::Benchmark* b) {
  b->MeasureProcessCPUTime()->Unit(benchmark::kMillisecond);
}

// The call as a pipeline makes it: once per mesh, with other work in between. Before each
// timed call the heap is left as that other work leaves it (scrambleHeap); the timing covers
// the call alone. Counters: minor page faults and kernel (system) milliseconds per call.
// "plain/warm" is the same plain call back to back, nothing in between.
void scrambleHeap(std::size_t bytes) {
  malloc_trim(0);  // freed memory back to the kernel
  {
    std::unique_ptr<unsigned char[]> other(new unsigned char[bytes]);  // unrelated work of the call's size
    for (std::size_t i = 0; i < bytes; i += 4096) other[i] = static_cast<unsigned char>(i);
    benchmark::DoNotOptimize(other.get());
  }
  malloc_trim(0);
}

struct Usage {
  double faults = 0, systemSeconds = 0;
  static Usage now() {
    rusage r{};
    getrusage(RUSAGE_SELF, &r);
    return {double(r.ru_minflt), double(r.ru_stime.tv_sec) + 1e-6 * double(r.ru_stime.tv_usec)};
  }
};

void timeFresh(benchmark::State& state, const Input& in, bool scramble, const std::function<void()>& call) {
  const std::size_t bytes = in.indices.size() * 64;  // about what one call of the library or a peer touches
  Usage total;
  std::size_t calls = 0;
  call();  // the code and the input paged in; what stays of the call's memory is the call's to keep
  for (auto _ : state) {
    if (scramble) {
      state.PauseTiming();
      scrambleHeap(bytes);
      state.ResumeTiming();
    }
    const Usage before = Usage::now();
    call();
    const Usage after = Usage::now();
    total.faults += after.faults - before.faults;
    total.systemSeconds += after.systemSeconds - before.systemSeconds;
    ++calls;
    benchmark::ClobberMemory();
  }
  state.counters["faults_per_call"] = total.faults / double(std::max<std::size_t>(1, calls));
  state.counters["system_ms_per_call"] = 1e3 * total.systemSeconds / double(std::max<std::size_t>(1, calls));
  counters(state, in, 1);
}

void registerFreshMemory(const InputSource& source) {
  if (source.name.rfind("sphere-", 0) != 0) return;  // single-primitive spheres: the sizes
  for (const bool scramble : {false, true}) {
    const std::string mode = scramble ? "cold" : "warm";
    // The README's plain call: no workspace of the caller's.
    reportProcessCpuTime(benchmark::RegisterBenchmark(("plain/" + mode + "/t1/" + source.name).c_str(),
                                                      [source, scramble](benchmark::State& state) {
                                                        const Input& in = input(source);
                                                        std::vector<float> tangents(in.indices.size() * 4);
                                                        timeFresh(state, in, scramble, [&] {
                                                          tangent::computeCornerTangents(in.arrays(), tangents, options(1));
                                                          benchmark::DoNotOptimize(tangents.data());
                                                        });
                                                      }));
    if (!scramble) continue;
    // meshoptimizer only: the reference C takes seconds a call at these sizes, and the issue's
    // targets are against meshoptimizer.
    for (tangent::bench::Peer peer : tangent::bench::peers()) {
      if (peer == tangent::bench::Peer::referenceMikktspace) continue;
      std::string name(toString(peer));
      std::replace(name.begin(), name.end(), '/', '-');
      reportProcessCpuTime(benchmark::RegisterBenchmark((name + "/cold/" + source.name).c_str(),
                                                        [source, peer](benchmark::State& state) {
                                                          const Input& in = input(source);
                                                          std::vector<float> tangents(in.indices.size() * 4);
                                                          timeFresh(state, in, true, [&] {
                                                            tangent::bench::runPeer(peer, in.arrays(), tangents);
                                                            benchmark::DoNotOptimize(tangents.data());
                                                          });
                                                        }));
    }
  }
}

// The library (array call, warm workspace) and the OpenMesh call at 1, 2 and all threads.
void registerLibrary(const InputSource& source) {
  const std::pair<const char*, unsigned> threadSettings[] = {{"t1", 1u}, {"t2", 2u}, {"tall", 0u}};
  for (const auto& [label, threads] : threadSettings) {
    reportProcessCpuTime(benchmark::RegisterBenchmark(("library/" + std::string(label) + "/" + source.name).c_str(),
                                                      [source, threads = threads](benchmark::State& state) {
                                                        const Input& in = input(source);
                                                        LibraryCall call(in);
                                                        const tangent::Options o = options(threads);
                                                        call(in, o);  // a pipeline calls again and again: warm workspace
                                                        for (auto _ : state) {
                                                          call(in, o);
                                                          benchmark::DoNotOptimize(call.data());
                                                          benchmark::ClobberMemory();
                                                        }
                                                        counters(state, in, actualThreads(threads));
                                                      }));
    reportProcessCpuTime(benchmark::RegisterBenchmark(
        ("openmesh/" + std::string(label) + "/" + source.name).c_str(),
        [source, threads = threads](benchmark::State& state) {
          const Input& in = input(source);
          tangent::CornerMesh mesh = tangent::buildCornerMesh(in.arrays());  // built once, outside the timing
          const tangent::Options o = options(threads);
          tangent::TangentWorkspace workspace;
          tangent::computeTangents(mesh, o, workspace);  // warm, as for the array call
          for (auto _ : state) benchmark::DoNotOptimize(tangent::computeTangents(mesh, o, workspace).corners);
          counters(state, in, actualThreads(threads));
        }));
  }
}

// The other methods on the same arrays, on one thread and on all of them: what they cost
// beside mikktspace, and that they use the threads they are given (wall against CPU time).
void registerOtherMethods(const InputSource& source) {
  for (const tangent::Method method : {tangent::Method::lengyel, tangent::Method::meshopt, tangent::Method::flat}) {
    for (const auto& [label, threads] : {std::pair<const char*, unsigned>{"t1", 1u}, {"tall", 0u}}) {
      const std::string name = std::string(tangent::toString(method)) + "/" + label + "/" + source.name;
      reportProcessCpuTime(benchmark::RegisterBenchmark(name.c_str(), [source, method, threads = threads](benchmark::State& state) {
        const Input& in = input(source);
        LibraryCall call(in);
        tangent::Options o = options(threads);
        o.method = method;
        call(in, o);
        for (auto _ : state) {
          call(in, o);
          benchmark::DoNotOptimize(call.data());
          benchmark::ClobberMemory();
        }
        counters(state, in, actualThreads(threads));
      }));
    }
  }
}

// The WebAssembly package's default path, natively: de-indexed corners (every corner its own
// vertex, as glTF-Transform passes them) shared by their bits (tangent/shared_vertices.hpp),
// then the core welding only the zero vertices; per-corner tangents. The same work as the npm
// package's generateTangents, so bench/node/wasm_cpu.mjs's times compare with this one's.
void registerDeindexed(const InputSource& source) {
  reportProcessCpuTime(benchmark::RegisterBenchmark(("library-deindexed/t1/" + source.name).c_str(), [source](benchmark::State& state) {
    const Input& in = input(source);
    const std::size_t corners = in.indices.size();
    std::vector<float> positions(3 * corners), normals(3 * corners), uvs(2 * corners), tangents(4 * corners);
    for (std::size_t c = 0; c < corners; ++c) {
      const std::size_t v = in.indices[c];
      std::copy_n(&in.positions[3 * v], 3, &positions[3 * c]);
      std::copy_n(&in.normals[3 * v], 3, &normals[3 * c]);
      std::copy_n(&in.uvs[2 * v], 2, &uvs[2 * c]);
    }
    tangent::SharedVertices shared;
    tangent::TangentWorkspace workspace;
    auto call = [&] {
      tangent::shareVertices(positions.data(), normals.data(), uvs.data(), corners, shared);
      const std::size_t n = shared.vertexCount;
      const tangent::MeshArrays mesh{{shared.positions.data(), 3 * n}, {shared.normals.data(), 3 * n}, {shared.uvs.data(), 2 * n},
                                     {shared.indices.data(), corners}};
      workspace.setWeldOnly(std::span<const std::uint32_t>(shared.zeroVertices));
      tangent::computeCornerTangents(mesh, tangent::CornerOutputs{tangents, {}, {}}, options(1), workspace);
      workspace.setWeldOnly(std::nullopt);
    };
    call();  // warm, as the package's second call on
    for (auto _ : state) {
      call();
      benchmark::DoNotOptimize(tangents.data());
      benchmark::ClobberMemory();
    }
    counters(state, in, 1);
  }));
}

// One call with a fresh workspace each time (its allocation and first touch included), as a
// single bake pays it.
void registerCold(const InputSource& source) {
  reportProcessCpuTime(benchmark::RegisterBenchmark(("library-cold/t1/" + source.name).c_str(), [source](benchmark::State& state) {
    const Input& in = input(source);
    std::vector<float> tangents(in.indices.size() * 4);
    std::vector<std::uint32_t> cornerVertex(in.indices.size());
    std::size_t workspaceBytes = 0;
    for (auto _ : state) {
      tangent::TangentWorkspace workspace;
      tangent::computeCornerTangents(in.arrays(), tangent::CornerOutputs{tangents, {}, cornerVertex}, options(1), workspace);
      benchmark::DoNotOptimize(tangents.data());
      benchmark::ClobberMemory();
      workspaceBytes = workspace.bytesReserved();
    }
    state.counters["workspace_bytes_per_triangle"] = double(workspaceBytes) / double(std::max<std::size_t>(1, in.triangles()));
    counters(state, in, 1);
  }));
}

void registerPeers(const InputSource& source) {
  for (tangent::bench::Peer peer : tangent::bench::peers()) {
    std::string name(toString(peer));
    std::replace(name.begin(), name.end(), '/', '-');  // "meshopt-compatible": one name segment
    reportProcessCpuTime(
        benchmark::RegisterBenchmark((name + "/" + source.name).c_str(), [source, peer](benchmark::State& state) {
          const Input& in = input(source);
          std::vector<float> tangents(in.indices.size() * 4);
          for (auto _ : state) {
            tangent::bench::runPeer(peer, in.arrays(), tangents);
            benchmark::DoNotOptimize(tangents.data());
            benchmark::ClobberMemory();
          }
          counters(state, in, 1);
        }));
  }
}

void registerInput(const InputSource& source) {
  registerLibrary(source);
  registerOtherMethods(source);
  registerDeindexed(source);
  registerCold(source);
  registerFreshMemory(source);
  registerPeers(source);
}

// --count-instructions, under `valgrind --tool=callgrind --instr-atstart=no`: one warm call of
// the library on one thread (mikktspace as library/t1, then lengyel/t1, meshopt/t1, flat/t1) and of each peer on the 10^5 sphere (issue 41's input), each
// between callgrind's start and a dump named after it (library/t1, mikktspace.c, ...), so that
// every dump holds that one call's instructions and nothing else (the input, the warm-up call
// and the other calls run with instrumentation off). Prints the triangle count.
int countInstructions() {
#if defined(TANGENT_HAVE_CALLGRIND)
  if (!RUNNING_ON_VALGRIND) {
    std::cerr << "kernel bench: --count-instructions runs under valgrind --tool=callgrind --instr-atstart=no\n";
    return 2;
  }
  const Input& in = input(sphere("sphere-1e5", 100000));
  auto count = [](const std::string& name, const std::function<void()>& call) {
    call();  // warm: a pipeline's workspace is allocated and touched, as in the timed benchmarks
    CALLGRIND_ZERO_STATS;
    CALLGRIND_START_INSTRUMENTATION;
    call();
    CALLGRIND_STOP_INSTRUMENTATION;
    CALLGRIND_DUMP_STATS_AT(name.c_str());
  };
  LibraryCall library(in);
  count("library/t1", [&] { library(in, options(1)); });
  for (const tangent::Method method : {tangent::Method::lengyel, tangent::Method::meshopt, tangent::Method::flat}) {
    tangent::Options o = options(1);
    o.method = method;
    count(std::string(tangent::toString(method)) + "/t1", [&] { library(in, o); });
  }
  std::vector<float> tangents(in.indices.size() * 4);
  for (tangent::bench::Peer peer : tangent::bench::peers())
    count(std::string(toString(peer)), [&] { tangent::bench::runPeer(peer, in.arrays(), tangents); });
  std::cout << "triangles " << in.triangles() << "\n";
  return 0;
#else
  std::cerr << "kernel bench: built without valgrind/callgrind.h (Debian package valgrind): --count-instructions is not available\n";
  return 2;
#endif
}

}  // namespace

int main(int argc, char** argv) {
  // Keep freed memory in the heap: meshoptimizer allocates its scratch on every call, and
  // with glibc's defaults large blocks are mapped and unmapped each time, so every call pays
  // its page faults again (measured at 1e6 triangles: 177 ms instead of 92). Peers are timed
  // at their best; the library's workspace needs none of this.
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  if (argc == 2 && std::string_view(argv[1]) == "--count-instructions") return countInstructions();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  if (tangent::bench::peers().empty()) std::cerr << "kernel bench: " << tangent::bench::peersNote() << "\n";
  // In the JSON's context, for the report: what "library" and the peers were in this build.
  benchmark::AddCustomContext("library_call", LibraryCall::description());
  benchmark::AddCustomContext("peers", tangent::bench::peersNote());
  benchmark::AddCustomContext("vector_isa", std::string(tangent::vectorIsa()));
  benchmark::AddCustomContext("hardware_threads", std::to_string(std::max(1u, std::thread::hardware_concurrency())));
  std::vector<InputSource> sources = {sphere("sphere-1e5", 100000), sphere("sphere-1e6", 1000000),
                                      sphere("sphere-4e6", 4000000)};
  for (auto& asset : assetInputs(fs::path(TANGENT_ASSETS_DIR))) sources.push_back(std::move(asset));
  for (const auto& source : sources) registerInput(source);
  const std::size_t ran = benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return ran ? 0 : 1;  // a filter that matches nothing fails (the CTest smoke test relies on it)
}
