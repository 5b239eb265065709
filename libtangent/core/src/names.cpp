// SPDX-License-Identifier: MIT
#include "tangent/tangent.hpp"

#include "workspace.hpp"

namespace tangent {

std::string_view vectorIsa() {
  switch (detail::activeVectorIsa()) {
    case detail::VectorIsa::avx2: return "avx2";
    case detail::VectorIsa::sse2: return "sse2";
    case detail::VectorIsa::scalar: return "scalar";
  }
  return "scalar";
}

std::string_view toString(Method method) {
  switch (method) {
    case Method::mikktspace: return "mikktspace";
    case Method::lengyel: return "lengyel";
    case Method::flat: return "flat";
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
  for (Method candidate : {Method::mikktspace, Method::lengyel, Method::flat}) {
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

}  // namespace tangent
