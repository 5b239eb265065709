// SPDX-License-Identifier: MIT
// URIs of buffers and images (glTF 2.0 spec 3.1.1 and RFC 3986) and the containment rule:
// an asset may read data: URIs and relative paths that stay inside its asset root after
// `..` and symbolic links are resolved. Every file an asset names goes through resolveFileUri.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {

// RFC 3986 percent-decoding; a '%' not followed by two hex digits stays as it is.
std::string percentDecode(const std::string& uri);

bool isDataUri(const std::string& uri);
// A URI that names a file relative to the document (not data:, not absolute, no scheme).
bool isRelativeFileUri(const std::string& uri);
// Base64 payload of a data: URI; throws InputError (naming `what`) when it is not base64.
std::vector<std::uint8_t> decodeDataUri(const std::string& uri, const std::string& what);
// The same checks without decoding (images, which are carried through as they are).
void checkDataUri(const std::string& uri, const std::string& what);

// The folder an asset's files must stay inside: `root` when given, else the input's folder;
// made absolute and canonical (symbolic links resolved).
std::filesystem::path assetRootFor(const std::filesystem::path& input, const std::filesystem::path& root);

// Thrown by resolveFileUri when a URI passes the rule but names no file: loading refuses a
// missing buffer, while a missing image is only a warning (images are carried through).
class MissingFileError : public InputError {
 public:
  using InputError::InputError;
};

// The file a relative URI names, resolved against `baseDir` and checked against the rule:
// no scheme, not absolute, inside `root` after resolving `..` and links, an existing regular
// file. Throws InputError "<label>: <what> uri '<uri>' ..." otherwise (MissingFileError when
// only the file is missing).
std::filesystem::path resolveFileUri(const std::string& uri, const std::filesystem::path& baseDir,
                                     const std::filesystem::path& root, const std::string& label, const std::string& what);

// True when `path` (canonical) lies inside `root` (canonical).
bool isInside(const std::filesystem::path& path, const std::filesystem::path& root);

}  // namespace tangent::gltf::detail
