// SPDX-License-Identifier: MIT
#include "read/uri.hpp"

#include <algorithm>
#include <cctype>
#include <string_view>

#include "tangent/gltf.hpp"
#include "tangent/text.hpp"

namespace tangent::gltf::detail {
namespace fs = std::filesystem;

namespace {

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// RFC 3986 3.1: scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"
bool hasScheme(const std::string& uri) {
  const std::size_t colon = uri.find(':');
  if (colon == std::string::npos || colon == 0) return false;
  if (!std::isalpha(static_cast<unsigned char>(uri[0]))) return false;
  return std::all_of(uri.begin(), uri.begin() + static_cast<std::ptrdiff_t>(colon), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.';
  });
}

}  // namespace

std::string percentDecode(const std::string& uri) {
  std::string out;
  out.reserve(uri.size());
  for (std::size_t i = 0; i < uri.size(); ++i) {
    const int high = uri[i] == '%' && i + 2 < uri.size() ? hexValue(uri[i + 1]) : -1;
    const int low = high >= 0 ? hexValue(uri[i + 2]) : -1;
    if (low >= 0) {
      out += static_cast<char>(high * 16 + low);
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

bool isDataUri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

bool isRelativeFileUri(const std::string& uri) {
  return !uri.empty() && !isDataUri(uri) && uri.find("://") == std::string::npos && uri.front() != '/';
}

namespace {

// Where a data: URI's base64 payload starts; throws InputError (naming `what`) for any other.
std::size_t base64Payload(const std::string& uri, const std::string& what) {
  const std::size_t comma = uri.find(',');
  if (comma == std::string::npos || uri.rfind(";base64", comma) == std::string::npos)
    throw InputError(what + ": data: URI is not base64 (only ';base64,' payloads are allowed)");
  return comma + 1;
}

// The 6 bits a base64 character stands for (standard and URL-safe alphabets), -1 for others.
int base64Value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+' || c == '-') return 62;
  if (c == '/' || c == '_') return 63;
  return -1;
}

[[noreturn]] void notBase64(const std::string& what, std::size_t offset) {
  throw InputError(what + ": data: URI has a character that is not base64 at offset " + std::to_string(offset));
}

}  // namespace

std::vector<std::uint8_t> decodeDataUri(const std::string& uri, const std::string& what) {
  const std::size_t start = base64Payload(uri, what);
  std::vector<std::uint8_t> out;
  out.reserve((uri.size() - start) / 4 * 3);
  unsigned buffer = 0;
  int bits = 0;
  for (std::size_t i = start; i < uri.size(); ++i) {
    const char c = uri[i];
    if (c == '=') break;
    const int v = base64Value(c);
    if (v < 0) notBase64(what, i);
    buffer = (buffer << 6) | static_cast<unsigned>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>((buffer >> bits) & 0xFF));
    }
  }
  return out;
}

void checkDataUri(const std::string& uri, const std::string& what) {
  for (std::size_t i = base64Payload(uri, what); i < uri.size() && uri[i] != '='; ++i) {
    if (base64Value(uri[i]) < 0) notBase64(what, i);
  }
}

fs::path assetRootFor(const fs::path& input, const fs::path& root) {
  std::error_code ec;
  const fs::path chosen = root.empty() ? fs::absolute(input, ec).parent_path() : fs::absolute(root, ec);
  fs::path canonical = fs::weakly_canonical(chosen, ec);
  if (ec) canonical = chosen.lexically_normal();
  return canonical;
}

bool isInside(const fs::path& path, const fs::path& root) {
  auto p = path.begin();
  for (auto r = root.begin(); r != root.end(); ++r, ++p) {
    if (r->empty() && std::next(r) == root.end()) break;  // a trailing separator
    if (p == path.end() || *p != *r) return false;
  }
  return true;
}

fs::path resolveFileUri(const std::string& uri, const fs::path& baseDir, const fs::path& root, const std::string& label,
                        const std::string& what) {
  const std::string prefix = label + ": " + what + " uri '" + text::quoted(uri) + "' ";  // a hostile name can be megabytes long
  if (uri.empty()) throw InputError(prefix + "is empty");
  if (hasScheme(uri)) throw InputError(prefix + "has a scheme; only data: URIs and relative paths are allowed");
  const std::string decoded = percentDecode(uri);
  if (decoded.find('\0') != std::string::npos) throw InputError(prefix + "contains a NUL byte");
  const fs::path relative(decoded);
  if (relative.is_absolute() || decoded.front() == '/' || decoded.front() == '\\')
    throw InputError(prefix + "is an absolute path; only paths relative to the asset are allowed");
  std::error_code ec;
  const fs::path joined = (fs::absolute(baseDir, ec) / relative).lexically_normal();
  const fs::path resolved = fs::weakly_canonical(joined, ec);
  if (ec) throw InputError(prefix + "cannot be resolved: " + ec.message());
  if (!isInside(resolved, root))
    throw InputError(prefix + "leaves the asset root " + root.string() +
                     " (resolved to " + resolved.string() + "); pass --asset-root to allow a wider folder");
  const fs::file_status status = fs::status(resolved, ec);
  if (ec || !fs::exists(status)) throw MissingFileError(prefix + "names a file that does not exist (" + resolved.string() + ")");
  if (fs::is_directory(status)) throw InputError(prefix + "names a directory, not a file (" + resolved.string() + ")");
  if (!fs::is_regular_file(status)) throw InputError(prefix + "names a device, pipe or socket, not a file (" + resolved.string() + ")");
  return resolved;
}

}  // namespace tangent::gltf::detail
