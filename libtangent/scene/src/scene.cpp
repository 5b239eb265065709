// SPDX-License-Identifier: MIT
// Flattening a glTF document for display (see tangent/scene.hpp). Node transforms follow the
// glTF 2.0 spec 3.5.3 (matrix, or T * R * S); lights come from KHR_lights_punctual.
#include "tangent/scene.hpp"

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include "read/accessors.hpp"
#include "read/animation_rules.hpp"
#include "read/asset.hpp"
#include "check/check_primitive.hpp"
#include "entry_point.hpp"
#include "read/normals.hpp"
#include "read/primitive.hpp"
#include "tangent/gltf.hpp"
#include "tangent/text.hpp"
#include "check/tangent_rules.hpp"
#include "read/uri.hpp"

namespace tangent::gltf {
namespace {

using Json = nlohmann::ordered_json;

std::vector<ImageSource> readImages(const detail::Asset& asset) {
  std::vector<ImageSource> images;
  if (!asset.json.contains("images")) return images;
  const auto dir = std::filesystem::absolute(asset.path).parent_path();
  for (std::size_t i = 0; i < asset.json["images"].size(); ++i) {
    const Json& image = asset.json["images"][i];
    ImageSource source;
    // Names the file and the image (and its URI) in the viewer's messages.
    source.label = asset.path.string() + ": image " + std::to_string(i);
    source.mimeType = image.value("mimeType", "");
    if (image.contains("uri") && image["uri"].is_string()) {
      const std::string uri = image["uri"].get<std::string>();
      if (detail::isDataUri(uri)) {
        source.bytes = detail::decodeDataUri(uri, asset.path.string() + ": /images/" + std::to_string(i));
        source.mimeType = uri.substr(5, uri.find(';') - 5);
      } else {
        // loadAsset refused URIs that leave the asset root; a missing file leaves the image empty
        // (loadAsset's warning, among the messages, says so).
        source.label += " '" + uri + "'";
        try {
          source.file = detail::resolveFileUri(uri, dir, asset.root, asset.path.string(), "/images/" + std::to_string(i));
        } catch (const detail::MissingFileError& e) {
          source.missing = e.what();
        }
      }
    } else if (image.contains("bufferView") && image["bufferView"].is_number_integer()) {
      const int viewIndex = image["bufferView"].get<int>();
      if (viewIndex >= 0 && viewIndex < static_cast<int>(asset.model.bufferViews.size())) {
        const auto& view = asset.model.bufferViews[viewIndex];
        const auto& buffer = asset.model.buffers[view.buffer].data;
        if (view.byteOffset <= buffer.size() && view.byteLength <= buffer.size() - view.byteOffset)
          source.bytes.assign(buffer.begin() + view.byteOffset, buffer.begin() + view.byteOffset + view.byteLength);
      }
    }
    images.push_back(std::move(source));
  }
  return images;
}

// glTF's sampler codes (the GL enums' values) as TextureSampler's; an unknown code gives the
// default (repeat, automatic).
TextureSampler::Wrap wrapOf(const Json& sampler, const char* key) {
  switch (sampler.contains(key) && sampler[key].is_number_integer() ? sampler[key].get<int>() : 10497) {
    case 33071: return TextureSampler::Wrap::clampToEdge;
    case 33648: return TextureSampler::Wrap::mirroredRepeat;
    default: return TextureSampler::Wrap::repeat;
  }
}

TextureSampler::Filter filterOf(const Json& sampler, const char* key) {
  using Filter = TextureSampler::Filter;
  switch (sampler.contains(key) && sampler[key].is_number_integer() ? sampler[key].get<int>() : 0) {
    case 9728: return Filter::nearest;
    case 9729: return Filter::linear;
    case 9984: return Filter::nearestMipmapNearest;
    case 9985: return Filter::linearMipmapNearest;
    case 9986: return Filter::nearestMipmapLinear;
    case 9987: return Filter::linearMipmapLinear;
    default: return Filter::automatic;
  }
}

TextureSampler samplerOf(const Json& doc, const Json& texture) {
  TextureSampler sampler;
  const int index = texture.contains("sampler") && texture["sampler"].is_number_integer() ? texture["sampler"].get<int>() : -1;
  if (index < 0 || !doc.contains("samplers") || !doc["samplers"].is_array() || index >= static_cast<int>(doc["samplers"].size()))
    return sampler;
  const Json& json = doc["samplers"][index];
  if (!json.is_object()) return sampler;
  sampler.wrapS = wrapOf(json, "wrapS");
  sampler.wrapT = wrapOf(json, "wrapT");
  sampler.magFilter = filterOf(json, "magFilter");
  sampler.minFilter = filterOf(json, "minFilter");
  return sampler;
}

TextureRef textureRef(const Json& doc, const Json& info) {
  TextureRef ref;
  if (!info.is_object() || !info.contains("index")) return ref;
  const int texture = info["index"].get<int>();
  if (!doc.contains("textures") || texture < 0 || texture >= static_cast<int>(doc["textures"].size())) return ref;
  const Json& textureJson = doc["textures"][texture];
  ref.image = textureJson.value("source", -1);
  ref.sampler = samplerOf(doc, textureJson);
  ref.texCoord = info.value("texCoord", 0);
  if (info.contains("extensions") && info["extensions"].contains("KHR_texture_transform")) {
    const Json& transform = info["extensions"]["KHR_texture_transform"];
    ref.texCoord = transform.value("texCoord", ref.texCoord);
    const std::array<double, 6> m = detail::textureTransformMatrix(transform);
    std::copy(m.begin(), m.end(), ref.uvTransform.begin());
  }
  ref.scale = info.value("scale", info.value("strength", 1.0f));
  return ref;
}

TextureRef colourTextureRef(const Json& doc, const Json& info) {
  TextureRef ref = textureRef(doc, info);
  ref.colour = true;
  return ref;
}

// A JSON number as a float: NaN for what is not a number, +-infinity past FLT_MAX (1e39), where
// a plain conversion would be undefined. The checks below then see what is not finite.
float jsonFloat(const Json& value) {
  if (!value.is_number()) return std::numeric_limits<float>::quiet_NaN();
  const double d = value.get<double>();
  if (std::abs(d) <= static_cast<double>(std::numeric_limits<float>::max())) return static_cast<float>(d);
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  return d > 0 ? kInfinity : d < 0 ? -kInfinity : std::numeric_limits<float>::quiet_NaN();
}

float floatValue(const Json& object, const char* key, float otherwise) {
  return object.contains(key) ? jsonFloat(object[key]) : otherwise;
}

template <std::size_t N>
void readFloats(const Json& object, const char* key, std::array<float, N>& out) {
  if (!object.contains(key) || !object[key].is_array() || object[key].size() != N) return;
  for (std::size_t i = 0; i < N; ++i) out[i] = jsonFloat(object[key][i]);
}

template <std::size_t N>
bool allFinite(const std::array<float, N>& values) {
  return std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); });
}

// The first element (a group of `components` values) of `values` with a value that is not
// finite, or -1 when every one is.
std::int64_t firstNonFinite(std::span<const float> values, std::size_t components) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i])) return static_cast<std::int64_t>(i / components);
  return -1;
}

// What makes a node's own transform unusable, or "" when nothing does: a value of its matrix,
// translation, rotation or scale that is not finite (NaN, or 1e39, past a float's range). Such
// a node is shown with the identity instead (flattenScene says so, once per node).
std::string transformProblem(const Json& node) {
  if (node.contains("matrix") && node["matrix"].is_array() && node["matrix"].size() == 16) {
    std::array<float, 16> matrix{};
    readFloats(node, "matrix", matrix);
    if (!allFinite(matrix)) return "matrix not finite";
  }
  std::array<float, 3> translation{0, 0, 0}, scale{1, 1, 1};
  std::array<float, 4> rotation{0, 0, 0, 1};
  readFloats(node, "translation", translation);
  readFloats(node, "rotation", rotation);
  readFloats(node, "scale", scale);
  if (!allFinite(translation)) return "translation not finite";
  if (!allFinite(rotation)) return "rotation not finite";
  if (!allFinite(scale)) return "scale not finite";
  return "";
}

std::vector<MaterialDesc> readMaterials(const Json& doc) {
  std::vector<MaterialDesc> materials;
  if (!doc.contains("materials")) return materials;
  for (const Json& m : doc["materials"]) {
    MaterialDesc material;
    material.name = m.value("name", "");
    material.doubleSided = m.value("doubleSided", false);
    if (m.contains("pbrMetallicRoughness")) {
      const Json& pbr = m["pbrMetallicRoughness"];
      readFloats(pbr, "baseColorFactor", material.baseColor);
      material.metallic = floatValue(pbr, "metallicFactor", 1.0f);
      material.roughness = floatValue(pbr, "roughnessFactor", 1.0f);
      if (pbr.contains("baseColorTexture")) material.baseColorTexture = colourTextureRef(doc, pbr["baseColorTexture"]);
      if (pbr.contains("metallicRoughnessTexture")) material.metallicRoughnessTexture = textureRef(doc, pbr["metallicRoughnessTexture"]);
    }
    if (m.contains("normalTexture")) material.normalTexture = textureRef(doc, m["normalTexture"]);
    if (m.contains("emissiveTexture")) material.emissiveTexture = colourTextureRef(doc, m["emissiveTexture"]);
    if (m.contains("occlusionTexture")) material.occlusionTexture = textureRef(doc, m["occlusionTexture"]);
    readFloats(m, "emissiveFactor", material.emissive);
    const std::string alphaMode = m.value("alphaMode", "OPAQUE");
    material.alphaMode = alphaMode == "MASK"    ? MaterialDesc::AlphaMode::mask
                         : alphaMode == "BLEND" ? MaterialDesc::AlphaMode::blend
                                                : MaterialDesc::AlphaMode::opaque;
    material.alphaCutoff = floatValue(m, "alphaCutoff", 0.5f);
    material.unlit = m.contains("extensions") && m["extensions"].contains("KHR_materials_unlit");
    if (m.contains("extensions") && m["extensions"].contains("KHR_materials_specular")) {
      const Json& specular = m["extensions"]["KHR_materials_specular"];
      material.hasSpecular = true;
      material.specularFactor = floatValue(specular, "specularFactor", 1.0f);
      readFloats(specular, "specularColorFactor", material.specularColor);
      if (specular.contains("specularTexture")) material.specularTexture = textureRef(doc, specular["specularTexture"]);
      if (specular.contains("specularColorTexture")) material.specularColorTexture = colourTextureRef(doc, specular["specularColorTexture"]);
    }
    if (m.contains("extensions") && m["extensions"].contains("KHR_materials_clearcoat")) {
      const Json& clearcoat = m["extensions"]["KHR_materials_clearcoat"];
      material.clearcoat = floatValue(clearcoat, "clearcoatFactor", 0.0f);
      material.clearcoatRoughness = floatValue(clearcoat, "clearcoatRoughnessFactor", 0.0f);
      if (clearcoat.contains("clearcoatTexture")) material.clearcoatTexture = textureRef(doc, clearcoat["clearcoatTexture"]);
      if (clearcoat.contains("clearcoatRoughnessTexture"))
        material.clearcoatRoughnessTexture = textureRef(doc, clearcoat["clearcoatRoughnessTexture"]);
      if (clearcoat.contains("clearcoatNormalTexture")) material.clearcoatNormalTexture = textureRef(doc, clearcoat["clearcoatNormalTexture"]);
    }
    if (m.contains("extensions") && m["extensions"].contains("KHR_materials_anisotropy")) {
      const Json& anisotropy = m["extensions"]["KHR_materials_anisotropy"];
      material.hasAnisotropy = true;
      material.anisotropyStrength = floatValue(anisotropy, "anisotropyStrength", 0.0f);
      material.anisotropyRotation = floatValue(anisotropy, "anisotropyRotation", 0.0f);
      if (anisotropy.contains("anisotropyTexture")) material.anisotropyTexture = textureRef(doc, anisotropy["anisotropyTexture"]);
    }
    materials.push_back(material);
  }
  return materials;
}

// The node's local transform; the identity where transformProblem finds one (`usable` false).
glm::mat4 localTransform(const Json& node, bool usable) {
  if (!usable) return glm::mat4(1);
  if (node.contains("matrix") && node["matrix"].size() == 16) {
    glm::mat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = jsonFloat(node["matrix"][i]);
    return m;
  }
  std::array<float, 3> t{0, 0, 0}, s{1, 1, 1};
  std::array<float, 4> r{0, 0, 0, 1};
  readFloats(node, "translation", t);
  readFloats(node, "scale", s);
  readFloats(node, "rotation", r);
  const glm::quat q(r[3], r[0], r[1], r[2]);
  return glm::translate(glm::mat4(1), glm::vec3(t[0], t[1], t[2])) * glm::mat4_cast(q) * glm::scale(glm::mat4(1), glm::vec3(s[0], s[1], s[2]));
}

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

// Per-vertex values (components each) spread over the corners.
std::vector<float> perCorner(const std::vector<float>& values, int components, const std::vector<std::uint32_t>& corners) {
  std::vector<float> out(corners.size() * static_cast<std::size_t>(components));
  for (std::size_t c = 0; c < corners.size(); ++c)
    std::copy_n(&values[static_cast<std::size_t>(components) * corners[c]], components, &out[static_cast<std::size_t>(components) * c]);
  return out;
}

// Morph targets (POSITION, NORMAL, TANGENT deltas) and skin influences (every JOINTS_n /
// WEIGHTS_n pair) of a primitive, per corner. A malformed one is left out with a message: the
// primitive is still shown, undeformed.
void readDeformation(const detail::Asset& asset, const Json& primitive, std::size_t vertexCount, const std::vector<std::uint32_t>& corners,
                     const std::string& where, DrawItem& item, std::vector<std::string>& messages) {
  try {
    if (primitive.contains("targets") && primitive["targets"].is_array()) {
      for (std::size_t t = 0; t < primitive["targets"].size(); ++t) {
        const Json& target = primitive["targets"][t];
        MorphTarget morph;
        const std::string prefix = where + ": morph target " + std::to_string(t) + " ";
        // The deltas of one attribute, per corner; a value that is not finite would carry every
        // corner it moves to NaN, so it is refused by element.
        auto deltas = [&](int accessor, const char* attribute) {
          const std::vector<float> values = detail::readVectors(asset.model, accessor, 3, vertexCount, prefix + attribute);
          if (const std::int64_t bad = firstNonFinite(values, 3); bad >= 0)
            throw InputError(prefix + attribute + " element " + std::to_string(bad) + " is not finite");
          return perCorner(values, 3, corners);
        };
        if (const int a = detail::accessorOf(target, "POSITION"); a >= 0) morph.positions = deltas(a, "POSITION");
        if (const int a = detail::accessorOf(target, "NORMAL"); a >= 0) morph.normals = deltas(a, "NORMAL");
        if (const int a = detail::accessorOf(target, "TANGENT"); a >= 0 && item.tangentsFromFile) morph.tangents = deltas(a, "TANGENT");
        item.morphTargets.push_back(std::move(morph));
      }
    }
  } catch (const InputError& e) {
    item.morphTargets.clear();
    messages.push_back(std::string(e.what()) + "; morph targets not applied");
  }
  try {
    const Json& attributes = primitive["attributes"];
    std::vector<std::vector<float>> joints, weights;
    for (int set = 0;; ++set) {
      const int j = detail::accessorOf(attributes, "JOINTS_" + std::to_string(set));
      const int w = detail::accessorOf(attributes, "WEIGHTS_" + std::to_string(set));
      if (j < 0 || w < 0) break;
      joints.push_back(detail::readVectors(asset.model, j, 4, vertexCount, where + ": JOINTS_" + std::to_string(set)));
      weights.push_back(detail::readVectors(asset.model, w, 4, vertexCount, where + ": WEIGHTS_" + std::to_string(set)));
      // A weight that is not finite would make the corner's skin matrix, and so the corner, NaN.
      if (const std::int64_t bad = firstNonFinite(weights.back(), 4); bad >= 0)
        throw InputError(where + ": WEIGHTS_" + std::to_string(set) + " element " + std::to_string(bad) + " is not finite");
    }
    const int sets = static_cast<int>(joints.size());
    item.influencesPerCorner = 4 * sets;
    item.joints.resize(corners.size() * item.influencesPerCorner);
    item.jointWeights.resize(corners.size() * item.influencesPerCorner);
    for (std::size_t c = 0; c < corners.size(); ++c) {
      for (int set = 0; set < sets; ++set) {
        for (int k = 0; k < 4; ++k) {
          const std::size_t out = c * item.influencesPerCorner + 4 * set + k;
          const float joint = joints[set][4 * corners[c] + k];
          item.joints[out] = static_cast<std::uint16_t>(std::clamp(joint, 0.0f, 65535.0f));
          item.jointWeights[out] = weights[set][4 * corners[c] + k];
        }
      }
    }
  } catch (const InputError& e) {
    item.influencesPerCorner = 0;
    item.joints.clear();
    item.jointWeights.clear();
    messages.push_back(std::string(e.what()) + "; skin not applied");
  }
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
  const std::size_t cornerCount = geometry.corners.size();
  const std::vector<std::uint32_t>& corners = geometry.corners;
  CornerGeometry core = cornerGeometry(geometry);

  // Fresh tangents, per corner, as check computes its reference.
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

  item.normals = shadedNormals(core);
  item.positions = std::move(core.positions);
  item.uvNormal = std::move(core.uvs);
  // TEXCOORD_0 and _1 as stored, per corner: the viewer applies each texture's own set and
  // KHR_texture_transform (the normal texture's are in uvNormal already).
  for (int set = 0; set < 2; ++set) {
    item.uvSets[set].assign(cornerCount * 2, 0.0f);
    const int accessor = detail::accessorOf(primitive["attributes"], "TEXCOORD_" + std::to_string(set));
    if (accessor < 0) continue;
    const std::vector<float> uvs = detail::readVectors(asset.model, accessor, 2, geometry.vertexCount, where + ": TEXCOORD_" + std::to_string(set));
    item.uvSets[set] = perCorner(uvs, 2, corners);
  }

  // COLOR_0 (glTF 2.0 3.7.2.1: float, or normalized unsigned byte or short; RGB or RGBA), per
  // corner as RGBA; another form is left out with a message.
  if (const int colour = detail::accessorOf(primitive["attributes"], "COLOR_0"); colour >= 0) {
    detail::AccessorData header;
    const std::vector<float> values = detail::readFloats(asset.model, colour, where + ": COLOR_0", header);
    const bool form = header.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                      (header.normalized && (header.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                             header.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
    if (!form || (header.components != 3 && header.components != 4) || header.count != geometry.vertexCount) {
      messages.push_back(where + ": COLOR_0 is not a VEC3 or VEC4 of floats or normalized unsigned bytes or shorts per vertex; not applied");
    } else {
      const std::size_t components = header.components;
      item.colors.assign(cornerCount * 4, 1.0f);
      for (std::size_t c = 0; c < cornerCount; ++c)
        std::copy_n(&values[components * corners[c]], components, &item.colors[4 * c]);
    }
  }

  // The file's tangents, and what check says of each corner.
  item.tangents = item.computedTangents;
  readFileTangents(asset, primitive, needs, geometry, where, options, item, messages);
  applyVerdicts(verdicts, where, item, messages);
  // Frames nothing defines (DrawItem::tangents): the fixed fallback, marked. The computed set is
  // marked even where the file has TANGENT (it is what the compare view shows beside the
  // file's); the file's own frames are kept as written.
  markUndefinedFrames(sources, item.computedTangents);
  if (!item.tangentsFromFile) markUndefinedFrames(sources, item.tangents);
  readDeformation(asset, primitive, geometry.vertexCount, corners, where, item, messages);
  return item;
}

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

LightDesc lightAt(const Json& definition, const glm::mat4& world) {
  LightDesc light;
  const std::string type = definition.value("type", "directional");
  light.type = type == "point" ? LightDesc::Type::point : type == "spot" ? LightDesc::Type::spot : LightDesc::Type::directional;
  light.name = definition.value("name", "");
  readFloats(definition, "color", light.color);
  light.intensity = floatValue(definition, "intensity", 1.0f);
  light.range = floatValue(definition, "range", 0.0f);
  if (definition.contains("spot")) {
    light.innerConeAngle = floatValue(definition["spot"], "innerConeAngle", 0.0f);
    light.outerConeAngle = floatValue(definition["spot"], "outerConeAngle", 0.785398f);
  }
  const glm::vec3 position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
  const glm::vec3 direction = glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
  light.position = {position.x, position.y, position.z};
  light.direction = {direction.x, direction.y, direction.z};
  return light;
}

// What makes a light unusable, or "" when nothing does: a value that is not finite (its own, or
// its place and direction, as its node puts them).
std::string lightProblem(const LightDesc& light) {
  if (!allFinite(light.color)) return "color not finite";
  if (!std::isfinite(light.intensity)) return "intensity not finite";
  if (!std::isfinite(light.range)) return "range not finite";
  if (!std::isfinite(light.innerConeAngle) || !std::isfinite(light.outerConeAngle)) return "spot cone angle not finite";
  if (!allFinite(light.position) || !allFinite(light.direction)) return "position or direction not finite (its node's transform)";
  return "";
}

bool posable(const Json& doc) {
  auto nonEmpty = [&](const char* key) { return doc.contains(key) && doc[key].is_array() && !doc[key].empty(); };
  if (nonEmpty("animations") || nonEmpty("skins")) return true;
  if (!nonEmpty("meshes")) return false;
  for (const Json& mesh : doc["meshes"]) {
    for (const Json& primitive : mesh.value("primitives", Json::array()))
      if (primitive.contains("targets") && !primitive["targets"].empty()) return true;
  }
  return false;
}

// Every node's parent, local transform, morph weights and skin (glTF 2.0 3.5). A node whose
// transform is unusable (`unusable`, which flattenScene has reported) keeps the identity; a morph
// weight that is not finite is 0, with a message naming the node.
std::vector<SceneNode> readNodes(const Json& doc, const std::vector<char>& unusable, const std::string& file,
                                 std::vector<std::string>& messages) {
  const std::size_t nodeCount = doc["nodes"].size();
  std::vector<SceneNode> nodes(nodeCount);
  for (std::size_t n = 0; n < nodeCount; ++n) {
    const Json& node = doc["nodes"][n];
    SceneNode& out = nodes[n];
    if (!unusable[n]) {  // else the identity: SceneNode's defaults
      if (node.contains("matrix") && node["matrix"].is_array() && node["matrix"].size() == 16) {
        out.hasMatrix = true;
        readFloats(node, "matrix", out.matrix);
      }
      readFloats(node, "translation", out.translation);
      readFloats(node, "rotation", out.rotation);
      readFloats(node, "scale", out.scale);
    }
    out.skin = node.value("skin", -1);
    const Json* weights = nullptr;
    if (node.contains("weights") && node["weights"].is_array()) weights = &node["weights"];
    else if (node.contains("mesh") && node["mesh"].is_number_integer() && doc.contains("meshes")) {
      const int mesh = node["mesh"].get<int>();
      if (mesh >= 0 && mesh < static_cast<int>(doc["meshes"].size()) && doc["meshes"][mesh].contains("weights"))
        weights = &doc["meshes"][mesh]["weights"];
    }
    if (weights) {
      for (const Json& w : *weights) {
        const float weight = jsonFloat(w);
        if (!std::isfinite(weight))
          messages.push_back(file + ": node " + std::to_string(n) + ": morph weight " + std::to_string(out.weights.size()) +
                             " is not finite; treated as 0");
        out.weights.push_back(std::isfinite(weight) ? weight : 0.0f);
      }
    }
    for (const Json& child : node.value("children", Json::array())) {
      const auto c = child.get<std::size_t>();
      if (c < nodeCount) nodes[c].parent = static_cast<int>(n);
    }
  }
  return nodes;
}

std::vector<Skin> readSkins(const detail::Asset& asset, std::size_t nodeCount, std::vector<SceneNode>& nodes, std::vector<std::string>& messages) {
  const Json& doc = asset.json;
  std::vector<Skin> skins;
  if (!doc.contains("skins")) return skins;
  for (std::size_t s = 0; s < doc["skins"].size(); ++s) {
    const Json& json = doc["skins"][s];
    const std::string where = asset.path.string() + ": skin " + std::to_string(s);
    Skin skin;
    try {
      for (const Json& joint : json.value("joints", Json::array())) {
        const auto node = joint.get<std::int64_t>();
        if (node < 0 || static_cast<std::size_t>(node) >= nodeCount) throw InputError(where + ": joint " + std::to_string(node) + " is not a node");
        skin.joints.push_back(static_cast<std::uint32_t>(node));
      }
      const std::array<float, 16> identity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
      skin.inverseBindMatrices.assign(skin.joints.size(), identity);
      if (const int a = detail::accessorOf(json, "inverseBindMatrices"); a >= 0) {
        const std::vector<float> matrices = detail::readVectors(asset.model, a, 16, skin.joints.size(), where + ": inverseBindMatrices");
        if (const std::int64_t bad = firstNonFinite(matrices, 16); bad >= 0)
          throw InputError(where + ": inverseBindMatrices element " + std::to_string(bad) + " is not finite");
        for (std::size_t j = 0; j < skin.joints.size(); ++j) std::copy_n(&matrices[16 * j], 16, skin.inverseBindMatrices[j].begin());
      }
    } catch (const InputError& e) {
      messages.push_back(std::string(e.what()) + "; meshes with this skin shown unskinned");
      skin = Skin{};
    }
    skins.push_back(std::move(skin));
  }
  for (SceneNode& node : nodes)
    if (node.skin >= static_cast<int>(skins.size()) || (node.skin >= 0 && skins[node.skin].joints.empty())) node.skin = -1;
  return skins;
}

// glTF 2.0 3.7.3.1: a JOINTS value is an index into the skin's joints. A node whose skin has
// fewer joints than one of its primitives names (with a weight) is drawn unskinned, with a
// message naming the node, the primitive and the joint; the rest of its skinning would be a guess.
void dropSkinsPastTheirJoints(Scene& scene, const std::string& file) {
  for (const DrawInstance& instance : scene.instances) {
    if (instance.node >= scene.nodes.size()) continue;
    SceneNode& node = scene.nodes[instance.node];
    if (node.skin < 0) continue;
    const DrawItem& item = scene.items[instance.item];
    const std::size_t jointCount = scene.skins[static_cast<std::size_t>(node.skin)].joints.size();
    for (std::size_t i = 0; i < item.joints.size(); ++i) {
      if (item.jointWeights[i] == 0 || item.joints[i] < jointCount) continue;
      const auto influences = static_cast<std::size_t>(item.influencesPerCorner);
      scene.messages.push_back(file + ": node " + std::to_string(instance.node) + ": " + item.label + ": JOINTS_" +
                               std::to_string(i % influences / 4) + " at corner " + std::to_string(i / influences) + " names joint " +
                               std::to_string(item.joints[i]) + ", past the " + std::to_string(jointCount) + " joint(s) of skin " +
                               std::to_string(node.skin) + "; the node drawn unskinned");
      node.skin = -1;
      break;
    }
  }
}

// glTF 2.0 3.11. A channel or sampler that cannot be used is left out with a message.
std::vector<Animation> readAnimations(const detail::Asset& asset, std::size_t nodeCount, std::vector<std::string>& messages) {
  const Json& doc = asset.json;
  std::vector<Animation> animations;
  if (!doc.contains("animations")) return animations;
  for (std::size_t a = 0; a < doc["animations"].size(); ++a) {
    const Json& json = doc["animations"][a];
    const std::string where = asset.path.string() + ": animation " + std::to_string(a);
    Animation animation;
    animation.name = json.value("name", "");
    const Json samplers = json.value("samplers", Json::array());
    std::vector<int> usable(samplers.size(), 0);
    for (std::size_t s = 0; s < samplers.size(); ++s) {
      AnimationSampler sampler;
      // loadAsset's validation checked the name (animation_rules.hpp); absent is LINEAR.
      switch (detail::interpolationOf(samplers[s].value("interpolation", "LINEAR")).value_or(detail::Interpolation::linear)) {
        case detail::Interpolation::step: sampler.interpolation = AnimationSampler::Interpolation::step; break;
        case detail::Interpolation::cubicSpline: sampler.interpolation = AnimationSampler::Interpolation::cubicSpline; break;
        case detail::Interpolation::linear: sampler.interpolation = AnimationSampler::Interpolation::linear; break;
      }
      try {
        const int input = detail::accessorOf(samplers[s], "input"), output = detail::accessorOf(samplers[s], "output");
        if (input < 0 || output < 0) throw InputError(where + ": sampler " + std::to_string(s) + " lacks input or output");
        sampler.times = detail::readVectors(asset.model, input, 1, 0, where + ": sampler " + std::to_string(s) + " input");
        detail::AccessorData header;
        sampler.values = detail::readFloats(asset.model, output, where + ": sampler " + std::to_string(s) + " output", header);
        if (sampler.times.empty()) throw InputError(where + ": sampler " + std::to_string(s) + " has no keyframes");
        if (const std::int64_t bad = firstNonFinite(sampler.times, 1); bad >= 0)
          throw InputError(where + ": sampler " + std::to_string(s) + " input element " + std::to_string(bad) + " is not finite");
        if (const std::int64_t bad = firstNonFinite(sampler.values, 1); bad >= 0)
          throw InputError(where + ": sampler " + std::to_string(s) + " output value " + std::to_string(bad) + " is not finite");
        for (std::size_t k = 1; k < sampler.times.size(); ++k)
          if (!(sampler.times[k] > sampler.times[k - 1]))
            throw InputError(where + ": sampler " + std::to_string(s) + " input times do not increase");
        animation.duration = std::max(animation.duration, sampler.times.back());
        usable[s] = 1;
      } catch (const InputError& e) {
        messages.push_back(std::string(e.what()) + "; its channels left out");
      }
      animation.samplers.push_back(std::move(sampler));
    }
    for (const Json& channel : json.value("channels", Json::array())) {
      const int sampler = channel.value("sampler", -1);
      const Json target = channel.value("target", Json::object());
      const int node = target.value("node", -1);
      const std::string path = target.value("path", "");
      AnimationChannel out;
      const std::optional<detail::AnimationPath> parsed = detail::animationPathOf(path);
      if (!parsed) continue;  // pointer (KHR_animation_pointer) is not shown
      switch (*parsed) {
        case detail::AnimationPath::translation: out.path = AnimationChannel::Path::translation; break;
        case detail::AnimationPath::rotation: out.path = AnimationChannel::Path::rotation; break;
        case detail::AnimationPath::scale: out.path = AnimationChannel::Path::scale; break;
        case detail::AnimationPath::weights: out.path = AnimationChannel::Path::weights; break;
      }
      // Validation checked the output's format and count against the input's keyframes
      // (keyframeValueCount); what is left is data: times that do not increase.
      if (sampler < 0 || sampler >= static_cast<int>(usable.size()) || !usable[sampler] || node < 0 || node >= static_cast<int>(nodeCount))
        continue;
      out.node = static_cast<std::uint32_t>(node);
      out.sampler = static_cast<std::uint32_t>(sampler);
      animation.channels.push_back(out);
    }
    animations.push_back(std::move(animation));
  }
  return animations;
}

// The nodes the walk starts from: the default scene's, or, in a file without one, every node
// without a parent.
std::vector<int> rootNodes(const Json& doc) {
  std::vector<int> roots;
  const int sceneIndex = doc.value("scene", 0);
  const std::size_t nodeCount = doc.contains("nodes") ? doc["nodes"].size() : 0;
  if (doc.contains("scenes") && sceneIndex >= 0 && sceneIndex < static_cast<int>(doc["scenes"].size())) {
    for (const Json& root : doc["scenes"][sceneIndex].value("nodes", Json::array())) roots.push_back(root.get<int>());
  } else if (nodeCount > 0) {
    std::vector<char> isChild(nodeCount, 0);
    for (const Json& node : doc["nodes"]) {
      if (!node.contains("children")) continue;
      for (const Json& child : node["children"]) isChild[child.get<std::size_t>()] = 1;
    }
    for (std::size_t n = 0; n < nodeCount; ++n)
      if (!isChild[n]) roots.push_back(static_cast<int>(n));
  }
  return roots;
}

// check's verdict on every corner it judges (checkCorners with options.check): what the error
// view shows. A file check cannot judge is still shown, without verdicts, and a message says why.
std::vector<PrimitiveVerdicts> judgeCorners(const detail::Asset& asset, const std::filesystem::path& input, const SceneOptions& options,
                                            std::vector<std::string>& messages) {
  try {
    return detail::checkCorners(asset, input, options.check);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    messages.push_back(std::string(e.what()) + "; tangent check cannot judge it, so the error view shows no verdict");
    return {};
  }
}

// The KHR_lights_punctual lights the document defines (nodes refer to them by index).
std::vector<Json> lightDefinitionsOf(const Json& doc) {
  std::vector<Json> lightDefinitions;
  if (doc.contains("extensions") && doc["extensions"].contains("KHR_lights_punctual") &&
      doc["extensions"]["KHR_lights_punctual"].contains("lights")) {
    for (const Json& light : doc["extensions"]["KHR_lights_punctual"]["lights"]) lightDefinitions.push_back(light);
  }
  return lightDefinitions;
}

// Nodes whose own transform is unusable: shown with the identity, each named once.
std::vector<char> unusableTransforms(const Json& doc, std::size_t nodeCount, const std::string& file, std::vector<std::string>& messages) {
  std::vector<char> unusableTransform(nodeCount, 0);
  for (std::size_t n = 0; n < nodeCount; ++n) {
    if (const std::string problem = transformProblem(doc["nodes"][n]); !problem.empty()) {
      unusableTransform[n] = 1;
      messages.push_back(file + ": node " + std::to_string(n) + ": " + problem + "; treated as identity");
    }
  }
  return unusableTransform;
}

// A node's KHR_lights_punctual reference (`reference`) placed by its world transform into
// scene.lights, or a message saying why it was left out.
void addNodeLight(const Json& reference, int nodeIndex, const glm::mat4& world, const std::vector<Json>& lightDefinitions,
                  const std::string& file, Scene& scene) {
  const bool hasIndex = reference.contains("light") && reference["light"].is_number_integer();
  const std::int64_t lightIndex = hasIndex ? reference["light"].get<std::int64_t>() : -1;
  const std::string where = file + ": node " + std::to_string(nodeIndex) + ": KHR_lights_punctual light ";
  if (lightIndex < 0 || lightIndex >= static_cast<std::int64_t>(lightDefinitions.size())) {
    const std::string named = reference.contains("light") ? text::dumpJson(reference["light"]) : std::string("(none)");
    scene.messages.push_back(where + named + " is not one of the file's " + std::to_string(lightDefinitions.size()) +
                             " light(s); left out");
    return;
  }
  LightDesc light = lightAt(lightDefinitions[static_cast<std::size_t>(lightIndex)], world);
  light.definition = static_cast<int>(lightIndex);
  light.node = nodeIndex;
  if (const std::string problem = lightProblem(light); !problem.empty())
    scene.messages.push_back(where + std::to_string(lightIndex) + ": " + problem + "; left out");
  else
    scene.lights.push_back(std::move(light));
}

Scene flattenScene(const std::filesystem::path& input, const SceneOptions& options) {
  const detail::Asset asset = detail::loadAsset(input, options.assetRoot);
  const Json& doc = asset.json;
  Scene scene;
  scene.messages = asset.warnings;
  scene.images = readImages(asset);
  scene.materials = readMaterials(doc);
  const std::vector<PrimitiveVerdicts> verdicts =
      options.judge ? judgeCorners(asset, input, options, scene.messages) : std::vector<PrimitiveVerdicts>{};

  const std::vector<Json> lightDefinitions = lightDefinitionsOf(doc);

  // Depth first with a stack of its own, so that a chain of a million nodes needs no call stack.
  // loadAsset's validation leaves each node one parent at most and no cycle; a node that the
  // scene lists twice, or lists beside an ancestor, is shown once, so each node costs one visit.
  const std::size_t nodeCount = doc.contains("nodes") ? doc["nodes"].size() : 0;
  const std::string file = input.string();
  const std::vector<char> unusableTransform = unusableTransforms(doc, nodeCount, file, scene.messages);
  std::vector<char> visited(nodeCount, 0);
  std::size_t reachedAgain = 0;
  std::vector<std::optional<std::vector<std::int64_t>>> meshItems(doc.contains("meshes") ? doc["meshes"].size() : 0);
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  std::vector<std::pair<int, glm::mat4>> stack;
  const std::vector<int> roots = rootNodes(doc);
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::mat4(1));
  while (!stack.empty()) {
    const auto [nodeIndex, parent] = stack.back();
    stack.pop_back();
    if (nodeIndex < 0 || nodeIndex >= static_cast<int>(nodeCount)) continue;
    if (visited[nodeIndex]) {
      ++reachedAgain;
      continue;
    }
    visited[nodeIndex] = 1;
    const Json& node = doc["nodes"][nodeIndex];
    glm::mat4 world = parent * localTransform(node, !unusableTransform[nodeIndex]);
    const auto finite = [](float v) { return std::isfinite(v); };
    if (!unusableTransform[nodeIndex] && !std::all_of(glm::value_ptr(world), glm::value_ptr(world) + 16, finite)) {
      // Finite transforms whose product is not (scales of 1e30 under 1e30): the parent's alone.
      scene.messages.push_back(file + ": node " + std::to_string(nodeIndex) +
                               ": world transform not finite (its transforms' product overflows); its own treated as identity");
      world = parent;
    }
    // Pushed in reverse so that nodes are visited in document order (depth first).
    if (node.contains("children")) {
      const Json& children = node["children"];
      for (auto it = children.rbegin(); it != children.rend(); ++it) stack.emplace_back(it->get<int>(), world);
    }
    if (node.contains("extensions") && node["extensions"].contains("KHR_lights_punctual"))
      addNodeLight(node["extensions"]["KHR_lights_punctual"], nodeIndex, world, lightDefinitions, file, scene);
    if (!node.contains("mesh")) continue;
    const int meshIndex = node["mesh"].get<int>();
    if (meshIndex < 0 || meshIndex >= static_cast<int>(meshItems.size())) continue;
    if (!meshItems[meshIndex]) meshItems[meshIndex] = readMeshItems(asset, meshIndex, verdicts, options, scene);
    for (const std::int64_t item : *meshItems[meshIndex]) {
      if (item < 0) continue;
      DrawInstance instance;
      instance.item = static_cast<std::uint32_t>(item);
      instance.node = static_cast<std::uint32_t>(nodeIndex);
      std::copy(glm::value_ptr(world), glm::value_ptr(world) + 16, instance.world.begin());
      growBounds(scene.items[static_cast<std::size_t>(item)], world, lo, hi);
      scene.instances.push_back(instance);
    }
  }
  if (nodeCount > 0 && posable(doc)) {
    scene.nodes = readNodes(doc, unusableTransform, file, scene.messages);
    scene.skins = readSkins(asset, nodeCount, scene.nodes, scene.messages);
    dropSkinsPastTheirJoints(scene, file);
    scene.animations = readAnimations(asset, nodeCount, scene.messages);
  }
  if (reachedAgain > 0)
    scene.messages.push_back(input.string() + ": " + std::to_string(reachedAgain) +
                             " node(s) reached again from the scene's roots (listed twice, or beside an ancestor); each shown once");
  if (lo.x <= hi.x) {
    scene.boundsMin = {lo.x, lo.y, lo.z};
    scene.boundsMax = {hi.x, hi.y, hi.z};
  }
  return scene;
}

}  // namespace

Scene loadScene(const std::filesystem::path& input, const SceneOptions& options) {
  return detail::throwingInputError(input, [&] { return flattenScene(input, options); });
}

}  // namespace tangent::gltf
