// SPDX-License-Identifier: MIT
// tangent/text.hpp and tangent/output.hpp: exact results on hand-made byte strings, the glb
// size limit at its boundary, the atomic writer's failures.
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

#include "support/temp_dir.hpp"
#include "tangent/output.hpp"
#include "tangent/text.hpp"

namespace {

using namespace std::string_literals;

TEST(Text, Utf8SafeKeepsValidUtf8AndEscapesEveryOtherByte) {
  EXPECT_EQ(tangent::text::utf8Safe("plain"), "plain");
  EXPECT_EQ(tangent::text::utf8Safe("caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80"), "caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80");
  EXPECT_EQ(tangent::text::utf8Safe("n\xFF.glb"), "n\\xFF.glb");
  EXPECT_EQ(tangent::text::utf8Safe("gen\xC0"), "gen\\xC0");                   // a lead byte with nothing after it
  EXPECT_EQ(tangent::text::utf8Safe("\xC0\xAF"), "\\xC0\\xAF");                // overlong '/'
  EXPECT_EQ(tangent::text::utf8Safe("\xED\xA0\x80"), "\\xED\\xA0\\x80");       // a UTF-16 surrogate
  EXPECT_EQ(tangent::text::utf8Safe("\xF4\x90\x80\x80"), "\\xF4\\x90\\x80\\x80");  // past U+10FFFF
  EXPECT_EQ(tangent::text::utf8Safe("\xE2\x82"), "\\xE2\\x82");                // cut short
  EXPECT_EQ(tangent::text::utf8Safe("a\0b"s), "a\0b"s);                        // NUL is valid UTF-8
}

TEST(Text, TerminalSafeEscapesControlCharactersAndCuts) {
  EXPECT_EQ(tangent::text::terminalSafe("a\x1B[31mb\rc\0d\x7F"s), "a\\x1B[31mb\\x0Dc\\x00d\\x7F");
  // A newline in file-derived text (a file name) would start a line of its own in a log.
  EXPECT_EQ(tangent::text::terminalSafe("tab\tnew\nline"), "tab\tnew\\x0Aline");
  EXPECT_EQ(tangent::text::terminalSafeLines("tab\tnew\nline\r\x1B"), "tab\tnew\nline\\x0D\\x1B");
  EXPECT_EQ(tangent::text::terminalSafe("c1 \xC2\x9B" "2J"), "c1 \\u009B2J");  // U+009B is CSI on some terminals
  EXPECT_EQ(tangent::text::terminalSafe("\xFF"), "\\xFF");
  EXPECT_EQ(tangent::text::terminalSafe("abcdefgh", 3), "abc... (8 bytes)");
  // Cut on a character boundary, never inside a UTF-8 sequence.
  EXPECT_EQ(tangent::text::terminalSafe("ab\xE2\x82\xAC" "cd", 3), "ab\xE2\x82\xAC... (7 bytes)");
  EXPECT_EQ(tangent::text::quoted(std::string(100000, 'x')).size(), tangent::text::kMaxMessageText + std::string("... (100000 bytes)").size());
}

TEST(Text, DumpJsonRepairsStringsAndKeysThatAreNotUtf8) {
  nlohmann::ordered_json json = {{"name", "bad\xC0"}, {"list", {"ok", "\xFF"}}};
  json["k\xFE"] = 1;
  EXPECT_THROW((void)json.dump(), nlohmann::json::type_error);
  const std::string text = tangent::text::dumpJson(json);
  EXPECT_EQ(text, R"({"name":"bad\\xC0","list":["ok","\\xFF"],"k\\xFE":1})");
  EXPECT_EQ(nlohmann::ordered_json::parse(text)["name"], "bad\\xC0");
  const nlohmann::ordered_json good = {{"a", "caf\xC3\xA9"}};
  EXPECT_EQ(tangent::text::dumpJson(good, 2), good.dump(2));
}

TEST(Output, GlbSizeLimitAtTheFormatsBoundary) {
  namespace out = tangent::output;
  // 12 (header) + 8 + json + 8 + bin: the largest that fits ends exactly at 2^32 - 1... which is
  // not a multiple of 4, so the largest a writer can make is 2^32 - 4.
  const std::uint64_t json = 1000, frame = 12 + 8 + 8;
  const std::uint64_t binFits = 0xFFFFFFFCull - frame - json;
  EXPECT_NO_THROW(out::checkGlbFits("x.glb", json, binFits));
  EXPECT_THROW(out::checkGlbFits("x.glb", json, binFits + 1), std::runtime_error);  // padded to 2^32
  EXPECT_NO_THROW(out::checkGlbFits("x.glb", json, 0));
  try {
    out::checkGlbFits("big.glb", json, std::uint64_t(5) << 30);
    FAIL() << "a 5 GiB .glb was accepted";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("big.glb"), std::string::npos) << message;
    EXPECT_NE(message.find(std::to_string(frame + json + (std::uint64_t(5) << 30))), std::string::npos) << message;
    EXPECT_NE(message.find(".gltf"), std::string::npos) << message;
  }
}

TEST(Output, AtomicWriteReplacesWholeAndFailsWithoutATrace) {
  tangent::testing::TempDir dir;
  const auto path = dir.path() / "file.txt";
  tangent::output::writeFileAtomic(path, "first");
  tangent::output::writeFileAtomic(path, "second");
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(text, "second");
  // A folder that does not exist: the message names the file and why.
  try {
    tangent::output::writeFileAtomic(dir.path() / "missing" / "x.txt", "x");
    FAIL() << "wrote into a folder that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("x.txt"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No such file"), std::string::npos) << e.what();
  }
  // The destination is a folder: the rename fails and the temporary is gone.
  std::filesystem::create_directory(dir.path() / "taken");
  std::ofstream(dir.path() / "taken" / "inside") << "x";
  EXPECT_THROW(tangent::output::writeFileAtomic(dir.path() / "taken", "x"), std::runtime_error);
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

std::string contentOf(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

std::vector<std::string> namesIn(const std::filesystem::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::span<const std::uint8_t> bytesOf(const std::string& text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

// A folder that appears where a staged file goes (after the checks up front; root or not, a
// rename cannot replace it): the files renamed before it are put back, the earlier one's bytes
// and the new one's absence alike, and the last file (an output) is never touched.
TEST(Output, CommitAllPutsEveryFileBackWhereOneRenameFails) {
  namespace out = tangent::output;
  tangent::testing::TempDir dir;
  std::ofstream(dir / "earlier.png") << "earlier bytes";
  std::ofstream(dir / "out.glb") << "earlier output";
  const std::string copy = "new copy", fresh = "fresh copy", blocked = "blocked copy", output = "new output";
  {
    out::StagedFile a(dir / "earlier.png", {bytesOf(copy)});
    out::StagedFile b(dir / "fresh.png", {bytesOf(fresh)});
    out::StagedFile c(dir / "blocked.png", {bytesOf(blocked)});
    out::StagedFile d(dir / "out.glb", {bytesOf(output)});
    std::filesystem::create_directory(dir / "blocked.png");
    std::ofstream(dir / "blocked.png" / "inside") << "x";
    out::StagedFile* files[] = {&a, &b, &c, &d};
    try {
      out::commitAll(files);
      FAIL() << "renamed a file over a folder";
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find((dir / "blocked.png").string() + ": cannot rename"), std::string::npos) << message;
      EXPECT_EQ(message.find("could not be put back"), std::string::npos) << message;
    }
  }
  EXPECT_EQ(contentOf(dir / "earlier.png"), "earlier bytes");
  EXPECT_EQ(contentOf(dir / "out.glb"), "earlier output");
  EXPECT_EQ(namesIn(dir.path()), (std::vector<std::string>{"blocked.png", "earlier.png", "out.glb"}));
  EXPECT_EQ(namesIn(dir / "blocked.png"), std::vector<std::string>{"inside"});

  // Without the folder in the way, every file is replaced and nothing else is left.
  std::filesystem::remove_all(dir / "blocked.png");
  {
    out::StagedFile a(dir / "earlier.png", {bytesOf(copy)});
    out::StagedFile b(dir / "fresh.png", {bytesOf(fresh)});
    out::StagedFile d(dir / "out.glb", {bytesOf(output)});
    out::StagedFile* files[] = {&a, &b, &d};
    out::commitAll(files);
  }
  EXPECT_EQ(contentOf(dir / "earlier.png"), copy);
  EXPECT_EQ(contentOf(dir / "fresh.png"), fresh);
  EXPECT_EQ(contentOf(dir / "out.glb"), output);
  EXPECT_EQ(namesIn(dir.path()), (std::vector<std::string>{"earlier.png", "fresh.png", "out.glb"}));
}

// A signal while a SignalDeferral lives (here raised inside two nested ones) waits for the
// last to end, then ends the process as the handler does, removing the guarded temporaries.
TEST(Output, ASignalWaitsForTheLastDeferralThenRemovesTheTemporaries) {
  namespace out = tangent::output;
  tangent::testing::TempDir dir;
  std::ofstream(dir / "kept.png") << "earlier bytes";
  const std::string fresh = "new bytes";
  auto child = [&] {
    out::removeTemporariesOnSignal();
    out::StagedFile staged(dir / "kept.png", {bytesOf(fresh)});  // a temporary beside it, never committed
    {
      const out::SignalDeferral outer;
      {
        const out::SignalDeferral inner;
        ::raise(SIGTERM);
      }
      std::ofstream(dir / "after-raise") << "still running";
    }
    std::ofstream(dir / "after-deferrals") << "not reached";
    std::exit(0);
  };
  EXPECT_EXIT(child(), ::testing::KilledBySignal(SIGTERM), "");
  EXPECT_TRUE(std::filesystem::exists(dir / "after-raise"));
  EXPECT_EQ(contentOf(dir / "kept.png"), "earlier bytes");
  EXPECT_EQ(namesIn(dir.path()), (std::vector<std::string>{"after-raise", "kept.png"}));
}

// A signal between two of commitAll's renames ends the process only once every file is in
// place and the earlier bytes it kept under temporary names are dropped: nothing
// half-replaced, no temporary left.
TEST(Output, CommitAllFinishesBeforeASignalBetweenItsRenamesEndsTheProcess) {
  namespace out = tangent::output;
  tangent::testing::TempDir dir;
  std::ofstream(dir / "earlier.png") << "earlier bytes";
  std::ofstream(dir / "out.glb") << "earlier output";
  const std::string copy = "new copy", output = "new output";
  auto child = [&] {
    out::removeTemporariesOnSignal();
    out::StagedFile a(dir / "earlier.png", {bytesOf(copy)});
    out::StagedFile d(dir / "out.glb", {bytesOf(output)});
    out::StagedFile* files[] = {&a, &d};
    out::commitAllAfterRename = [](std::size_t renamed) {
      if (renamed == 1) ::raise(SIGINT);
    };
    out::commitAll(files);
    std::exit(0);
  };
  EXPECT_EXIT(child(), ::testing::KilledBySignal(SIGINT), "");
  EXPECT_EQ(contentOf(dir / "earlier.png"), copy);
  EXPECT_EQ(contentOf(dir / "out.glb"), output);
  EXPECT_EQ(namesIn(dir.path()), (std::vector<std::string>{"earlier.png", "out.glb"}));
}

// The line a JSON pointer's value starts on, for reports that point code-review tools at a
// .gltf's lines: members found past skipped values of every kind, arrays by index, and text
// that is not JSON (or does not hold the element) answered with nullopt, deep or not.
TEST(JsonPointerLine, FindsTheLineOfAnElement) {
  const std::string json =
      "{\n  \"asset\": {\"version\": \"2.0\", \"extras\": [1, {\"a\": \"}]\\\"\"}, null, -1.5e3]},\n"
      "  \"meshes\": [\n    {\"primitives\": []},\n    {\"name\": \"b\",\n     \"primitives\": [\n"
      "       {\"attributes\": {}},\n\n       {\"attributes\": {}}]}]}\n";
  EXPECT_EQ(tangent::text::jsonPointerLine(json, ""), 1u);
  EXPECT_EQ(tangent::text::jsonPointerLine(json, "/meshes"), 3u);
  EXPECT_EQ(tangent::text::jsonPointerLine(json, "/meshes/1/primitives/0"), 7u);
  EXPECT_EQ(tangent::text::jsonPointerLine(json, "/meshes/1/primitives/1"), 9u);
  EXPECT_EQ(tangent::text::jsonPointerLine(json, "/meshes/1/primitives/2"), std::nullopt);
  EXPECT_EQ(tangent::text::jsonPointerLine(json, "/meshes/0/primitives/0"), std::nullopt);
  EXPECT_EQ(tangent::text::jsonPointerLine(json, "/nodes"), std::nullopt);
  EXPECT_EQ(tangent::text::jsonPointerLine(json, "/meshes/x"), std::nullopt);
  for (const std::string broken : {"", "{", "{\"meshes\": [", "[[[[", "{\"meshes\" [1]}", "\"\\"})
    EXPECT_EQ(tangent::text::jsonPointerLine(broken, "/meshes/0"), std::nullopt) << broken;
  const std::string deep = std::string(200000, '[') + std::string(200000, ']');
  EXPECT_EQ(tangent::text::jsonPointerLine("{\"a\": " + deep + ", \"b\":\n 1}", "/b"), 2u);
}

}  // namespace
