// SPDX-License-Identifier: MIT
// What a mesh's primitives become for display: corners as check reads them, fresh tangents as
// check computes its reference, the file's tangents, colours, UV sets and check's verdicts.
#include "scene_parts.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "read/accessors.hpp"
#include "read/normals.hpp"
#include "read/primitive.hpp"

namespace tangent::gltf::scene_parts {
// Per-vertex values (components each) spread over the corners.
std::vector<float> perCorner(const std::vector<float>& values, int components, const std::vector<std::uint32_t>& corners) {
  std::vector<float> out(corners.size() * static_cast<std::size_t>(components));
  for (std::size_t c = 0; c < corners.size(); ++c)
    std::copy_n(&values[static_cast<std::size_t>(components) * corners[c]], components, &out[static_cast<std::size_t>(components) * c]);
  return out;
}

namespace {

// Reads what exists of POSITION, NORMAL and UVs; zero UVs where there are none, no normals
// where there is no NORMAL (cornerGeometry generates them).
detail::PrimitiveGeometry readForDisplay(const detail::Asset& asset, const Json& primitive, const detail::PrimitiveNeeds& needs,
                                         const std::string& where, std::vector<std::string>& messages, bool& hasUvs) {
  const Json& attributes = primitive["attributes"];
  const bool hasNormal = detail::accessorOf(attributes, "NORMAL") >= 0;
  hasUvs = detail::accessorOf(attributes, "TEXCOORD_" + std::to_string(needs.texCoord)) >= 0;
  // As check and bake read it (the normal texture's KHR_texture_transform applied): without
  // NORMAL, cornerGeometry generates the normals.
  if (hasUvs) {
    if (!hasNormal) messages.push_back(where + ": no NORMAL; shown with face normals");
    return detail::readGeometry(asset, primitive, needs, where, /*normalOptional=*/true);
  }
  // Fall back: positions and indices, then derived normals / zero UVs.
  const int position = detail::accessorOf(attributes, "POSITION");
  if (position < 0) throw InputError(where + ": has no POSITION attribute");
  detail::PrimitiveGeometry geometry;
  {
    detail::AccessorData header;
    geometry.positions = detail::readFloats(asset.model, position, where + ": POSITION", header);
    geometry.vertexCount = geometry.positions.size() / 3;
    geometry.mode = primitive.value("mode", 4);
    std::vector<std::uint32_t> sequence;
    const int indices = detail::accessorOf(primitive, "indices");
    if (indices >= 0) sequence = detail::toIndices(detail::readAccessor(asset.model, indices, where + ": indices"), geometry.vertexCount, where);
    else {
      sequence.resize(geometry.vertexCount);
      std::iota(sequence.begin(), sequence.end(), 0u);
    }
    geometry.corners = detail::triangleList(geometry.mode, std::move(sequence));
  }
  if (hasNormal) geometry.normals = detail::readVectors(asset.model, detail::accessorOf(attributes, "NORMAL"), 3, geometry.vertexCount, where + ": NORMAL");
  else messages.push_back(where + ": no NORMAL; shown with face normals");  // cornerGeometry's, empty here
  messages.push_back(where + ": no TEXCOORD_" + std::to_string(needs.texCoord) + "; tangents undefined, textures not applied");
  geometry.uvs.assign(geometry.vertexCount * 2, 0.0f);
  return geometry;
}

// A primitive's corners as the core sees them in bake and check: positions, the normal
// texture's UVs and NORMAL where the file has it, else the flat normals withGeneratedNormals
// gives (glTF 2.0 3.7.2.1; a triangle without area gets +Z), so that the fresh tangents are
// check's reference.
struct CornerGeometry {
  std::vector<float> positions, normals, uvs;  // 3, 3 and 2 per corner
};

CornerGeometry cornerGeometry(const detail::PrimitiveGeometry& geometry) {
  CornerGeometry out;
  out.positions = perCorner(geometry.positions, 3, geometry.corners);
  out.uvs = perCorner(geometry.uvs, 2, geometry.corners);
  if (!geometry.normals.empty()) {
    out.normals = perCorner(geometry.normals, 3, geometry.corners);
    return out;
  }
  std::vector<std::uint32_t> source;
  const detail::PrimitiveGeometry flat = detail::withGeneratedNormals(geometry, /*smooth=*/false, 0, source);
  out.normals = perCorner(flat.normals, 3, flat.corners);
  return out;
}

// The normals shaded with: the core's, except that a zero NORMAL takes its triangle's face
// normal (display only: check and the fresh tangents see the zero, as bake does).
std::vector<float> shadedNormals(const CornerGeometry& corners) {
  std::vector<float> normals = corners.normals;
  for (std::size_t t = 0; t < normals.size() / 9; ++t) {
    const float* p = &corners.positions[9 * t];
    const glm::vec3 face = glm::cross(glm::make_vec3(p + 3) - glm::make_vec3(p), glm::make_vec3(p + 6) - glm::make_vec3(p));
    const float length = glm::length(face);
    for (int k = 0; k < 3; ++k) {
      float* n = &normals[9 * t + 3 * k];
      if (n[0] == 0 && n[1] == 0 && n[2] == 0 && length > 0) std::copy_n(glm::value_ptr(face / length), 3, n);
    }
  }
  return normals;
}

// The file's TANGENT per corner into item.tangents (which hold the computed ones on entry), or a
// message why the computed ones stay.
void readFileTangents(const detail::Asset& asset, const Json& primitive, const detail::PrimitiveNeeds& needs,
                      const detail::PrimitiveGeometry& geometry, const std::string& where, const SceneOptions& options, DrawItem& item,
                      std::vector<std::string>& messages) {
  const int tangentAccessor = detail::accessorOf(primitive["attributes"], "TANGENT");
  if (tangentAccessor >= 0) {
    const auto data = detail::readAccessor(asset.model, tangentAccessor, where + ": TANGENT");
    if (data.type == TINYGLTF_TYPE_VEC4 && data.count == geometry.vertexCount) {
      const std::vector<float> fileTangents = detail::toFloats(data);
      item.tangentsFromFile = true;
      for (std::size_t c = 0; c < geometry.corners.size(); ++c)
        std::copy_n(&fileTangents[4 * geometry.corners[c]], 4, &item.tangents[4 * c]);
    } else {
      messages.push_back(where + ": TANGENT is not a VEC4 per vertex; computed tangents shown");
    }
  } else if (needs.hasNormalTexture) {
    messages.push_back(where + ": no TANGENT; computed with " + toString(Generator{options.check.method, options.check.weighting}) +
                       " at load");
  }
  if (options.negateFileW)
    for (std::size_t c = 0; c < geometry.corners.size(); ++c) item.tangents[4 * c + 3] = -item.tangents[4 * c + 3];
}

// check's verdict on each corner (tangent/verdict.hpp), where check judged the primitive: the
// error view's angle and problem bits.
void applyVerdicts(const PrimitiveVerdicts* verdicts, const std::string& where, DrawItem& item, std::vector<std::string>& messages) {
  const std::size_t corners = item.positions.size() / 3;
  item.tangentErrorDegrees.assign(corners, 0.0f);
  item.cornerProblems.assign(corners, 0);
  if (!verdicts) return;
  if (verdicts->corners.size() != corners) {
    messages.push_back(where + ": check judged " + std::to_string(verdicts->corners.size()) + " corners, " +
                       std::to_string(corners) + " are shown; no verdict shown");
    return;
  }
  for (std::size_t c = 0; c < corners; ++c) {
    item.tangentErrorDegrees[c] = verdicts->corners[c].referenceDegrees;
    item.cornerProblems[c] = verdicts->corners[c].problems;
  }
}

// Fresh tangents into item.computedTangents, per corner, as check computes its reference; the
// source of each frame (for markUndefinedFrames).
std::vector<FrameSource> freshTangents(const CornerGeometry& core, const SceneOptions& options, DrawItem& item) {
  const std::size_t cornerCount = core.positions.size() / 3;
  std::vector<std::uint32_t> identity(cornerCount);
  std::iota(identity.begin(), identity.end(), 0u);
  item.freshOptions.method = options.check.method;
  item.freshOptions.weighting = options.check.weighting;
  item.freshOptions.uvOrigin = kGltfUvOrigin;
  item.computedTangents.resize(cornerCount * 4);
  std::vector<FrameSource> sources(cornerCount);
  if (cornerCount > 0)
    item.report =
        computeCornerTangents({core.positions, core.normals, core.uvs, identity}, item.computedTangents, item.freshOptions, sources);
  return sources;
}

// TEXCOORD_0 and _1 as stored, per corner: the viewer applies each texture's own set and
// KHR_texture_transform (the normal texture's are in uvNormal already).
void readUvSets(const detail::Asset& asset, const Json& primitive, const detail::PrimitiveGeometry& geometry, const std::string& where,
                DrawItem& item) {
  for (int set = 0; set < 2; ++set) {
    item.uvSets[set].assign(geometry.corners.size() * 2, 0.0f);
    const int accessor = detail::accessorOf(primitive["attributes"], "TEXCOORD_" + std::to_string(set));
    if (accessor < 0) continue;
    const std::vector<float> uvs = detail::readVectors(asset.model, accessor, 2, geometry.vertexCount, where + ": TEXCOORD_" + std::to_string(set));
    item.uvSets[set] = perCorner(uvs, 2, geometry.corners);
  }
}

// COLOR_0 (glTF 2.0 3.7.2.1: float, or normalized unsigned byte or short; RGB or RGBA), per
// corner as RGBA; another form is left out with a message.
void readColours(const detail::Asset& asset, const Json& primitive, const detail::PrimitiveGeometry& geometry, const std::string& where,
                 DrawItem& item, std::vector<std::string>& messages) {
  const int colour = detail::accessorOf(primitive["attributes"], "COLOR_0");
  if (colour < 0) return;
  detail::AccessorData header;
  const std::vector<float> values = detail::readFloats(asset.model, colour, where + ": COLOR_0", header);
  const bool form = header.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                    (header.normalized && (header.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                           header.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
  if (!form || (header.components != 3 && header.components != 4) || header.count != geometry.vertexCount) {
    messages.push_back(where + ": COLOR_0 is not a VEC3 or VEC4 of floats or normalized unsigned bytes or shorts per vertex; not applied");
    return;
  }
  const std::size_t components = header.components;
  item.colors.assign(geometry.corners.size() * 4, 1.0f);
  for (std::size_t c = 0; c < geometry.corners.size(); ++c)
    std::copy_n(&values[components * geometry.corners[c]], components, &item.colors[4 * c]);
}

DrawItem makeDrawItem(const detail::Asset& asset, const Json& primitive, PrimitiveIndex index, const PrimitiveVerdicts* verdicts,
                      const SceneOptions& options, std::vector<std::string>& messages) {
  const Json& doc = asset.json;
  DrawItem item;
  item.primitive = index;
  item.label = detail::primitiveLabel(doc, index.mesh, index.primitive);
  const std::string where = asset.path.string() + ": " + item.label;
  item.material = primitive.value("material", -1);
  const detail::PrimitiveNeeds needs = detail::primitiveNeeds(doc, primitive, true);
  const detail::PrimitiveGeometry geometry = readForDisplay(asset, primitive, needs, where, messages, item.hasUvs);
  CornerGeometry core = cornerGeometry(geometry);
  const std::vector<FrameSource> sources = freshTangents(core, options, item);

  item.normals = shadedNormals(core);
  item.positions = std::move(core.positions);
  item.uvNormal = std::move(core.uvs);
  readUvSets(asset, primitive, geometry, where, item);
  readColours(asset, primitive, geometry, where, item, messages);

  // The file's tangents, and what check says of each corner.
  item.tangents = item.computedTangents;
  readFileTangents(asset, primitive, needs, geometry, where, options, item, messages);
  applyVerdicts(verdicts, where, item, messages);
  // Frames nothing defines (DrawItem::tangents): the fixed fallback, marked. The computed set is
  // marked even where the file has TANGENT (it is what the compare view shows beside the
  // file's); the file's own frames are kept as written.
  markUndefinedFrames(sources, item.computedTangents);
  if (!item.tangentsFromFile) markUndefinedFrames(sources, item.tangents);
  readDeformation(asset, primitive, geometry.vertexCount, geometry.corners, where, item, messages);
  return item;
}

}  // namespace

// The items that a mesh's primitives become, read on the mesh's first instance and shared by the
// rest: per primitive, an index into scene.items, or -1 where it is not shown (the message says
// why, once). `verdicts`: check's, on every primitive it judged, in (mesh, primitive) order.
std::vector<std::int64_t> readMeshItems(const detail::Asset& asset, int meshIndex, const std::vector<PrimitiveVerdicts>& verdicts,
                                        const SceneOptions& options, Scene& scene) {
  const Json& doc = asset.json;
  const Json& primitives = doc["meshes"][meshIndex]["primitives"];
  std::vector<std::int64_t> items(primitives.size(), -1);
  for (std::size_t p = 0; p < primitives.size(); ++p) {
    const PrimitiveIndex index{meshIndex, static_cast<int>(p)};
    const detail::PrimitiveNeeds needs = detail::primitiveNeeds(doc, primitives[p], true);
    if (!needs.triangles) {
      scene.messages.push_back(detail::primitiveLabel(doc, index.mesh, index.primitive) + ": " + needs.why + "; not shown");
      continue;
    }
    const auto judged = std::lower_bound(verdicts.begin(), verdicts.end(), index,
                                         [](const PrimitiveVerdicts& v, const PrimitiveIndex& i) { return v.primitive < i; });
    const bool found = judged != verdicts.end() && judged->primitive == index;
    DrawItem item = makeDrawItem(asset, primitives[p], index, found ? &*judged : nullptr, options, scene.messages);
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (std::size_t c = 0; c < item.positions.size() / 3; ++c) {
      const glm::vec3 position = glm::make_vec3(&item.positions[3 * c]);
      if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z)) continue;
      lo = glm::min(lo, position);
      hi = glm::max(hi, position);
    }
    item.boundsMin = {lo.x, lo.y, lo.z};
    item.boundsMax = {hi.x, hi.y, hi.z};
    items[p] = static_cast<std::int64_t>(scene.items.size());
    scene.items.push_back(std::move(item));
  }
  return items;
}

// Grows [lo, hi] by an item's object-space box under `world`: its eight corners, so that the cost
// per instance does not grow with the mesh (exact unless the transform turns the box off its axes).
void growBounds(const DrawItem& item, const glm::mat4& world, glm::vec3& lo, glm::vec3& hi) {
  if (item.boundsMin[0] > item.boundsMax[0]) return;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p(corner & 1 ? item.boundsMax[0] : item.boundsMin[0], corner & 2 ? item.boundsMax[1] : item.boundsMin[1],
                      corner & 4 ? item.boundsMax[2] : item.boundsMin[2]);
    const glm::vec3 q = glm::vec3(world * glm::vec4(p, 1));
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) continue;
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
}

}  // namespace tangent::gltf::scene_parts
