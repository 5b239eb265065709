// SPDX-License-Identifier: MIT
// libFuzzer target: the check configuration file and the report writers. The first byte picks
// what the rest is: a --config file (parsed with the asset loader's limits; a refusal is an
// answer, a crash or a hang a finding), or names and messages from a file that every writer
// must carry out as valid UTF-8 JSON (reports, manifests) and every terminal line without a
// control character.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "tangent/batch.hpp"
#include "tangent/check.hpp"
#include "tangent/text.hpp"

namespace {

[[noreturn]] void broken(const char* what, std::string_view text) {
  std::fprintf(stderr, "text contract broken: %s (%zu bytes)\n", what, text.size());
  std::abort();
}

void checkConfig(std::string_view bytes) {
  static const std::filesystem::path file = tangent::fuzz::assetFolder() / "config.json";
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  tangent::gltf::CheckOptions options;
  try {
    tangent::gltf::applyCheckConfig(file, options);
  } catch (const std::exception&) {
    // A refusal: the answer for bad input.
  }
}

void checkWriters(std::string_view bytes) {
  // Three pieces of file-derived text: a path, a name, a message.
  const std::size_t a = bytes.size() / 3, b = 2 * bytes.size() / 3;
  const std::string path(bytes.substr(0, a)), name(bytes.substr(a, b - a)), message(bytes.substr(b));

  tangent::gltf::FileCheck file;
  file.file = path;
  file.error = message;
  tangent::gltf::PrimitiveCheck primitive;
  primitive.meshName = name;
  tangent::gltf::CheckFinding finding;
  finding.check = "reference";
  finding.message = message;
  finding.worst.push_back({0, 1.0, false, name});
  primitive.findings.push_back(finding);
  file.primitives.push_back(primitive);
  file.skipped.push_back(name + ": " + message);

  tangent::gltf::BatchEntry entry;
  entry.input = path;
  entry.output = name;
  entry.error = message;
  nlohmann::ordered_json manifest = {{"files", {{tangent::text::utf8Safe(name), {{"error", message}}}}}};
  for (const nlohmann::ordered_json& json : {tangent::gltf::toJson(file), tangent::gltf::toJson(entry), manifest}) {
    const std::string text = tangent::text::dumpJson(json, 2);
    try {
      const auto parsed = nlohmann::ordered_json::parse(text);  // strict: rejects anything that is not UTF-8
      if (parsed.is_discarded()) broken("dumpJson wrote JSON that does not parse", text);
    } catch (const std::exception&) {
      broken("dumpJson wrote JSON that does not parse", text);
    }
  }
  for (const std::string& piece : {path, name, message}) {
    const std::string safe = tangent::text::utf8Safe(piece);
    if (tangent::text::utf8Safe(safe) != safe) broken("utf8Safe is not stable on its own output", piece);
    const std::string shown = tangent::text::terminalSafe(piece, 64);
    for (std::size_t i = 0; i < shown.size(); ++i) {
      const auto c = static_cast<unsigned char>(shown[i]);
      if ((c < 0x20 && c != '\t' && c != '\n') || c == 0x7F) broken("a control character reached the terminal", piece);
      if (c == 0xC2 && i + 1 < shown.size() && static_cast<unsigned char>(shown[i + 1]) < 0xA0)
        broken("a C1 control character reached the terminal", piece);
    }
    if (tangent::text::utf8Safe(shown) != shown) broken("terminalSafe wrote bytes that are not UTF-8", piece);
    if (shown.size() > 64 + 32) broken("terminalSafe did not cut", piece);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  if (data[0] % 2 == 0) checkConfig(rest);
  else checkWriters(rest);
  return 0;
}
