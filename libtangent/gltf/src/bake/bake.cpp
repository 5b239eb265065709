// SPDX-License-Identifier: MIT
// `bake`: TANGENT for the primitives that need it (glTF 2.0 spec 3.7.2.1), vertices split where
// the corners of one glTF vertex got different frames, every other attribute carried along.
// The pipeline's phases are PrimitiveBaker's (bake/primitive_baker.hpp); this file runs them
// over a file and writes the result.
#include <algorithm>
#include <filesystem>
#include <system_error>

#include "bake/primitive_baker.hpp"
#include "entry_point.hpp"

namespace tangent::gltf {
namespace detail {

std::vector<PrimitiveResult> PrimitiveBaker::bakeAll() {
  // Every plan first: which primitives share a vertex buffer decides how each is baked.
  std::vector<PrimitivePlan> plans = planAll();
  const PlanGroups groups = groupPlans(plans);
  std::vector<PrimitiveResult> results;
  results.reserve(plans.size());
  for (std::size_t i = 0; i < plans.size(); ++i) {
    PrimitivePlan& plan = plans[i];
    if (plan.bake) refer(plan, bakedFor(i, groups, plans));
    results.push_back(std::move(plan.result));
  }
  return results;
}

// What plan `planIndex`'s inputs baked to: computed and emitted the first time its input key
// comes up (with the rest of its vertex group, where the group has several input keys).
const SharedBake& PrimitiveBaker::bakedFor(std::size_t planIndex, const PlanGroups& groups, std::vector<PrimitivePlan>& plans) {
  const std::string& inputKey = groups.inputKeys[planIndex];
  if (const auto found = baked_.find(inputKey); found != baked_.end()) return found->second;
  const VertexGroup& group = groups.groups[groups.groupOfPlan[planIndex]];
  if (group.firstOfInput.size() == 1) return baked_.emplace(inputKey, bakeInputs(plans[planIndex])).first->second;
  bakeVertexGroup(group, plans);  // every input key of the group
  for (const std::size_t first : group.firstOfInput) baked_.emplace(groups.inputKeys[first], std::move(groupBakes_[first]));
  groupBakes_.clear();
  return baked_.find(inputKey)->second;
}

// The primitive's inputs alone: its tangents over the whole of its vertex accessors.
SharedBake PrimitiveBaker::bakeInputs(PrimitivePlan& plan) {
  SharedBake shared;
  if (std::optional<ComputedTangents> computed = compute(plan)) {
    shared = emit(plan, *computed);
  } else {
    shared.notBaked = plan.result.reason;
  }
  carried_.clear();
  return shared;
}

}  // namespace detail

namespace {

using Json = nlohmann::ordered_json;

// Adds `name` to extensionsUsed and extensionsRequired unless there already.
void declareRequiredExtension(Json& doc, const char* name) {
  for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
    if (!doc.contains(list) || !doc[list].is_array()) doc[list] = Json::array();
    if (std::find(doc[list].begin(), doc[list].end(), Json(name)) == doc[list].end()) doc[list].push_back(name);
  }
}

// Refused before anything is read: an output that is not glTF, or that is the input itself.
void refuseOutputPath(const std::filesystem::path& input, const std::filesystem::path& output) {
  namespace fs = std::filesystem;
  const std::string outExt = output.extension().string();
  if (outExt != ".glb" && outExt != ".gltf")
    throw InputError(output.string() + ": output must end in .glb or .gltf");
  std::error_code ec;
  if (fs::exists(output, ec) && fs::equivalent(input, output, ec))
    throw InputError(output.string() + ": is the input file; bake never writes to its input");
}

// The output's folder, created where missing; then refused: an output (or a .gltf's .bin beside
// it) that is a file the input uses.
void prepareOutputPath(const detail::Asset& asset, const std::filesystem::path& output) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!output.parent_path().empty() && !fs::is_directory(output.parent_path(), ec)) {
    std::error_code made;
    fs::create_directories(output.parent_path(), made);
    if (!fs::is_directory(output.parent_path(), ec))
      throw std::runtime_error(output.parent_path().string() + ": cannot create the output's folder: " +
                               (made ? made.message() : std::string("not a folder")));
  }
  const bool gltf = output.extension() == ".gltf";
  fs::path binPath = output;
  binPath.replace_extension(".bin");
  for (const fs::path& used : detail::referencedFiles(asset)) {
    if ((gltf && fs::exists(used, ec) && fs::exists(binPath, ec) && fs::equivalent(used, binPath, ec)) ||
        (fs::exists(used, ec) && fs::exists(output, ec) && fs::equivalent(used, output, ec)))
      throw InputError(output.string() + ": would overwrite " + used.string() + ", which the input uses");
  }
}

// Warnings about what was baked: frame consumers on other UV sets, and non-finite input.
void warnAboutBaked(const std::filesystem::path& input, const Json& doc, const detail::Asset& asset, const BakeOptions& options,
                    BakeResult& result) {
  for (const PrimitiveResult& baked : result.primitives) {
    const std::string where = input.string() + ": " + detail::primitiveLabel(doc, baked.mesh, baked.primitive);
    // Consumers of the frame on other UV sets: TANGENT follows the first (the normal texture).
    if (baked.action == PrimitiveAction::baked) {
      const Json& primitive = doc["meshes"][baked.mesh]["primitives"][baked.primitive];
      const std::string other = detail::primitiveNeeds(doc, primitive, options.all || asset.fromMeshFile).otherFrames;
      if (!other.empty()) result.warnings.push_back(where + ": " + other);
    }
    // Non-finite input is baked (its corners get fallback frames) but never silently.
    if (!baked.tangents.nonFiniteTriangles && !baked.tangents.invalidNormals) continue;
    if (baked.tangents.nonFiniteTriangles)
      result.warnings.push_back(where + ": " + std::to_string(baked.tangents.nonFiniteTriangles) +
                                " triangles have non-finite (NaN or infinite) positions or UVs; their corners got fallback frames");
    if (baked.tangents.invalidNormals)
      result.warnings.push_back(where + ": " + std::to_string(baked.tangents.invalidNormals) +
                                " corners have zero or non-finite normals; replaced by their faces' normals");
  }
}

BakeResult bakeChecked(const std::filesystem::path& input, const std::filesystem::path& output, const BakeOptions& options) {
  refuseOutputPath(input, output);
  detail::Asset asset = detail::loadAsset(input, options.assetRoot);
  prepareOutputPath(asset, output);

  BakeResult result;
  result.warnings = asset.warnings;
  detail::OutputDocument document(asset);
  detail::PrimitiveBaker baker(asset, document, options);
  Json& doc = document.json();
  result.primitives = baker.bakeAll();
  warnAboutBaked(input, doc, asset, options, result);
  // Declared after the loop: no reference into the document is held across the insertion.
  if (std::any_of(result.primitives.begin(), result.primitives.end(),
                  [](const PrimitiveResult& p) { return p.action == PrimitiveAction::baked && p.tangentFormat != TangentFormat::float32; }))
    declareRequiredExtension(doc, "KHR_mesh_quantization");
  result.bytesWritten = document.write(output, options.protectedFiles, options.keepExternalImages);
  result.filesWritten = document.filesWritten();
  result.extensionsRemoved = document.extensionsRemoved();
  return result;
}

}  // namespace

BakeResult bakeFile(const std::filesystem::path& input, const std::filesystem::path& output, const BakeOptions& options) {
  return detail::throwingInputError(input, [&] { return bakeChecked(input, output, options); });
}

}  // namespace tangent::gltf
