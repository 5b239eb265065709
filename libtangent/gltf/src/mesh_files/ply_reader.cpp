// SPDX-License-Identifier: MIT
// PLY is read here, not by OpenMesh: its header parser looped forever on some malformed
// headers, and its body reader trusts every count (a face list declaring 2 billion corners
// was allocated before any corner was read). The header is checked line by line, every
// element count against the bytes that follow it, and the body element by element with every
// list count bounded by the rest of the file. ASCII and binary, either byte order.
// Read: vertex x y z, nx ny nz, a UV pair (u v, s t, texture_u texture_v or texture_s
// texture_t), face vertex_indices (or vertex_index) and a per-corner texcoord list (u v per
// corner, as MeshLab writes). Every other element and property is read past.
// Format: Greg Turk, "The PLY Polygon File Format" (1994).
#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mesh_files/mesh_import.hpp"
#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {
namespace {

enum class PlyType { none, i8, u8, i16, u16, i32, u32, f32, f64 };

PlyType plyType(const std::string& name) {
  static const std::pair<const char*, PlyType> types[] = {
      {"char", PlyType::i8},     {"int8", PlyType::i8},    {"uchar", PlyType::u8},  {"uint8", PlyType::u8},
      {"short", PlyType::i16},   {"int16", PlyType::i16},  {"ushort", PlyType::u16}, {"uint16", PlyType::u16},
      {"int", PlyType::i32},     {"int32", PlyType::i32},  {"uint", PlyType::u32},  {"uint32", PlyType::u32},
      {"float", PlyType::f32},   {"float32", PlyType::f32}, {"double", PlyType::f64}, {"float64", PlyType::f64}};
  for (const auto& [n, type] : types) {
    if (name == n) return type;
  }
  return PlyType::none;
}

std::size_t plyBytes(PlyType type) {
  switch (type) {
    case PlyType::i8: case PlyType::u8: return 1;
    case PlyType::i16: case PlyType::u16: return 2;
    case PlyType::i32: case PlyType::u32: case PlyType::f32: return 4;
    case PlyType::f64: return 8;
    case PlyType::none: break;
  }
  return 0;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::none;       // the value's, or a list's items'
  PlyType countType = PlyType::none;  // a list's count; none for a scalar
};
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};
struct PlyHeader {
  enum class Format { ascii, little, big } format = Format::ascii;
  std::vector<PlyElement> elements;
  std::size_t bodyStart = 0;
};

PlyHeader readPlyHeader(const std::string& text, const std::string& label) {
  PlyHeader header;
  std::string line;
  std::size_t lineNumber = 0, at = 0;
  auto next = [&]() -> bool {
    if (at >= text.size()) return false;
    const std::size_t end = std::min(text.find('\n', at), text.size());
    line.assign(text, at, end - at);
    at = end + 1;
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  };
  auto fail = [&](const std::string& what) -> void {
    throw InputError(label + ": PLY header line " + std::to_string(lineNumber) + ": " + what);
  };
  if (!next() || line != "ply") fail("the file must start with a line 'ply'");
  if (!next()) fail("missing format line");
  const std::vector<std::string> format = words(line);
  if (format.size() != 3 || format[0] != "format" || format[2] != "1.0" ||
      (format[1] != "ascii" && format[1] != "binary_little_endian" && format[1] != "binary_big_endian"))
    fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
  header.format = format[1] == "ascii" ? PlyHeader::Format::ascii
                  : format[1] == "binary_little_endian" ? PlyHeader::Format::little : PlyHeader::Format::big;
  const bool ascii = header.format == PlyHeader::Format::ascii;
  for (;;) {
    if (!next()) fail("the header has no end_header line");
    if (at > (1u << 20)) fail("the header is longer than 1 MiB");
    const std::vector<std::string> w = words(line);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") break;
    if (w[0] == "element") {
      if (w.size() != 3 || !isCount(w[2])) fail("expected 'element NAME COUNT'");
      header.elements.push_back({w[1], std::stoull(w[2]), {}});
    } else if (w[0] == "property") {
      if (header.elements.empty()) fail("a property before any element");
      if (w.size() == 3 && plyType(w[1]) != PlyType::none) {
        header.elements.back().properties.push_back({w[2], plyType(w[1]), PlyType::none});
      } else if (w.size() == 5 && w[1] == "list" && plyType(w[2]) != PlyType::none && plyType(w[3]) != PlyType::none) {
        if (plyType(w[2]) == PlyType::f32 || plyType(w[2]) == PlyType::f64) fail("a list's count must be an integer type");
        header.elements.back().properties.push_back({w[4], plyType(w[3]), plyType(w[2])});
      } else {
        fail("expected 'property TYPE NAME' or 'property list TYPE TYPE NAME'");
      }
    } else {
      // Free text in a header (an old Blender wrote one line of it) is not PLY.
      fail("unknown keyword '" + w[0].substr(0, 40) + "' (a PLY header line is comment, obj_info, element, property or end_header)");
    }
  }
  header.bodyStart = std::min(at, text.size());
  const std::uint64_t body = text.size() - header.bodyStart;
  for (const PlyElement& e : header.elements) {
    std::uint64_t minBytes = 0;  // an ASCII value takes at least 2 bytes ("0 ")
    for (const PlyProperty& p : e.properties) minBytes += ascii ? 2 : plyBytes(p.countType != PlyType::none ? p.countType : p.type);
    if (e.count > 0 && e.count * std::max<std::uint64_t>(minBytes, 1) > body + 1)
      throw InputError(label + ": PLY header declares " + std::to_string(e.count) + " " + e.name +
                       " elements, more than the " + std::to_string(body) + " bytes after the header can hold");
  }
  return header;
}

}  // namespace

namespace {

// The body of a PLY file after its header, read value by value (ASCII words or binary of the
// header's byte order), with the place of each value kept for messages.
class PlyBodyReader {
 public:
  PlyBodyReader(const std::string& text, const PlyHeader& header, const std::string& label)
      : text_(text),
        label_(label),
        ascii_(header.format == PlyHeader::Format::ascii),
        swap_((header.format == PlyHeader::Format::big) != (std::endian::native == std::endian::big)),
        at_(header.bodyStart) {}

  // Where the next values are: "vertex 3 property x", 1-based, in messages.
  void at(const PlyElement& element, std::uint64_t item) {
    element_ = &element;
    item_ = item;
  }
  void at(const PlyProperty& property) { property_ = &property; }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(label_ + ": PLY " + element_->name + " " + std::to_string(item_ + 1) + " (1-based) property " +
                     property_->name + ": " + what);
  }

  // One value of the given type, as a double (every PLY type fits one exactly).
  double value(PlyType type) {
    if (ascii_) return asciiValue(type);
    const std::size_t bytes = plyBytes(type);
    if (text_.size() - at_ < bytes) fail("the file ends here");
    unsigned char b[8];
    std::memcpy(b, text_.data() + at_, bytes);
    at_ += bytes;
    if (swap_) std::reverse(b, b + bytes);
    switch (type) {
      case PlyType::i8: return static_cast<std::int8_t>(b[0]);
      case PlyType::u8: return b[0];
      case PlyType::i16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::u16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::i32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::u32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::f32: { float v; std::memcpy(&v, b, 4); return v; }
      case PlyType::f64: { double v; std::memcpy(&v, b, 8); return v; }
      case PlyType::none: break;
    }
    return 0.0;
  }

  // The item count of the current list property, bounded by what the rest of the file can hold.
  std::size_t listCount() {
    const double n = value(property_->countType);
    // An item takes at least its size in binary, two bytes in ASCII.
    const double room = static_cast<double>(text_.size() - at_) / (ascii_ ? 2.0 : static_cast<double>(plyBytes(property_->type))) + 1.0;
    if (n < 0) fail("a list count of " + std::to_string(static_cast<long long>(n)) + " (negative)");
    if (n > room) fail("a list of " + std::to_string(static_cast<long long>(n)) + " items, more than the rest of the file holds");
    return static_cast<std::size_t>(n);
  }

 private:
  double asciiValue(PlyType type) {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
    std::size_t end = at_;
    while (end < text_.size() && !std::isspace(static_cast<unsigned char>(text_[end]))) ++end;
    if (end == at_) fail("the file ends here");
    const std::string word = text_.substr(at_, end - at_);
    at_ = end;
    char* stop = nullptr;
    const double x = std::strtod(word.c_str(), &stop);
    if (stop != word.c_str() + word.size()) fail("'" + word.substr(0, 20) + "' is not a number");
    if (type != PlyType::f32 && type != PlyType::f64 && !(x == std::floor(x) && std::fabs(x) < 4.3e9))
      fail("'" + word.substr(0, 20) + "' is not an integer");
    return x;
  }

  const std::string& text_;
  const std::string& label_;
  const bool ascii_, swap_;
  std::size_t at_;
  const PlyElement* element_ = nullptr;
  std::uint64_t item_ = 0;
  const PlyProperty* property_ = nullptr;
};

// Which property of an element fills what, by index; -1 where absent.
struct PlyRoles {
  bool isVertex = false, isFace = false;
  int x = -1, y = -1, z = -1, nx = -1, ny = -1, nz = -1, u = -1, v = -1, indexList = -1, uvList = -1;
  bool normals() const { return nx >= 0 && ny >= 0 && nz >= 0; }
};

PlyRoles plyRoles(const PlyElement& e, const std::string& label) {
  auto find = [&](const char* name) {
    for (std::size_t i = 0; i < e.properties.size(); ++i) {
      if (e.properties[i].name == name && e.properties[i].countType == PlyType::none) return static_cast<int>(i);
    }
    return -1;
  };
  auto findList = [&](std::initializer_list<const char*> names) {
    for (const char* name : names) {
      for (std::size_t i = 0; i < e.properties.size(); ++i) {
        if (e.properties[i].name == name && e.properties[i].countType != PlyType::none) return static_cast<int>(i);
      }
    }
    return -1;
  };
  PlyRoles r;
  r.isVertex = e.name == "vertex";
  r.isFace = e.name == "face";
  if (r.isVertex) {
    r.x = find("x"), r.y = find("y"), r.z = find("z"), r.nx = find("nx"), r.ny = find("ny"), r.nz = find("nz");
    if (r.x < 0 || r.y < 0 || r.z < 0) throw InputError(label + ": PLY element vertex has no x, y and z properties");
    for (const auto& [a, b] : {std::pair{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}}) {
      if (r.u < 0 && find(a) >= 0 && find(b) >= 0) r.u = find(a), r.v = find(b);
    }
  }
  if (r.isFace) {
    r.indexList = findList({"vertex_indices", "vertex_index"});
    r.uvList = findList({"texcoord"});
    if (r.indexList < 0 && e.count > 0) throw InputError(label + ": PLY element face has no 'vertex_indices' list property");
  }
  return r;
}

// One item's values: scalars into `values` (by property index), the face's corners and its
// corners' UVs from their lists; other lists read past.
struct PlyItem {
  std::vector<double> values;
  Polygon corners;
  std::vector<float> uvValues;
};

void readPlyItem(PlyBodyReader& reader, const PlyElement& e, const PlyRoles& roles, PlyItem& item) {
  item.corners.clear();
  item.uvValues.clear();
  for (std::size_t i = 0; i < e.properties.size(); ++i) {
    const PlyProperty& property = e.properties[i];
    reader.at(property);
    if (property.countType == PlyType::none) {
      item.values[i] = reader.value(property.type);
      continue;
    }
    const std::size_t n = reader.listCount();
    const int index = static_cast<int>(i);
    if (index == roles.indexList) {
      if (n < 3) reader.fail("a face of " + std::to_string(n) + " corners (a face needs at least 3)");
      for (std::size_t k = 0; k < n; ++k) {
        const double corner = reader.value(property.type);
        // One past the vertices read so far the importer names; a negative or huge one here.
        if (corner < 0 || corner >= 2147483647.0)
          reader.fail("corner " + std::to_string(k + 1) + " is vertex " + std::to_string(static_cast<long long>(corner)) +
                      ", not a vertex index");
        item.corners.push_back(static_cast<VertexIndex>(corner));
      }
    } else if (index == roles.uvList) {
      for (std::size_t k = 0; k < n; ++k) item.uvValues.push_back(static_cast<float>(reader.value(property.type)));
    } else {
      for (std::size_t k = 0; k < n; ++k) reader.value(property.type);
    }
  }
}

// A face item into the importer: its simple polygons, each with its corners' UVs.
void addPlyFace(PlyBodyReader& reader, const PlyElement& e, const PlyRoles& roles, const PlyItem& item, CheckedImporter& importer) {
  if (roles.uvList >= 0) {
    reader.at(e.properties[static_cast<std::size_t>(roles.uvList)]);
    if (item.uvValues.size() != 2 * item.corners.size())
      reader.fail("lists " + std::to_string(item.uvValues.size()) + " values for a face of " + std::to_string(item.corners.size()) +
                  " corners (u v per corner)");
  }
  // The face, or where it visits a vertex twice its simple polygons, each with its corners' UVs.
  addSimplePolygons(importer, item.corners, [&](std::size_t face, std::size_t n, const auto& position) {
    if (roles.uvList < 0) return;
    for (std::size_t j = 0; j < n; ++j)
      importer.setCornerUv(face, j, {item.uvValues[2 * position(j)], item.uvValues[2 * position(j) + 1]});
  });
}

}  // namespace

void readPly(const std::string& text, CheckedImporter& importer, const std::string& label) {
  const PlyHeader header = readPlyHeader(text, label);
  PlyBodyReader reader(text, header, label);
  PlyItem item;
  for (const PlyElement& e : header.elements) {
    const PlyRoles roles = plyRoles(e, label);
    item.values.assign(e.properties.size(), 0.0);
    for (std::uint64_t n = 0; n < e.count; ++n) {
      reader.at(e, n);
      readPlyItem(reader, e, roles, item);
      if (roles.isVertex) {
        const auto f = [&](int i) { return static_cast<float>(item.values[i]); };
        const VertexIndex vertex = importer.addVertex({f(roles.x), f(roles.y), f(roles.z)});
        if (roles.normals()) importer.setNormal(vertex, {f(roles.nx), f(roles.ny), f(roles.nz)});
        if (roles.u >= 0) importer.setUv(vertex, {f(roles.u), f(roles.v)});
      } else if (roles.isFace) {
        addPlyFace(reader, e, roles, item, importer);
      }
    }
  }
}

}  // namespace tangent::gltf::detail
