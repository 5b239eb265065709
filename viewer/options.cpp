// SPDX-License-Identifier: MIT
// tangent-view's command line (--help, every option and its checks), the note channel, and
// the defaults that follow the rasteriser.
#include <ctime>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app.hpp"
#include "tangent/arguments.hpp"
#include "tangent/option_table.hpp"
#include "debug_colours.hpp"
#include "pointer.hpp"
#include "shader_check.hpp"
#include "textures.hpp"
#include "tangent/gltf.hpp"
#include "tangent/input_file.hpp"
#include "tangent/tangent.hpp"

namespace tangent::viewer::app {

void printNote(std::string_view text) { std::cerr << "note: " << shown(text) << "\n"; }
void printError(std::string_view text) { std::cerr << "error: " << shown(text) << "\n"; }

namespace {

const char* kUsageHead =
    "usage: tangent-view [IN] [options]\n"
    "\n"
    "Shows a glTF asset (default: the bundled demo scene) with shadowed normal and specular mapping\n"
    "and views that validate its tangent frames.\n"
    "\n";
const char* kUsageKeys =
    "keys: m normal map, s specular, h shadows, p PCF, f green flip, 1-9 and 0 views, g glyphs,\n"
    "      c split compare view, a compare-angle view, d anisotropy-direction view,\n"
    "      b per-vertex/per-fragment bitangent,\n"
    "      r reload shaders, o open, mouse: left orbit (drag the divider to move it), right/middle pan, wheel zoom\n";

// tangent-view's one command: its rows of the option table.
constexpr unsigned kView = 1u;

// The names of a table of the viewer's (kDebugViews, kShadings, ...) as the option table's
// choices: "a|b|c", kept for the life of the program.
template <class Entries>
std::string_view choicesOf(const Entries& entries) {
  static const std::string text = [&] {
    std::string names;
    for (const auto& entry : entries) names += (names.empty() ? "" : "|") + std::string(entry.name);
    return names;
  }();
  return text;
}

// tangent-view's options, parsed and listed in --help by the same parser as tangent's commands
// (tangent/arguments.hpp); the choices are the viewer's own tables, so a view added there is an
// option value here.
std::span<const options::Option> viewerOptions() {
  using options::Kind;
  constexpr unsigned kCli = options::kCommandLine;
  constexpr double kHuge = 3.4e38;
  // --reference takes what tangent check --reference takes (its row's choices; "lengyel" among them).
  const std::string_view generators = options::find("reference", options::kCheck, kCli)->choices;
  static const std::vector<options::Option> table = {
    {"screenshot", 0, Kind::path, "", "", 0, 0, false, kView, kCli, "OUT.png", "render one frame without a window, write it and exit"},
    {"size", 0, Kind::text, "", "", 0, 0, false, kView, kCli, "WxH", "window or screenshot size, 16..8192 each (default 1280x720)"},
    {"camera", 0, Kind::choice, kCameraViews, "iso", 0, 0, false, kView, kCli, "NAME", "the side the camera looks from"},
    {"ortho", 0, Kind::flag, "", "false", 0, 0, false, kView, kCli, "", "orthographic projection"},
    {"frame-box", 0, Kind::text, "", "", 0, 0, false, kView, kCli, "X0,Y0,Z0,X1,Y1,Z1",
     "frame the camera on this world-space box instead of the scene"},
    {"view", 0, Kind::choice, choicesOf(kDebugViews), "lit", 0, 0, false, kView, kCli, "NAME",
     "what the pixels show. handedness: the file's w; face-orientation: front blue, back red; handedness-world: w "
     "after the node's mirroring; compare-angle: the per-pixel angle between the file's tangent frames and the "
     "--compare set's (blue 0, green 1 deg, yellow 5 deg, red >= 20 deg); anisotropy-direction: "
     "KHR_materials_anisotropy's direction in world space as colour (grey where a material has none); "
     "clearcoat-normal: KHR_materials_clearcoat's normal (its normal map through TANGENT) in world space as colour"},
    {"compare", 0, Kind::text, "", "", 0, 0, false, kView, kCli, "SET",
     "split view: left of the divider the file's TANGENT, right of it SET: fresh (the --reference generator's "
     "tangents computed at load, the default set of compare-angle) | file (the file's TANGENT again) | "
     "FILE.gltf/.glb (a second file's TANGENT, for the same triangles in the same order, e.g. another bake)"},
    {"split", 0, Kind::number, "", "0.5", 0, 1, false, kView, kCli, "F", "the divider's place, a fraction of the width from the left"},
    {"bitangent", 0, Kind::choice, choicesOf(kBitangentModes), "per-fragment", 0, 0, false, kView, kCli, "MODE",
     "per-fragment: B = cross(N, T) * w from the interpolated N and T; per-vertex: B interpolated from the "
     "vertices; to match the baker"},
    {"glyphs", 0, Kind::flag, "", "false", 0, 0, false, kView, kCli, "", "draw tangent frames (T red, B green, N blue); in the anisotropy-direction view, the anisotropy's direction (amber)"},
    {"no-shadows", 0, Kind::flag, "", "false", 0, 0, false, kView, kCli, "", "no shadow map"},
    {"pcf", 0, Kind::integer, "", "1", 0, 2, false, kView, kCli, "N",
     "percentage-closer filtering: 0 off, 1 = 3x3, 2 = 5x5 (0 by default on a software rasteriser)"},
    {"shadow-map-size", 0, Kind::integer, "", "2048", 256, 8192, false, kView, kCli, "N", "the shadow map's width and height"},
    {"shading", 0, Kind::choice, choicesOf(kShadings), "pbr", 0, 0, false, kView, kCli, "NAME",
     "pbr: glTF metallic-roughness; blinn-phong and phong: the specular-map mode"},
    {"phong", 0, Kind::flag, "", "false", 0, 0, false, kView, kCli, "", "the same as --shading phong"},
    {"tone-map", 0, Kind::choice, choicesOf(kToneMappings), "khr-pbr-neutral", 0, 0, false, kView, kCli, "NAME",
     "none: values above 1 clip; unlit materials and debug views are never tone mapped"},
    {"exposure", 0, Kind::text, "", "", 0, 0, false, kView, kCli, "F|auto",
     "linear factor on the lit colour before tone mapping (default auto: a white surface facing the brightest "
     "light at the centre of the rest pose's bounds shows at 0.76; decided once per asset, the same at every "
     "--time and animation)"},
    {"depth-prepass", 0, Kind::flag, "", "false", 0, 0, false, kView, kCli, "", "draw opaque depth first, then shade each pixel once"},
    {"no-ibl", 0, Kind::flag, "", "false", 0, 0, false, kView, kCli, "",
     "pbr without image-based lighting: a plain sky term instead of the built-in environment (a sky, a ground "
     "and a sun, prefiltered at start-up)"},
    {"ibl-intensity", 0, Kind::number, "", "1", 0, kHuge, false, kView, kCli, "F",
     "factor on the environment's radiance (1: its mean radiance a fifth of the lights' direct level)"},
    {"animation", 0, Kind::text, "", "", 0, 0, false, kView, kCli, "N|NAME",
     "pose the scene by this animation (index or name; default: none, the nodes' own transforms, morph weights "
     "and skins in the rest pose); one the file does not have is an error listing those it has"},
    {"time", 0, Kind::number, "", "0", -kHuge, kHuge, false, kView, kCli, "SECONDS",
     "the animation's time (alone, it picks animation 0)"},
    {"msaa", 0, Kind::integer, "", "4", 0, 16, false, kView, kCli, "N",
     "samples per pixel in the window and screenshots (0 by default on a software rasteriser such as llvmpipe, "
     "where 4x costs 3-4 times the frame)"},
    {"no-normal-map", 0, Kind::flag, "", "false", 0, 0, false, kView, kCli, "", "shade with the geometry's normals"},
    {"no-specular", 0, Kind::flag, "", "false", 0, 0, false, kView, kCli, "", "no specular highlights"},
    {"flip-green", 0, Kind::flag, "", "false", 0, 0, false, kView, kCli, "", "read the normal map's green channel flipped (DirectX)"},
    {"negate-w", 0, Kind::flag, "", "false", 0, 0, false, kView, kCli, "", "negate the file's TANGENT w (a baker's other convention)"},
    {"reflectivity", 0, Kind::number, "", "0", 0, 1, false, kView, kCli, "F", "the sphere-map reflection's share"},
    {"sphere-map", 0, Kind::path, "", "", 0, 0, false, kView, kCli, "FILE", "the sphere map reflected (default: the demo's)"},
    {"uv-scale", 0, Kind::number, "", "1", 0, kHuge, true, kView, kCli, "F", "UV tiling factor"},
    {"frames", 0, Kind::integer, "", "1", 1, 10000, false, kView, kCli, "N",
     "with --screenshot: render N frames and print the median frame time (wall clock, and the CPU time of all "
     "the process's threads, a software rasteriser's included) and how many shadow-map passes they drew"},
    {"stats", 0, Kind::flag, "", "false", 0, 0, false, kView, kCli, "",
     "print what the file's scene holds (primitives, the instances that draw them, triangles, images, lights); "
     "without --screenshot, load the file, print and exit without a window (1 when it cannot be loaded)"},
    {"asset-root", 0, Kind::path, "", "", 0, 0, false, kView, kCli, "DIR",
     "folder buffer and image URIs may not leave (default: the file's folder)"},
    {"reference", 0, Kind::choice, generators, "mikktspace", 0, 0, false, kView, kCli, "NAME",
     "what the fresh tangents and the error view's verdicts use, as tangent check --reference (the error view is "
     "check --all's verdict)"},
    {"shader-dir", 0, Kind::path, "", "", 0, 0, false, kView, kCli, "DIR", "where the shaders are (default: the source tree's shaders/)"},
    {"print-state", 0, Kind::flag, "", "false", 0, 0, false, kView, kCli, "",
     "in the window: print the settings the keys and the mouse change (view, toggles, divider, camera) as a "
     "JSON line after each key press, each mouse button release and when it closes, for tests"},
    {"check-shaders", 0, Kind::flag, "", "false", 0, 0, false, kView, kCli, "",
     "link the programs in a spread of variants, compare their vertex inputs with the layout tables "
     "(viewer/vertex_layout.hpp) and exit (1 on a mismatch)"},
  };
  return table;
}


// The demo files the panel offers (data/demo/NAME.gltf), and where they are.

}  // namespace

const char* const kDemoFiles[] = {"scene", "quad", "cube", "sphere", "torus"};
const fs::path& demoFolder() {
  static const fs::path folder = resourceFolder("data") / "demo";
  return folder;
}

namespace {

// Where a choice names an entry of one of the viewer's tables: its value.
template <class Entries, class Member>
auto valueNamed(const Entries& entries, std::string_view name, Member member) {
  for (const auto& entry : entries)
    if (name == entry.name) return entry.*member;
  return entries[0].*member;  // not reached: the parser checked the name against the same table
}

// One checked option value into `options`; throws std::invalid_argument for what the table's
// kinds cannot check (--size, --frame-box, --exposure).
void applyViewerOption(Options& options, std::string_view name, const std::string& value) {
  RenderSettings& s = options.settings;
  const bool on = options::isTrue(value);
  if (name == "screenshot") options.screenshot = value;
  else if (name == "size") {
    if (std::sscanf(value.c_str(), "%dx%d", &options.width, &options.height) != 2 || options.width < 16 || options.height < 16 ||
        options.width > 8192 || options.height > 8192)
      throw std::invalid_argument("--size must be WxH, 16..8192");
  } else if (name == "camera") options.camera = value;
  else if (name == "ortho") options.orthographic = on;
  else if (name == "frame-box") {
    glm::vec3 lo, hi;
    if (std::sscanf(value.c_str(), "%f,%f,%f,%f,%f,%f", &lo.x, &lo.y, &lo.z, &hi.x, &hi.y, &hi.z) != 6 ||
        !glm::all(glm::lessThanEqual(lo, hi)) || !std::isfinite(glm::length(hi - lo)))
      throw std::invalid_argument("--frame-box must be X0,Y0,Z0,X1,Y1,Z1 with X0 <= X1, Y0 <= Y1, Z0 <= Z1");
    options.frameBox = {lo, hi};
  } else if (name == "view") s.view = valueNamed(kDebugViews, value, &DebugViewInfo::view);
  else if (name == "compare") {
    options.compare = value == "fresh" ? CompareSource::fresh : value == "file" ? CompareSource::file : CompareSource::otherFile;
    if (options.compare == CompareSource::otherFile) options.compareFile = value;
    s.split = true;
  } else if (name == "split") s.splitPosition = std::stof(value);
  else if (name == "bitangent") s.bitangent = valueNamed(kBitangentModes, value, &BitangentModeInfo::mode);
  else if (name == "glyphs") s.glyphs = on;
  else if (name == "no-shadows") s.shadows = !on;
  else if (name == "pcf") s.pcfRadius = std::stoi(value), options.pcfGiven = true;
  else if (name == "shadow-map-size") s.shadowMapSize = std::stoi(value);
  else if (name == "shading") s.shading = valueNamed(kShadings, value, &ShadingInfo::shading);
  else if (name == "phong") s.shading = on ? Shading::phong : s.shading;
  else if (name == "tone-map") s.toneMapping = valueNamed(kToneMappings, value, &ToneMappingInfo::toneMapping);
  else if (name == "exposure") {
    char* end = nullptr;
    const float factor = value == "auto" ? 0.0f : std::strtof(value.c_str(), &end);
    if (value != "auto" && (end != value.c_str() + value.size() || !(factor > 0) || !std::isfinite(factor)))
      throw std::invalid_argument("--exposure must be > 0 or auto");
    s.exposure = factor;
  } else if (name == "depth-prepass") s.depthPrePass = on;
  else if (name == "no-ibl") s.ibl = !on;
  else if (name == "ibl-intensity") s.iblIntensity = std::stof(value);
  else if (name == "animation") options.animation = value;
  else if (name == "time") options.time = std::stof(value);
  else if (name == "msaa") options.msaaSamples = std::stoi(value);
  else if (name == "no-normal-map") s.normalMapping = !on;
  else if (name == "no-specular") s.specular = !on;
  else if (name == "flip-green") s.flipGreen = on;
  else if (name == "negate-w") options.negateW = on;
  else if (name == "reflectivity") s.reflectivity = std::stof(value);
  else if (name == "sphere-map") options.sphereMap = value, options.sphereMapGiven = true;
  else if (name == "uv-scale") s.uvScale = std::stof(value);
  else if (name == "frames") options.frames = std::stoi(value);
  else if (name == "stats") options.stats = on;
  else if (name == "asset-root") options.assetRoot = value;
  else if (name == "reference") options.reference = *tangent::gltf::parseGenerator(value);
  else if (name == "shader-dir") options.shaderDir = value;
  else if (name == "print-state") options.printState = on;
  else if (name == "check-shaders") options.checkShaders = on;
  else throw std::logic_error("tangent-view: the option table's --" + std::string(name) + " has no effect here");
}

}  // namespace

int parseOptions(int argc, char** argv, Options& options) {
  const options::Arguments parsed = options::parseArguments(std::vector<std::string>(argv + 1, argv + argc), viewerOptions(), kView);
  if (parsed.help) {
    std::cout << kUsageHead << options::helpText(viewerOptions(), kView) << kUsageKeys;
    return 0;
  }
  try {
    if (!parsed.error.empty()) throw std::invalid_argument(parsed.error);
    if (parsed.operands.size() > 1)
      throw std::invalid_argument("one file at a time: '" + parsed.operands[0] + "' and '" + parsed.operands[1] + "'");
    if (!parsed.operands.empty()) options.input = parsed.operands.front();
    for (const auto& [option, value] : parsed.values) applyViewerOption(options, option->name, value);
  } catch (const std::exception& e) {
    std::cerr << "tangent-view: " << shown(e.what()) << " (see tangent-view --help)\n";
    return 2;
  }
  return -1;
}

tangent::gltf::SceneOptions sceneOptionsFor(const Options& options) {
  tangent::gltf::SceneOptions sceneOptions;
  sceneOptions.negateFileW = options.negateW;
  sceneOptions.assetRoot = options.assetRoot;
  sceneOptions.check.method = options.reference.method;
  sceneOptions.check.weighting = options.reference.weighting;
  return sceneOptions;
}

// --stats: one line on what a scene holds.
void printSceneStats(const fs::path& file, const tangent::gltf::Scene& scene) {
  std::size_t triangles = 0;
  for (const auto& instance : scene.instances) triangles += scene.items[instance.item].positions.size() / 9;
  std::printf("scene %s: %zu primitive(s), %zu instance(s), %zu triangle(s) drawn, %zu image(s), %zu light(s)\n", shown(file.string()).c_str(),
              scene.items.size(), scene.instances.size(), triangles, scene.images.size(), scene.lights.size());
  std::fflush(stdout);
}

// Whether the GL implementation of this name shades on the CPU: Mesa's llvmpipe and softpipe (as
// under Xvfb without a GPU), or SwiftShader (Chromium's WebGL without one, through ANGLE).
bool softwareRasteriser(std::string_view renderer) {
  for (const std::string_view name : {"llvmpipe", "softpipe", "SwiftShader"})
    if (renderer.find(name) != std::string_view::npos) return true;
  return false;
}

// The defaults that depend on the rasteriser, for the desktop and the web viewer alike: on the
// CPU, MSAA 4x costs 3-4 times the frame and PCF 3x3 (four bilinear comparisons per fragment)
// about a tenth of the lit frame, so both are off there unless --msaa or --pcf ask (without PCF
// the one comparison is still filtered over 2x2 texels).
void applyRasteriserDefaults(Options& options, bool software) {
  if (options.msaaSamples < 0) options.msaaSamples = software ? 0 : 4;
  if (!options.pcfGiven && software) options.settings.pcfRadius = 0;
}

}  // namespace tangent::viewer::app
