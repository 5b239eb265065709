// SPDX-License-Identifier: MIT
// Text that leaves the program. Names, URIs and paths come from files written by strangers:
// they may hold bytes that are not UTF-8 (Latin-1 exporters, file names in other encodings),
// terminal control sequences (ESC, CR, NUL) or megabytes of data: URI. Every string read from a
// file or a path goes through one of these where it enters a report, a document or a terminal.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace tangent::text {

// Longest file-derived text a message carries before it is cut.
inline constexpr std::size_t kMaxMessageText = 160;

// Valid UTF-8 as it is; every byte that does not belong to a valid UTF-8 sequence (overlong
// forms, surrogates and code points past U+10FFFF included) as the four characters "\xHH".
// The result is valid UTF-8, and different byte strings stay different in practice.
std::string utf8Safe(std::string_view bytes);

// For a terminal or a one-line log: utf8Safe, then control characters (C0 but tab, DEL, C1)
// as "\xHH", so that no escape sequence reaches the terminal and no file-derived text (a file
// name with a newline in it) starts a line of its own that a reader or a CI log takes for
// another message. Longer than maxBytes: cut on a character boundary and ended with
// "... (N bytes)".
std::string terminalSafe(std::string_view text, std::size_t maxBytes = static_cast<std::size_t>(-1));
// terminalSafe with newlines kept: for text whose line breaks are the program's own and that
// is encoded further before it is written (a GitHub annotation's message, newlines as %0A).
std::string terminalSafeLines(std::string_view text, std::size_t maxBytes = static_cast<std::size_t>(-1));

// A piece of file-derived text inside a message: terminalSafe, cut to kMaxMessageText.
std::string quoted(std::string_view text);

// Longest whole message (an error naming file, element and reason) a program prints.
inline constexpr std::size_t kMaxShownMessage = 4096;
// A whole message for the terminal, as the CLI and the viewer print every one: terminalSafe,
// cut to kMaxShownMessage.
inline std::string shown(std::string_view message) { return terminalSafe(message, kMaxShownMessage); }

// A relative file path as a URI reference (RFC 3986 section 4.2): glTF's buffer and image
// URIs, SARIF's artifactLocation.uri. A path segment may carry unreserved characters,
// sub-delimiters, ':' and '@' (section 3.3), '/' separates segments; everything else is
// percent-encoded, and ':' too: in the first segment of a relative reference it would read
// as a scheme (section 4.2), and an encoded one means the same anywhere.
std::string uriPath(std::string_view path);

// A query parameter's value (RFC 3986 section 3.4), as in a link `page.html?url=VALUE`:
// unreserved characters and '/' as they are, every other byte percent-encoded ('&', '=', '#',
// '+' included, which would end or change the value).
std::string uriQueryValue(std::string_view value);

// JSON as every writer writes it (reports, manifests, glTF documents): strings and keys that
// are not valid UTF-8 pass through utf8Safe first, where nlohmann's dump would throw.
std::string dumpJson(const nlohmann::ordered_json& json, int indent = -1);

// The line (from 1) on which the value at JSON pointer `pointer` ("/meshes/0/primitives/1")
// starts in the JSON text `json`, for reports that point code-review tools at a line of a
// .gltf; nullopt where the text does not hold it (or is not JSON). Linear in the text, no
// recursion (any nesting depth).
std::optional<std::size_t> jsonPointerLine(std::string_view json, std::string_view pointer);

}  // namespace tangent::text
