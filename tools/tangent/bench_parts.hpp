// SPDX-License-Identifier: MIT
// The parts of `tangent bench` (bench_command.cpp): how a run is timed and its error measured
// (bench_measure.cpp), shared by the analytic, asset and --peers tables; the --peers table
// (bench_peers.cpp).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "peers.hpp"
#include "tangent/scene.hpp"
#include "tangent/tangent.hpp"

namespace tangent::cli::measure {

using Clock = std::chrono::steady_clock;

// A row of the tables: a method with its weighting and thread count (w in the bottom-left
// convention).
struct Setting {
  std::string label;
  Options options;
};

// Every method and weighting on 1 and 2 threads.
std::vector<Setting> settings();

// The angle between two tangents' xyz, in degrees.
double angleDegrees(const float* a, const float* b);

struct Errors {
  double mean = 0, p99 = 0, max = 0;
  std::size_t wErrors = 0;
};

// Runs the library the way a caller does: computeCornerTangents on the plain arrays, a
// workspace of its own per call. Milliseconds, the median of `repeats` calls; `sources` (when
// given) receives where each corner's frame came from.
double timedRun(const MeshArrays& mesh, const Options& options, int repeats, std::vector<float>& cornerTangents,
                std::vector<FrameSource>* sources = nullptr);

// A peer (reference MikkTSpace in C, meshoptimizer) on the same arrays: milliseconds, the
// median of `repeats` calls. Its w is in the bottom-left convention; tangent::handedness turns
// it into uvOrigin's.
double timedPeerRun(bench::Peer peer, const MeshArrays& mesh, UvOrigin uvOrigin, int repeats, std::vector<float>& cornerTangents);

// The resident memory one call adds to the process at its peak, per triangle of `mesh`: its
// scratch beyond the caller's input and output arrays, as fresh memory (the heap's free pages
// given back first, then the kernel's high-water mark reset: Linux's /proc/self/clear_refs), as
// in a new process. The library's call gets a workspace of its own, made inside it. nullopt
// where the system does not say (not Linux, or /proc not writable), and for calls on more than
// one thread: after other inputs those read a fraction of a one-thread call (6-16 against
// 58-72 bytes a triangle for mikktspace), pages kept between calls on the workers' side that
// the measure cannot give back first.
std::optional<double> peakBytesPerTriangle(const MeshArrays& mesh, const Options& options, std::vector<float>& cornerTangents);
std::optional<double> peerPeakBytesPerTriangle(bench::Peer peer, const MeshArrays& mesh, std::vector<float>& cornerTangents);

// Mean, p99 and max angle and w mismatches of `corners` against `reference` (per vertex through
// `indices`, or per corner), over every corner or only those `compared` marks.
Errors compare(const std::vector<float>& corners, const std::vector<std::uint32_t>& indices, const std::vector<float>& reference,
               bool referencePerVertex, const std::vector<std::uint8_t>* compared = nullptr);

// A file's scene, or a warning naming it and nothing (the bench goes on with the others). Its
// geometry only: the bench runs no check.
std::optional<gltf::Scene> loadSceneOrWarn(const std::filesystem::path& file);

// The files of --assets: each file given, and the .glb/.gltf files of each folder given, sorted.
std::vector<std::filesystem::path> assetFiles(const std::vector<std::filesystem::path>& assets);

// bench_peers.cpp
// tangent bench --peers: the error-against-run-time table with the peers as rows. Every run is
// on one thread (the peers have no other), w in MikkTSpace's convention (as the reference C
// writes it); the library's mikktspace at all threads is one more row, for its time.
int peersTable(const std::vector<std::filesystem::path>& assets, std::size_t triangles, int repeats, const std::filesystem::path& outDir);

}  // namespace tangent::cli::measure
