// SPDX-License-Identifier: MIT
// Method `mikktspace` against the reference MikkTSpace (npm `mikktspace`, WebAssembly): every
// generated mesh, OBJ input through bake, and the shared sample assets; plus determinism
// under face shuffles, corner rotation and thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <numbers>
#include <random>

#include "read/accessors.hpp"
#include "read/asset.hpp"
#include "read/primitive.hpp"
#include "support/reference.hpp"
#include "support/skip_or_fail.hpp"
#include "support/temp_dir.hpp"
#include "support/test_assets.hpp"
#include "tangent/gltf.hpp"
#include "tangent/tangent.hpp"

namespace {

namespace fs = std::filesystem;
using tangent::FrameSource;
using tangent::testing::GridMesh;

constexpr double kMaxDegrees = 0.01;

struct NamedMesh {
  std::string name;
  GridMesh mesh;
  // Corners of coincident triangles copying a frame of their identity (FrameSource::inherited),
  // and corners that no triangle of their identity reaches (neighbour or fixed): where the
  // reference leaves an arbitrary frame. Counted by hand at generatedMeshes().
  std::size_t inherited = 0, fallback = 0;
  bool smooth = false;  // consistently wound, smooth normals: compared with the other methods too
};

GridMesh jitteredGrid(int nx, int ny, unsigned seed) {
  GridMesh m = tangent::testing::makeGrid(nx, ny, false);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(-0.3f, 0.3f);
  for (std::size_t v = 0; v < m.positions.size() / 3; ++v) {
    m.positions[3 * v] += jitter(rng) / static_cast<float>(nx);
    m.positions[3 * v + 1] += jitter(rng) / static_cast<float>(ny);
    m.uvs[2 * v] += jitter(rng) / static_cast<float>(nx);
    m.uvs[2 * v + 1] += jitter(rng) / static_cast<float>(ny);
  }
  return m;
}

// Open cylinder whose u seam has duplicated vertices (same position, different UV).
GridMesh cylinderWithSeam(int segments, int rows) {
  GridMesh m;
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i <= segments; ++i) {
      const double a = 2 * std::numbers::pi * (i % segments) / segments;
      m.positions.insert(m.positions.end(), {static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), static_cast<float>(j) / rows});
      m.normals.insert(m.normals.end(), {static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0});
      m.uvs.insert(m.uvs.end(), {static_cast<float>(i) / segments, static_cast<float>(j) / rows});
    }
  }
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < segments; ++i) {
      const std::uint32_t a = j * (segments + 1) + i, b = a + segments + 1;
      m.indices.insert(m.indices.end(), {a, a + 1, b + 1, a, b + 1, b});
    }
  }
  return m;
}

// A flat fan whose centre edge (0,1) is shared by three triangles, plus a mirrored island
// meeting the rest at vertex 0 only.
GridMesh nonManifoldFan() {
  GridMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 0.5f, 1, 0, 0.5f, -1, 0, 0.5f, 0.3f, 0.6f, -1, 0.2f, 0, -1, -0.8f, 0};
  for (int v = 0; v < 7; ++v) m.normals.insert(m.normals.end(), {0, 0, 1});
  m.uvs = {0, 0, 1, 0, 0.5f, 1, 0.5f, -1, 0.5f, 0.5f, 1, 0.2f, 1, -0.8f};
  m.indices = {0, 1, 2, 1, 0, 3, 0, 1, 4, 0, 5, 6};
  return m;
}

// A quad with a collapsed triangle (2,4,1), a zero-UV-area triangle touching it at vertex 2
// only (2,5,6), and a zero-UV-area (collinear UVs) triangle sharing its edge (1,2): (2,1,7).
GridMesh degenerateAndZeroUv() {
  GridMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0, 2, 2, 0, 2, 0.5f, 0};
  for (int v = 0; v < 8; ++v) m.normals.insert(m.normals.end(), {0, 0, 1});
  m.uvs = {0, 0, 1, 0, 1, 1, 0, 1, 1, 1, 1, 1, 1, 1, 1, 0.5f};
  m.indices = {0, 1, 2, 0, 2, 3, 2, 4, 1, 2, 5, 6, 2, 1, 7};
  return m;
}

GridMesh mirroredQuads() {
  GridMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0};
  for (int v = 0; v < 6; ++v) m.normals.insert(m.normals.end(), {0, 0, 1});
  m.uvs = {0, 0, 1, 0, 0, 0, 0, 1, 1, 1, 0, 1};
  m.indices = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
  return m;
}

// The sphere (32 x 16, exact poles): each pole row's quads have one triangle with two corners
// on the pole (coincident), 2 x 32 triangles whose 192 corners copy a frame of their identity
// (pole position, normal, UV (i/32, 0 or 1)). Pole copy i of the top row is a corner of slice
// i - 1's real triangle, except copy 0; of the bottom row, slice i's, except copy 32: those two
// corners find no frame of their identity and take a neighbour's, 190 inherit. Turning every
// triangle over changes no identity or neighbour: the same counts. The degenerate mesh: the
// collapsed triangle's 3 corners inherit; the zero-UV triangle touching at vertex 2 only
// (corners 9, 10, 11) and the far corner of the one across edge (1,2) (corner 14, vertex 7)
// are reached by no group.
std::vector<NamedMesh> generatedMeshes() {
  return {{"sphere with poles", tangent::testing::makeSphere(32, 16), 190, 2, true},
          {"sphere wound against its normals", tangent::testing::reverseWinding(tangent::testing::makeSphere(32, 16), 1), 190, 2},
          {"torus", tangent::testing::makeTorus(48, 24), 0, 0, true},
          {"grid", tangent::testing::makeGrid(12, 9, false), 0, 0, true},
          {"mirrored columns", tangent::testing::makeGrid(12, 9, true), 0, 0, true},
          {"jittered grid", jitteredGrid(20, 20, 11), 0, 0, true},
          {"cylinder with UV seam", cylinderWithSeam(24, 6), 0, 0, true},
          {"mirrored quads", mirroredQuads(), 0, 0, true},
          {"non-manifold fan", nonManifoldFan()},
          {"degenerate and zero-UV triangles", degenerateAndZeroUv(), 3, 4}};
}

struct Ours {
  std::vector<float> tangents;
  std::vector<FrameSource> sources;
  tangent::Report report;
};

Ours computeOurs(const tangent::MeshArrays& mesh, tangent::Options options) {
  Ours ours;
  ours.tangents.assign(mesh.indices.size() * 4, std::numeric_limits<float>::quiet_NaN());
  ours.sources.resize(mesh.indices.size());
  ours.report = tangent::computeCornerTangents(mesh, ours.tangents, options, ours.sources);
  return ours;
}

tangent::MeshArrays arraysOf(const GridMesh& m) { return {m.positions, m.normals, m.uvs, m.indices}; }

TEST(MikkTSpaceReference, GeneratedMeshes) {
  const auto meshes = generatedMeshes();
  std::vector<tangent::testing::CornerArrays> deindexed;
  for (const auto& named : meshes) deindexed.push_back(tangent::testing::deindex(named.name, arraysOf(named.mesh)));
  const auto reference = tangent::testing::referenceTangents(deindexed);
  ASSERT_EQ(reference.size(), meshes.size());
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const NamedMesh& named = meshes[i];
    SCOPED_TRACE(named.name);
    tangent::Options options;
    options.uvOrigin = tangent::UvOrigin::bottomLeft;  // the reference's own convention
    const Ours ours = computeOurs(arraysOf(named.mesh), options);
    const auto agreement = tangent::testing::compareWithReference(ours.tangents, reference[i], ours.sources, false);
    std::printf("%-34s %s\n", named.name.c_str(), agreement.describe().c_str());
    EXPECT_EQ(ours.report.inheritedCorners, named.inherited);
    EXPECT_EQ(ours.report.fallbackFromNeighbours + ours.report.fallbackFixed, named.fallback);
    EXPECT_EQ(agreement.ourFallback, named.fallback);
    EXPECT_EQ(agreement.referenceZero, 0u);
    EXPECT_EQ(agreement.compared, named.mesh.indices.size() - named.fallback);
    EXPECT_LE(agreement.maxDegrees, kMaxDegrees);
    EXPECT_EQ(agreement.wMismatches, 0u);
  }
}

// The other methods against the same reference, on every corner where both have a computed
// frame. On consistently wound meshes every method has the reference's w. A weighted sum of
// the tangents of a vertex's triangles, projected onto its tangent plane, lies between those
// triangles' own projected tangents, which are flat's frames there: lengyel, whatever the
// weighting, is never further from the reference than flat on the same mesh. Lengyel with
// angle weights differs from MikkTSpace only in projecting after summing, not before: within
// 1e-3 degrees on the smooth meshes (measured: 6e-5 at most), not on the jittered grid, whose
// triangles' tangents scatter by tens of degrees. Flat's own bound: on the sphere and the torus
// a triangle's dP/du follows the chord between two neighbouring rings of u, at most half
// their angle (360/32/2 and 360/48/2 degrees) from the tangent at either end; on the cylinder
// that chord is horizontal and projects exactly onto the circle's tangent. On the sphere wound
// against its normals lengyel's and flat's w (the sign of (N x T) . B, from the normals) is
// the opposite of MikkTSpace's (from the UV winding) on every corner.
TEST(MikkTSpaceReference, OtherMethodsOnConsistentlyWoundMeshes) {
  const auto meshes = generatedMeshes();
  std::vector<tangent::testing::CornerArrays> deindexed;
  for (const auto& named : meshes) deindexed.push_back(tangent::testing::deindex(named.name, arraysOf(named.mesh)));
  const auto reference = tangent::testing::referenceTangents(deindexed);
  ASSERT_EQ(reference.size(), meshes.size());
  auto compare = [&](std::size_t i, tangent::Method method, tangent::Weighting weighting) {
    tangent::Options options;
    options.method = method;
    options.weighting = weighting;
    options.uvOrigin = tangent::UvOrigin::bottomLeft;
    const Ours ours = computeOurs(arraysOf(meshes[i].mesh), options);
    return tangent::testing::compareWithReference(ours.tangents, reference[i], ours.sources, false);
  };
  const std::map<std::string, double> flatBound = {
      {"sphere with poles", 360.0 / 32 / 2}, {"torus", 360.0 / 48 / 2}, {"cylinder with UV seam", 0.0}, {"mirrored quads", 0.0}};
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const NamedMesh& named = meshes[i];
    const bool inverted = named.name == "sphere wound against its normals";
    if (!named.smooth && !inverted) continue;
    const auto flat = compare(i, tangent::Method::flat, tangent::Weighting::angle);
    std::printf("%-16s %-34s %s\n", "flat", named.name.c_str(), flat.describe().c_str());
    for (auto [label, weighting] : {std::pair{"lengyel/angle", tangent::Weighting::angle}, std::pair{"lengyel/area", tangent::Weighting::area},
                                    std::pair{"lengyel/uniform", tangent::Weighting::uniform}}) {
      SCOPED_TRACE(std::string(label) + ", " + named.name);
      const auto lengyel = compare(i, tangent::Method::lengyel, weighting);
      std::printf("%-16s %-34s %s\n", label, named.name.c_str(), lengyel.describe().c_str());
      EXPECT_EQ(lengyel.ourFallback, named.fallback);
      EXPECT_EQ(lengyel.compared, named.mesh.indices.size() - named.fallback);
      EXPECT_EQ(lengyel.wMismatches, inverted ? lengyel.compared : 0u);
      EXPECT_LE(lengyel.maxDegrees, flat.maxDegrees + 1e-4);
      if (weighting == tangent::Weighting::angle && named.name != "jittered grid") {
        EXPECT_LE(lengyel.maxDegrees, 1e-3);
      }
    }
    SCOPED_TRACE("flat, " + named.name);
    EXPECT_EQ(flat.ourFallback, named.fallback);
    EXPECT_EQ(flat.wMismatches, inverted ? flat.compared : 0u);
    if (flatBound.count(named.name)) {
      EXPECT_LE(flat.maxDegrees, flatBound.at(named.name) + 1e-3);
    }
  }
}

// Every corner of every normal-mapped primitive of a glTF file, our method vs the reference,
// in glTF's convention (reference w negated).
struct PrimitiveArrays {
  std::string name;
  std::vector<float> positions, normals, uvs, tangents;
  std::vector<std::uint32_t> corners;
  tangent::MeshArrays arrays() const { return {positions, normals, uvs, corners}; }
};

std::vector<PrimitiveArrays> normalMappedPrimitives(const fs::path& file, bool all = false) {
  using tangent::gltf::detail::readAccessor;
  using tangent::gltf::detail::toFloats;
  const auto asset = tangent::gltf::detail::loadAsset(file);
  std::vector<PrimitiveArrays> out;
  for (std::size_t m = 0; m < asset.json["meshes"].size(); ++m) {
    const auto& primitives = asset.json["meshes"][m]["primitives"];
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      const auto& primitive = primitives[p];
      const auto needs = tangent::gltf::detail::primitiveNeeds(asset.json, primitive, all || asset.fromMeshFile);
      if (needs.texCoord < 0 || !needs.triangles) continue;
      const auto& attributes = primitive["attributes"];
      auto floats = [&](const std::string& name) { return toFloats(readAccessor(asset.model, attributes[name].get<int>(), name)); };
      PrimitiveArrays arrays;
      arrays.name = file.filename().string() + " mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      arrays.positions = floats("POSITION");
      arrays.normals = floats("NORMAL");
      arrays.uvs = floats("TEXCOORD_" + std::to_string(needs.texCoord));
      if (attributes.contains("TANGENT")) arrays.tangents = floats("TANGENT");
      const std::size_t n = arrays.positions.size() / 3;
      std::vector<std::uint32_t> sequence;
      if (primitive.contains("indices"))
        sequence = tangent::gltf::detail::toIndices(readAccessor(asset.model, primitive["indices"].get<int>(), "indices"), n, "indices");
      else
        for (std::uint32_t i = 0; i < n; ++i) sequence.push_back(i);
      arrays.corners = tangent::gltf::detail::triangleList(primitive.value("mode", 4), sequence);
      out.push_back(std::move(arrays));
    }
  }
  return out;
}

std::vector<float> perCorner(const PrimitiveArrays& p, const std::vector<float>& perVertex) {
  std::vector<float> out;
  for (std::uint32_t v : p.corners) out.insert(out.end(), &perVertex[4 * v], &perVertex[4 * v + 4]);
  return out;
}

TEST(MikkTSpaceReference, SharedAssets) {
  const fs::path shared = tangent::testing::sharedAssets();
  if (shared.empty()) TANGENT_SKIP_OR_FAIL("../shared/assets is absent: skipping the shared sample assets");
  std::vector<PrimitiveArrays> primitives;
  for (const char* name : {"NormalTangentTest.glb", "NormalTangentMirrorTest.glb"}) {
    for (auto& p : normalMappedPrimitives(shared / name)) primitives.push_back(std::move(p));
  }
  ASSERT_GE(primitives.size(), 2u);
  std::vector<tangent::testing::CornerArrays> deindexed;
  for (const auto& p : primitives) deindexed.push_back(tangent::testing::deindex(p.name, p.arrays()));
  const auto reference = tangent::testing::referenceTangents(deindexed);
  ASSERT_EQ(reference.size(), primitives.size());
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    SCOPED_TRACE(primitives[i].name);
    const Ours ours = computeOurs(primitives[i].arrays(), {});
    const auto agreement = tangent::testing::compareWithReference(ours.tangents, reference[i], ours.sources, true);
    std::printf("mikktspace vs reference, %s: %s\n", primitives[i].name.c_str(), agreement.describe().c_str());
    EXPECT_LE(agreement.maxDegrees, kMaxDegrees);
    EXPECT_EQ(agreement.wMismatches, 0u);
    for (auto [label, method, weighting] : {std::tuple{"lengyel/angle", tangent::Method::lengyel, tangent::Weighting::angle},
                                            std::tuple{"lengyel/area", tangent::Method::lengyel, tangent::Weighting::area},
                                            std::tuple{"lengyel/uniform", tangent::Method::lengyel, tangent::Weighting::uniform},
                                            std::tuple{"flat", tangent::Method::flat, tangent::Weighting::angle}}) {
      tangent::Options options;
      options.method = method;
      options.weighting = weighting;
      const Ours other = computeOurs(primitives[i].arrays(), options);
      const auto otherAgreement = tangent::testing::compareWithReference(other.tangents, reference[i], other.sources, true);
      std::printf("  %-16s vs reference: %s\n", label, otherAgreement.describe().c_str());
      EXPECT_EQ(otherAgreement.wMismatches, 0u) << label;  // both assets are consistently wound
    }
    if (!primitives[i].tangents.empty()) {
      // The file's own tangents (Blender's MikkTSpace export) against ours.
      const auto supplied = perCorner(primitives[i], primitives[i].tangents);
      const auto vsFile = tangent::testing::compareWithReference(ours.tangents, supplied, ours.sources, false);
      std::printf("mikktspace vs the file's TANGENT, %s: %s\n", primitives[i].name.c_str(), vsFile.describe().c_str());
      EXPECT_LE(vsFile.maxDegrees, kMaxDegrees);
      EXPECT_EQ(vsFile.wMismatches, 0u);
    }
  }
}

TEST(MikkTSpaceReference, ObjInputThroughBake) {
  tangent::testing::TempDir dir;
  const GridMesh torus = tangent::testing::makeTorus(32, 16);
  {
    std::ofstream obj(dir / "torus.obj");
    for (std::size_t v = 0; v < torus.positions.size() / 3; ++v) {
      obj << "v " << torus.positions[3 * v] << " " << torus.positions[3 * v + 1] << " " << torus.positions[3 * v + 2] << "\n";
      obj << "vn " << torus.normals[3 * v] << " " << torus.normals[3 * v + 1] << " " << torus.normals[3 * v + 2] << "\n";
      obj << "vt " << torus.uvs[2 * v] << " " << torus.uvs[2 * v + 1] << "\n";
    }
    for (std::size_t t = 0; t < torus.indices.size() / 3; ++t) {
      obj << "f";
      for (int k = 0; k < 3; ++k) {
        const auto i = torus.indices[3 * t + k] + 1;
        obj << " " << i << "/" << i << "/" << i;
      }
      obj << "\n";
    }
  }
  tangent::gltf::bakeFile(dir / "torus.obj", dir / "torus.glb", {});
  auto primitives = normalMappedPrimitives(dir / "torus.glb", true);
  ASSERT_EQ(primitives.size(), 1u);
  const auto reference = tangent::testing::referenceTangents({tangent::testing::deindex("torus.obj", primitives[0].arrays())});
  ASSERT_EQ(reference.size(), 1u);
  const auto baked = perCorner(primitives[0], primitives[0].tangents);
  const auto agreement = tangent::testing::compareWithReference(baked, reference[0], {}, true);
  std::printf("torus.obj baked vs reference: %s\n", agreement.describe().c_str());
  EXPECT_EQ(agreement.compared, primitives[0].corners.size());
  EXPECT_LE(agreement.maxDegrees, kMaxDegrees);
  EXPECT_EQ(agreement.wMismatches, 0u);
}

// A pole whose vertices are 1e-16 apart instead of welded (what sin(pi) gives): the reference
// computes the pole slivers' edges in float, where their difference cancels to zero unless
// the sliver happens to start at the pole, so its frame there depends on corner order. Ours
// keeps the direction and lands nearer the analytic tangent (-sin phi, cos phi, 0).
TEST(MikkTSpaceReference, NearCoincidentPoleIsWhereFloatBreaks) {
  const GridMesh m = tangent::testing::makeSphere(32, 16, /*exactPoles=*/false);
  const auto references = tangent::testing::referenceTangents({tangent::testing::deindex("pole", arraysOf(m))});
  ASSERT_EQ(references.size(), 1u);
  const auto& reference = references[0];
  tangent::Options options;
  options.uvOrigin = tangent::UvOrigin::bottomLeft;
  const Ours ours = computeOurs(arraysOf(m), options);
  const std::uint32_t firstPoleVertex = 16 * 33;
  double worstOurs = 0, worstReference = 0;
  for (std::size_t c = 0; c < m.indices.size(); ++c) {
    if (m.indices[c] < firstPoleVertex || m.indices[c] == firstPoleVertex + 32) continue;  // bottom pole, not the seam copy
    const double phi = 2 * std::numbers::pi * (m.indices[c] - firstPoleVertex) / 32;
    auto angleTo = [&](const float* t) {
      return std::acos(std::clamp(t[0] * -std::sin(phi) + t[1] * std::cos(phi), -1.0, 1.0)) * 180 / std::numbers::pi;
    };
    worstOurs = std::max(worstOurs, angleTo(&ours.tangents[4 * c]));
    worstReference = std::max(worstReference, angleTo(&reference[4 * c]));
  }
  std::printf("near-coincident pole: worst angle to the analytic tangent, ours %.3f deg, reference %.3f deg\n", worstOurs, worstReference);
  EXPECT_LT(worstOurs, worstReference);
  EXPECT_LE(worstOurs, 360.0 / 32 / 2 + 1e-3);  // half a slice: the chord of a one-sided corner
}

TEST(MikkTSpace, SameBitsForAnyFaceOrderCornerRotationAndThreadCount) {
  // Large enough (over 4096 triangles per thread) that several threads really split the work.
  for (const GridMesh& m : {tangent::testing::makeTorus(96, 64), tangent::testing::makeGrid(70, 70, true)}) {
    const Ours reference = computeOurs(arraysOf(m), {});
    for (unsigned threads : {2u, 3u, 4u}) {
      tangent::Options options;
      options.threads = threads;
      const Ours threaded = computeOurs(arraysOf(m), options);
      ASSERT_EQ(0, std::memcmp(threaded.tangents.data(), reference.tangents.data(), reference.tangents.size() * 4)) << threads;
    }
    const auto shuffled = tangent::testing::shuffleFacesAndRotateCorners(m, 3);
    const Ours r = computeOurs(arraysOf(shuffled.mesh), {});
    for (std::size_t c = 0; c < shuffled.originalCorner.size(); ++c)
      ASSERT_EQ(0, std::memcmp(&r.tangents[4 * c], &reference.tangents[4 * shuffled.originalCorner[c]], 16));
  }
}

TEST(MikkTSpace, NonManifoldResultDoesNotDependOnFaceOrder) {
  GridMesh m = nonManifoldFan();
  const Ours a = computeOurs(arraysOf(m), {});
  EXPECT_EQ(a.report.nonManifoldFaces, 3u);  // the three faces on edge (0,1)
  std::reverse(m.indices.begin(), m.indices.end());  // reverses the face order and each winding
  GridMesh reversed = m;
  for (std::size_t t = 0; t < reversed.indices.size() / 3; ++t) std::swap(reversed.indices[3 * t + 1], reversed.indices[3 * t + 2]);
  const Ours b = computeOurs(arraysOf(reversed), {});
  // Triangle t of `reversed` is triangle (T-1-t) of the original with corners (2,0,1) order.
  const std::size_t triangles = m.indices.size() / 3;
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::size_t original = triangles - 1 - t;
    const int map[3] = {2, 0, 1};
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(0, std::memcmp(&b.tangents[4 * (3 * t + k)], &a.tangents[4 * (3 * original + map[k])], 16)) << t << " " << k;
  }
}

TEST(MikkTSpace, DegenerateCornersInheritAndZeroUvTrianglesJoinTheirGroup) {
  const GridMesh m = degenerateAndZeroUv();
  tangent::Options options;
  options.uvOrigin = tangent::UvOrigin::bottomLeft;
  const Ours ours = computeOurs(arraysOf(m), options);
  EXPECT_EQ(ours.report.degenerateTriangles, 1u);
  EXPECT_EQ(ours.report.zeroUvAreaTriangles, 2u);
  // The collapsed triangle (corners 6..8) copies the quad's frame at its vertices.
  EXPECT_EQ(ours.sources[6], FrameSource::inherited);
  EXPECT_EQ(0, std::memcmp(&ours.tangents[4 * 6], &ours.tangents[4 * 2], 16));
  // The zero-UV triangle across edge (1,2) joins the quad's groups at vertices 2 and 1.
  EXPECT_EQ(ours.sources[12], FrameSource::computed);
  EXPECT_EQ(ours.sources[13], FrameSource::computed);
  EXPECT_EQ(0, std::memcmp(&ours.tangents[4 * 12], &ours.tangents[4 * 2], 16));
  EXPECT_EQ(0, std::memcmp(&ours.tangents[4 * 13], &ours.tangents[4 * 1], 16));
  // The one touching at a vertex only is reached by no group: the reference leaves it a
  // default frame; ours borrows from the vertex and says so.
  EXPECT_EQ(ours.sources[9], FrameSource::neighbour);
  EXPECT_EQ(ours.report.fallbackFromNeighbours, 4u);  // corners 9, 10, 11 and 14 (vertex 7)
}

}  // namespace
