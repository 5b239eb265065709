// SPDX-License-Identifier: MIT
#include "tangent/tangent.hpp"

#include <string>

#include "workspace.hpp"

namespace tangent {

std::string_view vectorIsa() {
  switch (detail::activeVectorIsa()) {
    case detail::VectorIsa::avx2: return "avx2";
    case detail::VectorIsa::sse2: return "sse2";
    case detail::VectorIsa::simd128: return "simd128";
    case detail::VectorIsa::scalar: return "scalar";
  }
  return "scalar";
}

std::string_view toString(Method method) {
  switch (method) {
    case Method::mikktspace: return "mikktspace";
    case Method::lengyel: return "lengyel";
    case Method::flat: return "flat";
    case Method::meshopt: return "meshopt";
  }
  return "unknown";
}

std::string_view toString(Weighting weighting) {
  switch (weighting) {
    case Weighting::angle: return "angle";
    case Weighting::area: return "area";
    case Weighting::uniform: return "uniform";
  }
  return "unknown";
}

std::optional<Method> parseMethod(std::string_view name) {
  for (Method candidate : {Method::mikktspace, Method::lengyel, Method::flat, Method::meshopt}) {
    if (toString(candidate) == name) return candidate;
  }
  return std::nullopt;
}

std::optional<Weighting> parseWeighting(std::string_view name) {
  for (Weighting candidate : {Weighting::angle, Weighting::area, Weighting::uniform}) {
    if (toString(candidate) == name) return candidate;
  }
  return std::nullopt;
}

std::string_view toString(UvOrigin origin) { return origin == UvOrigin::topLeft ? "top-left" : "bottom-left"; }

std::optional<UvOrigin> parseUvOrigin(std::string_view name) {
  for (UvOrigin candidate : {UvOrigin::topLeft, UvOrigin::bottomLeft}) {
    if (toString(candidate) == name) return candidate;
  }
  return std::nullopt;
}

std::array<ReportCount, 13> reportCounts(const Report& report) {
  return {{{"triangles", report.triangles},
           {"corners", report.corners},
           {"degenerateTriangles", report.degenerateTriangles},
           {"zeroUvAreaTriangles", report.zeroUvAreaTriangles},
           {"nonFiniteTriangles", report.nonFiniteTriangles},
           {"mirroredCorners", report.mirroredCorners},
           {"splitVertices", report.splitVertices},
           {"nonManifoldFaces", report.nonManifoldFaces},
           {"invalidNormals", report.invalidNormals},
           {"inheritedCorners", report.inheritedCorners},
           {"fallbackFromNeighbours", report.fallbackFromNeighbours},
           {"fallbackFixed", report.fallbackFixed},
           {"outputVertices", report.outputVertices}}};
}

std::string reportJson(const Report& report) {
  // Names and enum strings are plain ASCII words: nothing to escape.
  std::string json = "{\"method\":\"" + std::string(toString(report.method)) + "\",\"weighting\":\"" +
                     std::string(report.weighting ? toString(*report.weighting) : std::string_view()) + "\"";
  for (const ReportCount& count : reportCounts(report)) json += ",\"" + std::string(count.name) + "\":" + std::to_string(count.value);
  return json + "}";
}

}  // namespace tangent
