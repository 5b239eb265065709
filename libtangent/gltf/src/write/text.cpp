// SPDX-License-Identifier: MIT
// UTF-8 validity after the Unicode Standard, table 3-7 (well-formed byte sequences).
#include "tangent/text.hpp"

#include <algorithm>

namespace tangent::text {
namespace {

constexpr char kHex[] = "0123456789ABCDEF";

void appendEscaped(std::string& out, unsigned char byte) {
  out += "\\x";
  out += kHex[byte >> 4];
  out += kHex[byte & 15];
}

// Length of the well-formed UTF-8 sequence at text[i], or 0 when the byte there starts none.
std::size_t sequenceLength(std::string_view text, std::size_t i) {
  const auto at = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = at(i);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  unsigned char low = 0x80, high = 0xBF;  // range of the second byte
  if (lead >= 0xC2 && lead <= 0xDF) length = 2;
  else if (lead == 0xE0) length = 3, low = 0xA0;
  else if (lead >= 0xE1 && lead <= 0xEC) length = 3;
  else if (lead == 0xED) length = 3, high = 0x9F;  // no surrogates
  else if (lead >= 0xEE && lead <= 0xEF) length = 3;
  else if (lead == 0xF0) length = 4, low = 0x90;
  else if (lead >= 0xF1 && lead <= 0xF3) length = 4;
  else if (lead == 0xF4) length = 4, high = 0x8F;  // nothing past U+10FFFF
  else return 0;
  if (i + length > text.size()) return 0;
  if (at(i + 1) < low || at(i + 1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k) {
    if (at(i + k) < 0x80 || at(i + k) > 0xBF) return 0;
  }
  return length;
}

bool isValidUtf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t length = sequenceLength(text, i);
    if (length == 0) return false;
    i += length;
  }
  return true;
}

// Repairs every string and key below `json` in place; true when something changed.
bool repairStrings(nlohmann::ordered_json& json) {
  bool changed = false;
  if (json.is_string()) {
    auto& value = json.get_ref<std::string&>();
    if (!isValidUtf8(value)) {
      value = utf8Safe(value);
      changed = true;
    }
  } else if (json.is_array()) {
    for (auto& item : json) changed = repairStrings(item) || changed;
  } else if (json.is_object()) {
    bool badKey = false;
    for (auto& [key, value] : json.items()) {
      badKey = badKey || !isValidUtf8(key);
      changed = repairStrings(value) || changed;
    }
    if (badKey) {
      nlohmann::ordered_json rebuilt = nlohmann::ordered_json::object();
      for (auto& [key, value] : json.items()) rebuilt[utf8Safe(key)] = std::move(value);
      json = std::move(rebuilt);
      changed = true;
    }
  }
  return changed;
}

}  // namespace

std::string utf8Safe(std::string_view bytes) {
  std::string out;
  out.reserve(bytes.size());
  for (std::size_t i = 0; i < bytes.size();) {
    const std::size_t length = sequenceLength(bytes, i);
    if (length == 0) {
      appendEscaped(out, static_cast<unsigned char>(bytes[i]));
      ++i;
    } else {
      out.append(bytes.substr(i, length));
      i += length;
    }
  }
  return out;
}

namespace {
std::string terminalSafeText(std::string_view text, std::size_t maxBytes, bool keepNewlines) {
  std::string out;
  std::size_t i = 0;
  for (; i < text.size(); ) {
    if (out.size() >= maxBytes) break;
    const std::size_t length = sequenceLength(text, i);
    const auto byte = static_cast<unsigned char>(text[i]);
    if (length == 0 || (length == 1 && ((byte < 0x20 && byte != '\t' && !(keepNewlines && byte == '\n')) || byte == 0x7F))) {
      appendEscaped(out, byte);
      ++i;
    } else if (length == 2 && byte == 0xC2 && static_cast<unsigned char>(text[i + 1]) < 0xA0) {
      // C1 controls (U+0080..U+009F): some terminals take U+009B as CSI.
      out += "\\u00";
      out += kHex[static_cast<unsigned char>(text[i + 1]) >> 4];
      out += kHex[static_cast<unsigned char>(text[i + 1]) & 15];
      i += 2;
    } else {
      out.append(text.substr(i, length));
      i += length;
    }
  }
  if (i < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}
}  // namespace

std::string terminalSafe(std::string_view text, std::size_t maxBytes) { return terminalSafeText(text, maxBytes, false); }

std::string terminalSafeLines(std::string_view text, std::size_t maxBytes) { return terminalSafeText(text, maxBytes, true); }

std::string quoted(std::string_view text) { return terminalSafe(text, kMaxMessageText); }

std::string dumpJson(const nlohmann::ordered_json& json, int indent) {
  try {
    return json.dump(indent);
  } catch (const nlohmann::json::type_error&) {
    // 316: a string that is not UTF-8. Rare: only then is the tree copied and repaired.
    nlohmann::ordered_json repaired = json;
    repairStrings(repaired);
    return repaired.dump(indent);
  }
}

namespace {
// Every byte outside ASCII letters, digits and `kept` as %HH (RFC 3986 section 2.1).
std::string percentEncode(std::string_view text, std::string_view kept) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : text) {
    const bool alphanumeric = (c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
    if (alphanumeric || kept.find(static_cast<char>(c)) != std::string_view::npos) {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}
}  // namespace

std::string uriPath(std::string_view path) {
  return percentEncode(path, "-._~/!$&'()*+,;=@");  // unreserved, '/', sub-delims, '@'
}

std::string uriQueryValue(std::string_view value) {
  return percentEncode(value, "-._~/");  // unreserved and '/'
}

namespace {

// A forward reader of JSON text that skips values without building them.
class JsonCursor {
 public:
  explicit JsonCursor(std::string_view text) : text_(text) {}
  std::size_t at() const { return at_; }
  char peek() {
    while (at_ < text_.size() && (text_[at_] == ' ' || text_[at_] == '\n' || text_[at_] == '\r' || text_[at_] == '\t')) ++at_;
    return at_ < text_.size() ? text_[at_] : '\0';
  }
  bool take(char c) {
    if (peek() != c) return false;
    ++at_;
    return true;
  }
  // A string's raw contents (escapes left as they are: pointers here name plain keys).
  std::optional<std::string_view> string() {
    if (!take('"')) return std::nullopt;
    const std::size_t start = at_;
    while (at_ < text_.size() && text_[at_] != '"') at_ += text_[at_] == '\\' ? 2 : 1;
    if (at_ >= text_.size()) return std::nullopt;
    return text_.substr(start, at_++ - start);
  }
  // Skips one value of any depth (brackets counted, strings skipped whole).
  bool skipValue() {
    std::size_t depth = 0;
    do {
      const char c = peek();
      if (c == '"') {
        if (!string()) return false;
      } else if (c == '{' || c == '[') {
        ++depth, ++at_;
      } else if (c == '}' || c == ']') {
        if (depth == 0) return false;
        --depth, ++at_;
      } else if (c == ',' || c == ':') {
        if (depth == 0) return false;
        ++at_;
      } else if (c == '\0') {
        return false;
      } else {
        while (at_ < text_.size() && std::string_view(",}] \n\r\t").find(text_[at_]) == std::string_view::npos) ++at_;
      }
    } while (depth > 0);
    return true;
  }

 private:
  std::string_view text_;
  std::size_t at_ = 0;
};

// Moves `cursor` from the start of an object or array to the start of its member `token`.
bool enter(JsonCursor& cursor, std::string_view token) {
  if (cursor.take('{')) {
    for (bool first = true;; first = false) {
      if (!first && !cursor.take(',')) return false;
      const auto key = cursor.string();
      if (!key || !cursor.take(':')) return false;
      if (*key == token) return true;
      if (!cursor.skipValue()) return false;
    }
  }
  if (!cursor.take('[') || token.empty() || token.find_first_not_of("0123456789") != std::string_view::npos) return false;
  std::size_t index = 0;
  for (const char digit : token) index = index * 10 + static_cast<std::size_t>(digit - '0');
  for (std::size_t k = 0; k < index; ++k)
    if (!cursor.skipValue() || !cursor.take(',')) return false;
  return cursor.peek() != ']' && cursor.peek() != '\0';
}

}  // namespace

std::optional<std::size_t> jsonPointerLine(std::string_view json, std::string_view pointer) {
  JsonCursor cursor(json);
  while (!pointer.empty()) {
    if (pointer.front() != '/') return std::nullopt;
    pointer.remove_prefix(1);
    const std::size_t end = std::min(pointer.find('/'), pointer.size());
    if (!enter(cursor, pointer.substr(0, end))) return std::nullopt;
    pointer.remove_prefix(end);
  }
  cursor.peek();
  const std::size_t at = std::min(cursor.at(), json.size());
  return 1 + static_cast<std::size_t>(std::count(json.begin(), json.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

}  // namespace tangent::text
