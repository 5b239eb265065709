// SPDX-License-Identifier: MIT
// tangent-view's application: its options, the loaded asset and its state (Viewer), and the
// rooms of the program, one file each: options.cpp (the command line), app.cpp (loading, pose,
// comparison), screenshot.cpp (headless images), panel.cpp (the Dear ImGui panel, desktop
// only), main.cpp (the window and its event loop) and web/web.inc (the browser's API).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "camera.hpp"
#include "pose.hpp"
#include "renderer.hpp"
#include "resources.hpp"
#include "shader_library.hpp"
#include "tangent/check.hpp"
#include "tangent/scene.hpp"
#include "tangent/text.hpp"

struct GLFWwindow;

namespace tangent::viewer::app {

namespace fs = std::filesystem;

// The note channel. Every line the viewer prints that may carry file-derived text (names, paths,
// the decoders' and loaders' messages) goes through here, escaped as the CLI escapes it
// (text::shown): no control character reaches the terminal, and no
// name can begin a line of its own (a mesh named "\nok" forging a line of a CI log).
using tangent::text::shown;
void printNote(std::string_view text);
void printError(std::string_view text);

// The demo files (data/demo/NAME.gltf) the panel offers, and their folder.
extern const char* const kDemoFiles[5];
const fs::path& demoFolder();

// What the split view's right side and the compare-angle view compare the file's tangents with
// (--compare): the --reference generator's tangents computed at load, the file's own TANGENT again, or a second file's.
enum class CompareSource : std::uint8_t { fresh, file, otherFile };

struct Options {
  fs::path input = demoFolder() / "scene.gltf";
  std::optional<fs::path> screenshot;
  int width = 1280, height = 720;
  std::string camera = "iso";
  std::optional<std::pair<glm::vec3, glm::vec3>> frameBox;  // --frame-box: min, max (world space)
  bool orthographic = false;
  RenderSettings settings;
  bool negateW = false;
  tangent::gltf::Generator reference;  // --reference: the fresh tangents' generator and check's
  fs::path sphereMap = demoFolder() / "spheremap.png";
  bool sphereMapGiven = false;  // --sphere-map: its failure is an error, not a note
  fs::path shaderDir = resourceFolder("shaders");
  fs::path assetRoot;  // --asset-root: the folder buffer and image URIs may not leave
  int frames = 1;
  bool checkShaders = false;
  bool stats = false;  // --stats
  int msaaSamples = -1;  // 0: off; -1: 4, or off on a software rasteriser (softwareRasteriser)
  bool pcfGiven = false;  // --pcf; else 3x3, or off (one bilinear comparison) on a software rasteriser
  std::optional<std::string> animation;  // --animation N|NAME (with --time alone: animation 0)
  std::optional<float> time;             // --time SECONDS
  CompareSource compare = CompareSource::fresh;
  fs::path compareFile;                  // --compare FILE
  bool printState = false;               // --print-state
};

// Reads the command line into `options`: -1 to go on, else the exit code (help printed, or a
// usage error).
int parseOptions(int argc, char** argv, Options& options);
tangent::gltf::SceneOptions sceneOptionsFor(const Options& options);
// --stats: one line on what a scene holds.
void printSceneStats(const fs::path& file, const tangent::gltf::Scene& scene);

// Everything about the loaded asset the window shows.
struct Viewer {
  Options options;
  ShaderLibrary shaders;
  Renderer renderer;
  OrbitCamera camera;
  std::vector<std::string> messages;
  fs::path loaded;
  int loadedDemo = -1;  // index into kDemoFiles of the file loaded, -1 for any other file
  PoseTime pose;        // the animation shown and its time
  bool playing = false; // the window advances the time (looping over the animation)

  explicit Viewer(const Options& o) : options(o), shaders(o.shaderDir), renderer(shaders) {}
  bool choosePose();
  bool applyCompare();
  bool load(const fs::path& file);
};

// Whether the GL implementation of this name shades on the CPU (llvmpipe, softpipe,
// SwiftShader), and the defaults that follow from it where the options left them open.
bool softwareRasteriser(std::string_view renderer);
void applyRasteriserDefaults(Options& options, bool software);

// --screenshot: the frames rendered offscreen and the last written as PNG; the exit code.
int screenshot(Viewer& viewer);

// The panel (Dear ImGui; not in the web build, whose page has its own controls).
void drawPanel(Viewer& viewer, GLFWwindow* window, const FrameStats& stats, double frameMs, char (&openPath)[1024], bool& focusOpen);

}  // namespace tangent::viewer::app
