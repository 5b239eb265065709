// SPDX-License-Identifier: MIT
// One error contract for the public entry points of the glTF layer: a malformed file makes
// each of them throw InputError, and nothing else, with the file and the element at fault in
// its message. One test per entry point, and the translation of what code below them throws.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>

#include "entry_point.hpp"
#include "support/temp_dir.hpp"
#include "tangent/check.hpp"
#include "tangent/gltf.hpp"
#include "tangent/input_file.hpp"
#include "tangent/scene.hpp"

namespace {

namespace fs = std::filesystem;
using tangent::gltf::InputError;
using tangent::testing::TempDir;

// A primitive whose POSITION names an accessor the file does not have.
fs::path writeMalformedGltf(const TempDir& dir) {
  const fs::path file = dir / "malformed.gltf";
  std::ofstream(file) << R"({"asset": {"version": "2.0"},
    "meshes": [{"primitives": [{"attributes": {"POSITION": 7}}]}]})";
  return file;
}
constexpr const char* kMalformedElement = "/meshes/0/primitives/0/attributes/POSITION";

// Runs `call`; expects InputError (only) whose message names `file` and `element`.
void expectInputError(const std::function<void()>& call, const fs::path& file, const std::string& element) {
  try {
    call();
    ADD_FAILURE() << "no exception for " << file;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find(element), std::string::npos) << message;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not InputError: " << e.what();
  }
}

TEST(ErrorContract, BakeFileThrowsInputErrorNamingFileAndElement) {
  TempDir dir;
  const fs::path input = writeMalformedGltf(dir);
  expectInputError([&] { tangent::gltf::bakeFile(input, dir / "out.glb", {}); }, input, kMalformedElement);
  EXPECT_FALSE(fs::exists(dir / "out.glb"));
}

TEST(ErrorContract, CheckFileThrowsInputErrorNamingFileAndElement) {
  TempDir dir;
  const fs::path input = writeMalformedGltf(dir);
  expectInputError([&] { tangent::gltf::checkFile(input, {}); }, input, kMalformedElement);
}

TEST(ErrorContract, DescribeFileThrowsInputErrorNamingFileAndElement) {
  TempDir dir;
  const fs::path input = writeMalformedGltf(dir);
  expectInputError([&] { tangent::gltf::describeFile(input); }, input, kMalformedElement);
}

TEST(ErrorContract, LoadSceneThrowsInputErrorNamingFileAndElement) {
  TempDir dir;
  const fs::path input = writeMalformedGltf(dir);
  expectInputError([&] { tangent::gltf::loadScene(input); }, input, kMalformedElement);
}

TEST(ErrorContract, MeshFileThrowsInputErrorNamingFileAndElement) {
  TempDir dir;
  // The face names vertex 9 of three.
  const fs::path input = dir / "malformed.obj";
  std::ofstream(input) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 9/3\n";
  for (const auto& call : std::initializer_list<std::function<void()>>{
           [&] { tangent::gltf::bakeFile(input, dir / "out.glb", {}); },
           [&] { tangent::gltf::checkFile(input, {}); },
           [&] { tangent::gltf::describeFile(input); },
           [&] { tangent::gltf::loadScene(input); }})
    expectInputError(call, input, "line 7");
}

// What code below an entry point throws besides InputError comes out as InputError naming the
// input: a JSON exception on a shape validation did not foresee, a failed number conversion.
TEST(ErrorContract, ForeignExceptionsBecomeInputErrorAtTheEntryPoint) {
  const fs::path input = "some/asset.gltf";
  expectInputError(
      [&] {
        tangent::gltf::detail::throwingInputError(input, [] { return nlohmann::json(1).get<std::string>(); });
      },
      input, "unexpected glTF structure");
  expectInputError(
      [&] { tangent::gltf::detail::throwingInputError(input, [] { return std::stoi("%zz"); }); }, input, "malformed input");
  // InputError passes through as it is.
  try {
    tangent::gltf::detail::throwingInputError(input, []() -> int { throw InputError("a.gltf", "/nodes/3", "is wrong"); });
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "a.gltf: /nodes/3: is wrong");
  }
}

// The one input rule (tangent/input_file.hpp): a regular file passes with its size; a folder,
// a FIFO (which would block a reader) and a character device (/dev/zero never ends) are refused
// by name before anything opens them, and an entry point given one says the same.
TEST(ErrorContract, OnlyRegularFilesOfBoundedSizeAreRead) {
  TempDir dir;
  std::ofstream(dir / "three.bin") << "abc";
  EXPECT_EQ(tangent::gltf::requireInputFile(dir / "three.bin", "a glTF file"), 3u);
  ASSERT_EQ(::mkfifo((dir / "fifo.gltf").c_str(), 0600), 0);
  const std::pair<fs::path, std::string> refused[] = {
      {dir / "missing.gltf", ": no such file"},
      {dir.path(), ": is a directory, not a glTF file"},
      {dir / "fifo.gltf", ": is not a regular file"},
      {"/dev/zero", ": is not a regular file"},
  };
  for (const auto& [file, why] : refused) {
    try {
      tangent::gltf::requireInputFile(file, "a glTF file");
      ADD_FAILURE() << file << " passed";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(file.string() + why, 0), 0u) << e.what();
    }
  }
  expectInputError([&] { tangent::gltf::loadScene(dir / "fifo.gltf"); }, dir / "fifo.gltf", "is not a regular file");
}

}  // namespace
