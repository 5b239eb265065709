// SPDX-License-Identifier: MIT
// tangent bench --peers: every method and peer against the reference MikkTSpace in C.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>

#include "analytic_surfaces.hpp"
#include "bench_parts.hpp"
#include "commands.hpp"

namespace tangent::cli::measure {

namespace fs = std::filesystem;

namespace {

// One input of the table, indexed as a vertex buffer is: corners with the same position,
// normal and UV bits share a vertex.
struct PeerInput {
  std::string name;
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint32_t> indices;
  MeshArrays arrays() const { return {positions, normals, uvs, indices}; }
};

PeerInput indexByValue(std::string name, const std::vector<float>& positions, const std::vector<float>& normals,
                       const std::vector<float>& uvs) {
  PeerInput input{std::move(name), {}, {}, {}, {}};
  using Key = std::array<std::uint32_t, 8>;
  std::map<Key, std::uint32_t> vertexOf;
  const std::size_t corners = positions.size() / 3;
  input.indices.reserve(corners);
  for (std::size_t c = 0; c < corners; ++c) {
    Key key;
    for (int i = 0; i < 3; ++i) key[i] = std::bit_cast<std::uint32_t>(positions[3 * c + i]);
    for (int i = 0; i < 3; ++i) key[3 + i] = std::bit_cast<std::uint32_t>(normals[3 * c + i]);
    for (int i = 0; i < 2; ++i) key[6 + i] = std::bit_cast<std::uint32_t>(uvs[2 * c + i]);
    const auto [at, added] = vertexOf.try_emplace(key, static_cast<std::uint32_t>(input.positions.size() / 3));
    if (added) {
      input.positions.insert(input.positions.end(), &positions[3 * c], &positions[3 * c] + 3);
      input.normals.insert(input.normals.end(), &normals[3 * c], &normals[3 * c] + 3);
      input.uvs.insert(input.uvs.end(), &uvs[2 * c], &uvs[2 * c] + 2);
    }
    input.indices.push_back(at->second);
  }
  return input;
}

// The generated sphere and torus, then every normal-mapped primitive with UVs of the files.
std::vector<PeerInput> peerInputs(const std::vector<fs::path>& files, std::size_t triangles) {
  std::vector<PeerInput> inputs;
  for (const std::string surface : {"sphere", "torus"}) {
    bench::AnalyticMesh mesh = bench::makeSurface(surface, triangles);
    inputs.push_back({surface + " (generated)", std::move(mesh.positions), std::move(mesh.normals), std::move(mesh.uvs), std::move(mesh.indices)});
  }
  for (const auto& file : files) {
    const std::optional<gltf::Scene> loaded = loadSceneOrWarn(file);
    if (!loaded) continue;
    const gltf::Scene& scene = *loaded;
    for (const auto& item : scene.items) {
      if (!item.hasUvs || item.positions.empty()) continue;
      std::string name = file.filename().string();
      if (scene.items.size() > 1) name += " " + item.label;
      inputs.push_back(indexByValue(std::move(name), item.positions, item.normals, item.uvNormal));
    }
  }
  return inputs;
}

// The corners MikkTSpace gives a frame of their own triangles (a fallback frame is arbitrary):
// the corners the table compares.
std::vector<std::uint8_t> cornersToCompare(const MeshArrays& arrays) {
  std::vector<float> scratch;
  std::vector<FrameSource> sources;
  Options probe;
  probe.uvOrigin = UvOrigin::bottomLeft;
  timedRun(arrays, probe, 1, scratch, &sources);
  std::vector<std::uint8_t> compared(arrays.indices.size());
  for (std::size_t c = 0; c < compared.size(); ++c)
    compared[c] = sources[c] == FrameSource::computed || sources[c] == FrameSource::inherited;
  return compared;
}

// One input's rows, on the terminal and into `csv`: the reference, each setting on one thread,
// each other peer, and the library's mikktspace at all threads.
void peerRows(const PeerInput& input, int repeats, std::ostringstream& csv) {
  const MeshArrays arrays = input.arrays();
  const std::size_t corners = input.indices.size();
  std::vector<float> reference;
  const double referenceMs = timedPeerRun(bench::Peer::referenceMikktspace, arrays, UvOrigin::bottomLeft, repeats, reference);
  const std::vector<std::uint8_t> compared = cornersToCompare(arrays);
  const std::size_t comparedCount = static_cast<std::size_t>(std::count(compared.begin(), compared.end(), 1));
  auto row = [&](const std::string& generator, unsigned threads, const std::optional<Errors>& e, double ms,
                 std::optional<double> bytes) {
    const std::string label = generator + (threads == 1 ? "" : " (" + std::to_string(threads) + " threads)");
    const std::string memory = bytes ? std::to_string(static_cast<long long>(std::lround(*bytes))) : "-";
    if (e) {
      std::printf("| %s | %zu | %s | %.3g | %.3g | %zu | %.2f | %s |\n", input.name.c_str(), corners / 3, label.c_str(), e->max, e->p99,
                  e->wErrors, ms, memory.c_str());
    } else {
      std::printf("| %s | %zu | %s | - | - | - | %.2f | %s |\n", input.name.c_str(), corners / 3, label.c_str(), ms, memory.c_str());
    }
    csv << '"' << input.name << "\"," << corners / 3 << "," << generator << "," << threads << "," << comparedCount << "," << corners << ","
        << (e ? e->max : 0.0) << "," << (e ? e->p99 : 0.0) << "," << (e ? e->wErrors : 0) << "," << ms << ","
        << (bytes ? std::to_string(*bytes) : "") << "\n";
  };
  std::vector<float> scratch;  // the memory runs' output (the timed runs' is compared)
  row("mikktspace.c (the reference)", 1, std::nullopt, referenceMs,
      peerPeakBytesPerTriangle(bench::Peer::referenceMikktspace, arrays, scratch));
  for (const Setting& setting : settings()) {
    if (setting.options.threads != 1) continue;
    Options options = setting.options;  // bottom-left: the reference's w
    std::vector<float> ours;
    const double ms = timedRun(arrays, options, repeats, ours);
    row(setting.label, 1, compare(ours, input.indices, reference, false, &compared), ms, peakBytesPerTriangle(arrays, options, scratch));
  }
  for (bench::Peer peer : bench::peers()) {
    if (peer == bench::Peer::referenceMikktspace) continue;
    std::vector<float> theirs;
    const double ms = timedPeerRun(peer, arrays, UvOrigin::bottomLeft, repeats, theirs);
    row(std::string(toString(peer)) + " (peer)", 1, compare(theirs, input.indices, reference, false, &compared), ms,
        peerPeakBytesPerTriangle(peer, arrays, scratch));
  }
  Options allThreads;
  allThreads.uvOrigin = UvOrigin::bottomLeft;
  std::vector<float> ours;
  const double ms = timedRun(arrays, allThreads, repeats, ours);
  row("mikktspace", threadCount(allThreads), compare(ours, input.indices, reference, false, &compared), ms,
      peakBytesPerTriangle(arrays, allThreads, scratch));
}

}  // namespace

int peersTable(const std::vector<fs::path>& assets, std::size_t triangles, int repeats, const fs::path& outDir) {
  if (bench::peers().empty()) {
    std::cerr << "tangent bench --peers: the peers are absent, so there is no reference C to compare with: " << bench::peersNote()
              << "\n";
    return kExitInputFailed;
  }
  const std::vector<PeerInput> inputs = peerInputs(assetFiles(assets), triangles);
  std::ostringstream csv;
  csv << "input,triangles,generator,threads,compared_corners,corners,max_deg,p99_deg,w_mismatches,ms,peak_bytes_per_triangle\n";
  std::printf("Against the reference MikkTSpace C (mikktspace.c, genTangSpaceDefault), on the corners whose reference frame comes from\n"
              "their own triangles; times are medians of %d calls, one thread unless said. Peak B/tri: the resident memory one\n"
              "more call adds at its peak (fresh scratch, beyond the input and the 16 bytes a corner of output), per triangle.\n\n",
              repeats);
  std::printf("| input | triangles | generator | max deg | p99 deg | w mismatches | ms | peak B/tri |\n"
              "|---|---:|---|---:|---:|---:|---:|---:|\n");
  for (const PeerInput& input : inputs) {
    peerRows(input, repeats, csv);
    std::fflush(stdout);
  }
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (!writeTextOutput((outDir / "peers.csv").string(), csv.str(), "bench")) return kExitInputFailed;
  std::printf("\nwrote %s/peers.csv\n", outDir.string().c_str());
  return kExitOk;
}

}  // namespace tangent::cli::measure
