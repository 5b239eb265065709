// SPDX-License-Identifier: MIT
#include <filesystem>
#include <iostream>
#include <utility>

#include "commands.hpp"
#include "tangent/gltf.hpp"
#include "tangent/text.hpp"

namespace tangent::cli {

namespace {

// One file's description (describeFile) as text: the file, each mesh, each primitive with its
// mode, material, compression, whether it needs tangents and why, its attributes, morph
// targets and the consumers of its tangent frame.
void printDescription(const nlohmann::ordered_json& info) {
  std::cout << shown(info["file"].get<std::string>()) << " (" << info["container"].get<std::string>() << ")\n";
  for (const auto& mesh : info["meshes"]) {
    std::cout << "  mesh " << mesh["index"].get<int>();
    if (mesh.contains("name")) std::cout << " '" << text::quoted(mesh["name"].get<std::string>()) << "'";
    std::cout << "\n";
    for (const auto& primitive : mesh["primitives"]) {
      std::cout << "    primitive " << primitive["index"].get<int>() << ": mode " << primitive["mode"].get<int>();
      if (primitive.contains("material")) std::cout << ", material " << primitive["material"].dump();
      for (const auto& name : primitive["compression"]) std::cout << ", " << name.get<std::string>();
      std::cout << (primitive["needsTangents"].get<bool>() ? ", needs tangents" : ", no tangents needed")
                << (primitive["hasTangents"].get<bool>() ? ", has TANGENT" : "") << " - "
                << primitive["why"].get<std::string>() << "\n";
      for (const auto& [name, description] : primitive["attributes"].items())
        std::cout << "      " << name << ": " << description.get<std::string>() << "\n";
      if (primitive.contains("morphTargets"))
        std::cout << "      morph targets: " << primitive["morphTargets"].dump() << "\n";
      if (!primitive["frameConsumers"].empty()) {
        std::cout << "      tangent frame read by:";
        for (const auto& use : primitive["frameConsumers"])
          std::cout << " " << use["consumer"].get<std::string>() << " (TEXCOORD_" << use["texCoord"].get<int>() << ")";
        std::cout << "\n";
      }
      if (primitive.contains("frameWarning"))
        std::cout << "      warning: " << shown(primitive["frameWarning"].get<std::string>()) << "\n";
    }
  }
}

}  // namespace

int infoCommand(const std::vector<std::string>& args) {
  std::vector<std::string> inputs;
  std::filesystem::path assetRoot;
  bool json = false, operandsOnly = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (operandsOnly || arg == "--") {  // "--" ends the options
      if (std::exchange(operandsOnly, true)) inputs.push_back(arg);
      continue;
    }
    if (arg == "--json") json = true;
    else if (arg == "--asset-root") {
      if (i + 1 >= args.size() || !std::filesystem::is_directory(args[i + 1])) {
        std::cerr << "tangent info: --asset-root needs a directory (see tangent info --help)\n";
        return kExitUsage;
      }
      assetRoot = args[++i];
    } else if (arg == "-h" || arg == "--help") {
      std::cout << "usage: tangent info IN... [options]\n"
                   "\n"
                   "Lists meshes, primitives and attributes, and which primitives need tangents and why.\n"
                   "Fails (exit 1) on any file bake would refuse.\n"
                   "\n"
                   "options:\n"
                   "  --json             the description as JSON, one document per input\n"
                   "  --asset-root DIR   folder buffer and image URIs may not leave (default: the input's folder)\n"
                   "  -h, --help         this text\n";
      return kExitOk;
    } else if (!arg.empty() && arg[0] == '-') {
      std::cerr << "tangent info: unknown option '" << shown(arg) << "' (see tangent info --help)\n";
      return kExitUsage;
    } else inputs.push_back(arg);
  }
  if (inputs.empty()) {
    std::cerr << "tangent info: no input files (see tangent info --help)\n";
    return kExitUsage;
  }
  int failed = 0;
  for (const auto& input : inputs) {
    try {
      const auto info = gltf::describeFile(input, assetRoot);
      if (json) {
        std::cout << text::dumpJson(info, 2) << "\n";
        continue;
      }
      printDescription(info);
      for (const auto& w : info["warnings"]) std::cerr << "warning: " << shown(w.get<std::string>()) << "\n";
    } catch (const std::exception& e) {
      ++failed;
      std::cerr << "error: " << shown(e.what()) << "\n";
    }
  }
  return failed ? kExitInputFailed : kExitOk;
}

}  // namespace tangent::cli
