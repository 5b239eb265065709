// SPDX-License-Identifier: MIT
// tangent-view's window driven by real input: X11 events synthesised with xdotool (XTEST, as a
// person's mouse and keyboard arrive) under the Xvfb that the CTest entry runs the viewer tests
// in; the window's pixels read back with xwd, and what the keys and drags changed from the
// viewer's --print-state lines. Needs xdotool and xwd (x11-apps; scripts/install-deps.sh).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/run_command.hpp"
#include "support/skip_or_fail.hpp"
#include "support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using tangent::testing::runCommand;
using tangent::testing::TempDir;

bool haveCommand(const std::string& name) { return runCommand("command -v " + name + " >/dev/null").exitCode == 0; }

// A window's pixels as `xwd -id WINDOW` writes them (X Window Dump, version 7: a big-endian
// header of 25 CARD32s, the window's name, the colour map, then the image in the server's pixel
// format: ZPixmap, 24- or 32-bit TrueColor with channel masks here).
struct WindowImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // top-down rows
  const std::uint8_t* at(int x, int y) const { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
};

std::uint32_t bigEndian32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (int i = 0; i < 4; ++i) value = value << 8 | static_cast<std::uint8_t>(bytes[at + i]);
  return value;
}

// Empty (width 0) when the capture fails or is in a form this does not read.
WindowImage captureWindow(const std::string& window, const fs::path& file) {
  WindowImage image;
  if (runCommand("xwd -silent -id " + window + " -out '" + file.string() + "'").exitCode != 0) return image;
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 100) return image;
  auto field = [&](int index) { return bigEndian32(bytes, 4 * static_cast<std::size_t>(index)); };
  const std::uint32_t headerSize = field(0), version = field(1), format = field(2), width = field(4), height = field(5);
  const std::uint32_t byteOrder = field(7), bitsPerPixel = field(11), bytesPerLine = field(12);
  const std::uint32_t masks[3] = {field(14), field(15), field(16)};
  const std::uint32_t colours = field(19);
  const std::size_t start = headerSize + static_cast<std::size_t>(colours) * 12;
  if (version != 7 || format != 2 || (bitsPerPixel != 32 && bitsPerPixel != 24) || width == 0 || width > 8192 || height > 8192 ||
      bytes.size() < start + static_cast<std::size_t>(bytesPerLine) * height)
    return image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.rgb.resize(static_cast<std::size_t>(width) * height * 3);
  const std::size_t pixelBytes = bitsPerPixel / 8;
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      const std::size_t p = start + static_cast<std::size_t>(y) * bytesPerLine + x * pixelBytes;
      std::uint32_t pixel = 0;
      for (std::size_t i = 0; i < pixelBytes; ++i) {
        const std::uint32_t byte = static_cast<std::uint8_t>(bytes[p + i]);
        pixel |= byteOrder == 0 ? byte << (8 * i) : byte << (8 * (pixelBytes - 1 - i));  // 0: LSBFirst
      }
      for (int c = 0; c < 3; ++c) {
        int shift = 0;
        while (shift < 32 && !((masks[c] >> shift) & 1u)) ++shift;
        image.rgb[(static_cast<std::size_t>(y) * width + x) * 3 + c] = static_cast<std::uint8_t>((pixel & masks[c]) >> shift);
      }
    }
  }
  return image;
}

// The columns that are the split view's divider, which the renderer draws as two columns of grey
// 0.85 (217 of 255) over the window's whole height: every pixel of the column is that grey.
std::set<int> dividerColumns(const WindowImage& image) {
  std::set<int> columns;
  for (int x = 0; x < image.width; ++x) {
    bool grey = image.height > 0;
    for (int y = 0; y < image.height && grey; ++y) {
      const std::uint8_t* p = image.at(x, y);
      grey = std::abs(p[0] - 217) <= 2 && std::abs(p[1] - 217) <= 2 && std::abs(p[2] - 217) <= 2;
    }
    if (grey) columns.insert(x);
  }
  return columns;
}

std::string show(const std::set<int>& columns) {
  std::string text;
  for (int x : columns) text += (text.empty() ? "" : ", ") + std::to_string(x);
  return "{" + text + "}";
}

// The JSON of each "state ..." line the viewer printed.
std::vector<nlohmann::json> stateLines(const std::string& output) {
  std::vector<nlohmann::json> states;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("state ", 0) == 0) states.push_back(nlohmann::json::parse(line.substr(6)));
  return states;
}

// The views in the order the keys 1-9 and 0 choose them, as docs/viewer.md and the panel's list
// give it ("Validation views (keys 1-9 and 0 ...): lit, geometry normal, tangent, ...").
const char* const kViewKeys[] = {"lit", "geometry-normal", "tangent", "bitangent", "shading-normal",
                                 "uv",  "handedness",      "error",   "face-orientation", "handedness-world"};

// The split compare view's divider follows a left drag begun on it, in the window: dragged from
// the middle (x = 500 of 1000) to x = 800, it is drawn at x = 800 (the two grey columns 799 and
// 800) and the state says 0.8; a left drag begun elsewhere (x = 900) orbits the camera by
// OrbitCamera's 0.008 rad a pixel and leaves the divider; a drag begun within 6 pixels of it
// (x = 803) and ended outside the window (x = 1150) leaves it at the right edge (1.0). Then the
// keys, each checked in the state it leaves, as the panel and docs/viewer.md name them: m normal
// mapping, s specular, h shadows, p PCF, f green flip, g glyphs, b bitangent mode, c the split view
// (twice: off, on), 1-9 and 0 the views in order, a the compare-angle view and back, d the
// anisotropy-direction view and back, r reload the
// shaders (a message), Escape close the window.
TEST(ViewerInput, DividerFollowsTheDragAndKeysDoWhatTheyAreDocumentedToDo) {
  if (!haveCommand("xdotool") || !haveCommand("xwd"))
    TANGENT_SKIP_OR_FAIL("xdotool or xwd (x11-apps) is not installed (scripts/install-deps.sh installs them)");
  TempDir dir;
  const fs::path asset = fs::path(TANGENT_SOURCE_DIR) / "data" / "demo" / "sphere.gltf";
  std::string viewerOutput;
  int viewerExit = -1;
  // The viewer's own time limit ends the test if the window never closes.
  std::thread viewer([&] {
    // In the test's folder, where the panel writes its imgui.ini.
    const auto result = runCommand("cd '" + dir.path().string() + "' && timeout 180 " + std::string(TANGENT_VIEW) + " '" + asset.string() +
                                   "' --size 1000x360 --compare file --print-state --msaa 0");
    viewerOutput = result.output;
    viewerExit = result.exitCode;
  });
  struct Join {
    std::thread& thread;
    ~Join() {
      if (thread.joinable()) thread.join();
    }
  } join{viewer};

  const auto found = runCommand("timeout 120 xdotool search --sync --onlyvisible --name '^tangent-view$' | head -1");
  const std::string window = found.output.substr(0, found.output.find('\n'));
  ASSERT_FALSE(window.empty()) << "no tangent-view window appeared: " << found.output;
  auto xdotool = [&](const std::string& arguments) {
    const auto result = runCommand("xdotool " + arguments);
    EXPECT_EQ(result.exitCode, 0) << "xdotool " << arguments << ": " << result.output;
  };
  // A left drag through the given window positions (the panel covers x < 380).
  auto drag = [&](std::initializer_list<std::pair<int, int>> points) {
    bool first = true;
    for (const auto& [x, y] : points) {
      xdotool("mousemove --window " + window + " " + std::to_string(x) + " " + std::to_string(y));
      if (first) xdotool("mousedown 1");
      first = false;
    }
    xdotool("mouseup 1");
  };

  // 1. From the divider in the middle to x = 800, in steps.
  drag({{500, 180}, {600, 180}, {700, 180}, {800, 180}});
  // The window shows it there once the viewer has drawn a frame after the drag.
  std::set<int> columns;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  do {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    const WindowImage image = captureWindow(window, dir / "window.xwd");
    ASSERT_EQ(image.width, 1000) << "xwd could not capture the window";
    columns = dividerColumns(image);
  } while (columns != std::set<int>{799, 800} && std::chrono::steady_clock::now() < deadline);
  EXPECT_EQ(columns, (std::set<int>{799, 800})) << "the divider is drawn at " << show(columns) << ", not where it was dragged";

  // 2. Elsewhere: the camera orbits; 3. from near the divider to past the window's right edge.
  drag({{900, 200}, {950, 220}});
  drag({{803, 180}, {1000, 180}, {1150, 180}});

  // 4. The keys, with the pointer in the window (no window manager: the focus follows the pointer).
  xdotool("mousemove --window " + window + " 900 300");
  xdotool("windowfocus " + window);
  xdotool("key --delay 20 m s h p f g b c c 1 2 3 4 5 6 7 8 9 0 a a d d r Escape");
  viewer.join();

  ASSERT_EQ(viewerExit, 0) << viewerOutput;
  const auto states = stateLines(viewerOutput);
  // Three drags (a line at each release), 25 keys (a line each), the close.
  ASSERT_EQ(states.size(), 3u + 25u + 1u) << viewerOutput;
  const auto& afterDrag = states[0];
  EXPECT_NEAR(afterDrag["splitPosition"].get<double>(), 0.8, 1e-6);
  const auto& afterOrbit = states[1];
  EXPECT_NEAR(afterOrbit["splitPosition"].get<double>(), 0.8, 1e-6) << "a drag begun off the divider moved it";
  EXPECT_NEAR(afterOrbit["camera"]["yaw"].get<double>() - afterDrag["camera"]["yaw"].get<double>(), -50 * 0.008, 1e-4);
  EXPECT_NEAR(afterOrbit["camera"]["pitch"].get<double>() - afterDrag["camera"]["pitch"].get<double>(), 20 * 0.008, 1e-4);
  const auto& afterEdge = states[2];
  EXPECT_NEAR(afterEdge["splitPosition"].get<double>(), 1.0, 1e-6);
  EXPECT_EQ(afterEdge["camera"], afterOrbit["camera"]) << "the divider drag orbited the camera too";

  // The keys, one state each, against the state before.
  std::size_t line = 3;
  auto next = [&]() -> const nlohmann::json& { return states[line++]; };
  auto toggled = [&](const char* key, const char* setting) {
    const auto& before = states[line - 1];
    const auto& after = next();
    EXPECT_NE(after[setting], before[setting]) << "key " << key << " did not change " << setting;
    for (const auto& [name, value] : after.items()) {
      if (name != setting && name != "messages") {
        EXPECT_EQ(value, before[name]) << "key " << key << " changed " << name;
      }
    }
  };
  EXPECT_TRUE(afterEdge["normalMapping"].get<bool>() && afterEdge["specular"].get<bool>() && afterEdge["shadows"].get<bool>());
  toggled("m", "normalMapping");
  toggled("s", "specular");
  toggled("h", "shadows");
  toggled("p", "pcfRadius");
  EXPECT_EQ(states[line - 1]["pcfRadius"].get<int>() * states[line - 2]["pcfRadius"].get<int>(), 0) << "p toggles PCF on and off";
  toggled("f", "flipGreen");
  toggled("g", "glyphs");
  toggled("b", "bitangent");
  EXPECT_EQ(states[line - 1]["bitangent"], "per-vertex");
  toggled("c", "split");
  EXPECT_FALSE(states[line - 1]["split"].get<bool>());
  toggled("c", "split");
  EXPECT_TRUE(states[line - 1]["split"].get<bool>());
  for (const char* view : kViewKeys) EXPECT_EQ(next()["view"], view);
  EXPECT_EQ(next()["view"], "compare-angle");
  EXPECT_EQ(next()["view"], "lit");
  EXPECT_EQ(next()["view"], "anisotropy-direction");
  EXPECT_EQ(next()["view"], "lit");
  const auto& reloaded = next();
  ASSERT_FALSE(reloaded["messages"].empty());
  EXPECT_EQ(reloaded["messages"].back(), "shaders reloaded");
  EXPECT_EQ(next()["view"], "lit");  // Escape's line
  EXPECT_EQ(next(), states[line - 2]);  // the window closed (exit 0 above) and said so
}

}  // namespace
