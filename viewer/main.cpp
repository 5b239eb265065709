// SPDX-License-Identifier: MIT
// tangent-view: shows a glTF asset with shadowed normal and specular mapping and the views that
// validate its tangent frames; renders headless screenshots for tests and reports.
#include "gl_platform.hpp"  // before GLFW: epoxy (or GLES3 on the web) provides the GL declarations
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#ifdef __EMSCRIPTEN__
// The web viewer: the page (viewer/web/index.html) holds the controls and calls web.inc's entry points.
#include <emscripten.h>
#else
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdlib>
#include <cstdio>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "camera.hpp"
#include "debug_colours.hpp"
#include "pointer.hpp"
#include "renderer.hpp"
#include "resources.hpp"
#include "shader_check.hpp"
#include "shader_library.hpp"
#include "tangent/check.hpp"
#include "tangent/gltf.hpp"
#include "tangent/input_file.hpp"
#include "tangent/scene.hpp"
#include "tangent/text.hpp"
#include "tangent/tangent.hpp"
#include "textures.hpp"

namespace {

namespace fs = std::filesystem;
using namespace tangent::viewer;

// The note channel. Every line the viewer prints that may carry file-derived text (names, paths,
// the decoders' and loaders' messages) goes through here, escaped as the CLI escapes it
// (text::shown): no control character reaches the terminal, and no
// name can begin a line of its own (a mesh named "\nok" forging a line of a CI log).
using tangent::text::shown;
void printNote(std::string_view text) { std::cerr << "note: " << shown(text) << "\n"; }
void printError(std::string_view text) { std::cerr << "error: " << shown(text) << "\n"; }

const char* kUsage =
    "usage: tangent-view [IN] [options]\n"
    "\n"
    "Shows a glTF asset (default: the bundled demo scene) with shadowed normal and specular mapping\n"
    "and views that validate its tangent frames.\n"
    "\n"
    "options:\n"
    "  --screenshot OUT.png     render one frame without a window and exit\n"
    "  --size WxH               window or screenshot size (default 1280x720)\n"
    "  --camera NAME            front | back | left | right | top | bottom | iso (default iso)\n"
    "  --ortho                  orthographic projection\n"
    "  --frame-box X0,Y0,Z0,X1,Y1,Z1  frame the camera on this world-space box instead of the scene\n"
    "  --view NAME              lit | geometry-normal | tangent | bitangent | shading-normal | uv |\n"
    "                           handedness (the file's w) | error | face-orientation (front blue, back red) |\n"
    "                           handedness-world (w after the node's mirroring) | compare-angle (the\n"
    "                           per-pixel angle between the file's tangent frames and the --compare set's:\n"
    "                           blue 0, green 1 deg, yellow 5 deg, red >= 20 deg) | anisotropy-direction\n"
    "                           (KHR_materials_anisotropy's direction in world space as colour, from the\n"
    "                           TANGENT frame, rotation and texture; grey where a material has none) (default lit)\n"
    "  --compare SET            split view: left of the divider the file's TANGENT, right of it SET:\n"
    "                           fresh (the --reference generator's tangents computed at load, the default\n"
    "                           set of compare-angle) |\n"
    "                           file (the file's TANGENT again: both sides alike) | FILE.gltf/.glb (a second\n"
    "                           file's TANGENT, for the same triangles in the same order, e.g. another bake)\n"
    "  --split F                the divider's place, a fraction of the width from the left (default 0.5)\n"
    "  --bitangent MODE         per-fragment (B = cross(N, T) * w from the interpolated N and T, default) |\n"
    "                           per-vertex (B interpolated from the vertices), to match the baker\n"
    "  --glyphs                 draw tangent frames (T red, B green, N blue)\n"
    "  --no-shadows, --pcf N (0 off, 1 = 3x3, 2 = 5x5; default 1, or 0 on a software rasteriser),\n"
    "                           --shadow-map-size N (1024..4096)\n"
    "  --shading NAME           pbr (glTF metallic-roughness, default) | blinn-phong | phong (specular-map mode)\n"
    "  --tone-map NAME          khr-pbr-neutral (default) | aces | none (values above 1 clip); unlit\n"
    "                           materials and debug views are never tone mapped\n"
    "  --exposure F|auto        linear factor on the lit colour before tone mapping (default auto: a white\n"
    "                           surface facing the brightest light at the centre of the rest pose's bounds\n"
    "                           shows at 0.76; decided once per asset, the same at every --time and animation)\n"
    "  --depth-prepass          draw opaque depth first, then shade each pixel once\n"
    "  --no-ibl                 pbr without image-based lighting: a plain sky term instead of the built-in\n"
    "                           environment (a sky, a ground and a sun, prefiltered at start-up)\n"
    "  --ibl-intensity F        factor on the environment's radiance (default 1: its mean radiance a fifth\n"
    "                           of the lights' direct level)\n"
    "  --animation N|NAME       pose the scene by this animation (index or name; default: none, the nodes'\n"
    "                           own transforms, morph weights and skins in the rest pose); one the file does\n"
    "                           not have is an error listing those it has\n"
    "  --time SECONDS           the animation's time (default 0; alone, it picks animation 0)\n"
    "  --msaa N                 samples per pixel in the window and screenshots (default 4, or 0 on a\n"
    "                           software rasteriser such as llvmpipe, where 4x costs 3-4 times the frame)\n"
    "  --no-normal-map, --no-specular, --phong (= --shading phong), --flip-green, --negate-w\n"
    "  --reflectivity F, --sphere-map FILE, --uv-scale F\n"
    "  --frames N               with --screenshot: render N frames and print the median frame time (wall\n"
    "                           clock, and the CPU time of all the process's threads, a software\n"
    "                           rasteriser's included) and how many shadow-map passes they drew\n"
    "  --stats                  print what the file's scene holds (primitives, the instances that draw\n"
    "                           them, triangles, images, lights); without --screenshot, load the file, print\n"
    "                           and exit without a window (1 when it cannot be loaded)\n"
    "  --asset-root DIR         folder buffer and image URIs may not leave (default: the file's folder)\n"
    "  --reference NAME         what the fresh tangents and the error view's verdicts use, as tangent check\n"
    "                           --reference: mikktspace (default) | lengyel/angle | lengyel/area |\n"
    "                           lengyel/uniform | flat | meshopt (the error view is check --all's verdict)\n"
    "  --shader-dir DIR         where the shaders are (default: the source tree's shaders/)\n"
    "  --print-state            in the window: print the settings the keys and the mouse change (view,\n"
    "                           toggles, divider, camera) as a JSON line after each key press, each mouse\n"
    "                           button release and when it closes, for tests\n"
    "  --check-shaders          link the programs in a spread of variants, compare their vertex inputs\n"
    "                           with the layout tables (viewer/vertex_layout.hpp) and exit (1 on a mismatch)\n"
    "keys: m normal map, s specular, h shadows, p PCF, f green flip, 1-9 and 0 views, g glyphs,\n"
    "      c split compare view, a compare-angle view, b per-vertex/per-fragment bitangent,\n"
    "      r reload shaders, o open, mouse: left orbit (drag the divider to move it), right/middle pan, wheel zoom\n";

// The demo files the panel offers (data/demo/NAME.gltf), and where they are.
const char* const kDemoFiles[] = {"scene", "quad", "cube", "sphere", "torus"};
const fs::path& demoFolder() {
  static const fs::path folder = resourceFolder("data") / "demo";
  return folder;
}

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

int parseOptions(int argc, char** argv, Options& options) {
  std::vector<std::string> args(argv + 1, argv + argc);
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw std::invalid_argument(arg + " needs a value");
      return args[++i];
    };
    try {
      if (arg == "-h" || arg == "--help") {
        std::cout << kUsage;
        return 0;
      } else if (arg == "--screenshot") options.screenshot = value();
      else if (arg == "--size") {
        const std::string size = value();
        if (std::sscanf(size.c_str(), "%dx%d", &options.width, &options.height) != 2 || options.width < 16 || options.height < 16 ||
            options.width > 8192 || options.height > 8192)
          throw std::invalid_argument("--size must be WxH, 16..8192");
      } else if (arg == "--camera") options.camera = value();
      else if (arg == "--ortho") options.orthographic = true;
      else if (arg == "--frame-box") {
        glm::vec3 lo, hi;
        if (std::sscanf(value().c_str(), "%f,%f,%f,%f,%f,%f", &lo.x, &lo.y, &lo.z, &hi.x, &hi.y, &hi.z) != 6 ||
            !glm::all(glm::lessThanEqual(lo, hi)) || !std::isfinite(glm::length(hi - lo)))
          throw std::invalid_argument("--frame-box must be X0,Y0,Z0,X1,Y1,Z1 with X0 <= X1, Y0 <= Y1, Z0 <= Z1");
        options.frameBox = {lo, hi};
      }
      else if (arg == "--view") {
        const std::string name = value();
        bool found = false;
        for (const auto& view : kDebugViews) {
          if (name == view.name) options.settings.view = view.view, found = true;
        }
        if (!found) throw std::invalid_argument("unknown --view " + name);
      } else if (arg == "--glyphs") options.settings.glyphs = true;
      else if (arg == "--no-shadows") options.settings.shadows = false;
      else if (arg == "--pcf") {
        options.settings.pcfRadius = std::clamp(std::stoi(value()), 0, 2);
        options.pcfGiven = true;
      }
      else if (arg == "--shadow-map-size") options.settings.shadowMapSize = std::clamp(std::stoi(value()), 256, 8192);
      else if (arg == "--no-normal-map") options.settings.normalMapping = false;
      else if (arg == "--no-specular") options.settings.specular = false;
      else if (arg == "--phong") options.settings.shading = Shading::phong;
      else if (arg == "--shading") {
        const std::string name = value();
        bool found = false;
        for (const auto& shading : kShadings) {
          if (name == shading.name) options.settings.shading = shading.shading, found = true;
        }
        if (!found) throw std::invalid_argument("unknown --shading " + name);
      } else if (arg == "--msaa") options.msaaSamples = std::clamp(std::stoi(value()), 0, 16);
      else if (arg == "--flip-green") options.settings.flipGreen = true;
      else if (arg == "--negate-w") options.negateW = true;
      else if (arg == "--reference") {
        const std::string name = value();
        const std::optional<tangent::gltf::Generator> generator = tangent::gltf::parseGenerator(name);
        if (!generator) throw std::invalid_argument("--reference must be " + tangent::gltf::generatorNames() + ", not " + name);
        options.reference = *generator;
      }
      else if (arg == "--reflectivity") options.settings.reflectivity = std::clamp(std::stof(value()), 0.0f, 1.0f);
      else if (arg == "--sphere-map") options.sphereMap = value(), options.sphereMapGiven = true;
      else if (arg == "--uv-scale") options.settings.uvScale = std::stof(value());
      else if (arg == "--frames") options.frames = std::clamp(std::stoi(value()), 1, 10000);
      else if (arg == "--shader-dir") options.shaderDir = value();
      else if (arg == "--asset-root") options.assetRoot = value();
      else if (arg == "--check-shaders") options.checkShaders = true;
      else if (arg == "--stats") options.stats = true;
      else if (arg == "--print-state") options.printState = true;
      else if (arg == "--depth-prepass") options.settings.depthPrePass = true;
      else if (arg == "--no-ibl") options.settings.ibl = false;
      else if (arg == "--ibl-intensity") {
        const float intensity = std::stof(value());
        if (!(intensity >= 0) || !std::isfinite(intensity)) throw std::invalid_argument("--ibl-intensity must be >= 0");
        options.settings.iblIntensity = intensity;
      }
      else if (arg == "--animation") options.animation = value();
      else if (arg == "--compare") {
        const std::string source = value();
        options.compare = source == "fresh" ? CompareSource::fresh : source == "file" ? CompareSource::file : CompareSource::otherFile;
        if (options.compare == CompareSource::otherFile) options.compareFile = source;
        options.settings.split = true;
      } else if (arg == "--split") {
        const float place = std::stof(value());
        if (!(place >= 0 && place <= 1)) throw std::invalid_argument("--split must be within 0..1");
        options.settings.splitPosition = place;
      } else if (arg == "--bitangent") {
        const std::string name = value();
        bool found = false;
        for (const auto& mode : kBitangentModes) {
          if (name == mode.name) options.settings.bitangent = mode.mode, found = true;
        }
        if (!found) throw std::invalid_argument("unknown --bitangent " + name);
      }
      else if (arg == "--time") {
        const float seconds = std::stof(value());
        if (!std::isfinite(seconds)) throw std::invalid_argument("--time must be a number of seconds");
        options.time = seconds;
      }
      else if (arg == "--exposure") {
        const std::string text = value();
        if (text == "auto") options.settings.exposure = 0;
        else if (!(std::stof(text) > 0) || !std::isfinite(std::stof(text))) throw std::invalid_argument("--exposure must be > 0 or auto");
        else options.settings.exposure = std::stof(text);
      } else if (arg == "--tone-map") {
        const std::string name = value();
        bool found = false;
        for (const auto& entry : kToneMappings) {
          if (name == entry.name) options.settings.toneMapping = entry.toneMapping, found = true;
        }
        if (!found) throw std::invalid_argument("unknown --tone-map " + name);
      }
      else if (!arg.empty() && arg[0] == '-') throw std::invalid_argument("unknown option " + arg);
      else options.input = arg;
    } catch (const std::exception& e) {
      std::cerr << "tangent-view: " << shown(e.what()) << "\n\n" << kUsage;
      return 2;
    }
  }
  OrbitCamera probe;
  if (!probe.frame(glm::vec3(-1), glm::vec3(1), options.camera)) {
    std::cerr << "tangent-view: unknown --camera " << shown(options.camera) << "\n";
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

  // The pose the options ask for: --animation and --time, else the rest pose. False (with a
  // message) for an animation the file does not have.
  bool choosePose() {
    pose = PoseTime{};
    playing = false;
    const auto& scene = renderer.scene();
    if (options.animation || options.time) {
      const std::optional<int> animation = findAnimation(scene, options.animation.value_or("0"));
      if (!animation) {
        const std::string text = "no animation '" + options.animation.value_or("0") + "' in " + loaded.string() + "; it has " +
                                 std::to_string(scene.animations.size()) + ": " + animationNames(scene);
        messages.push_back(text);
        printError(text);
        return !options.screenshot;  // a screenshot of another pose would mislead
      }
      pose = PoseTime{*animation, options.time.value_or(0.0f)};
      playing = !options.screenshot && !options.time;  // the window plays an animation named without a time
    }
    renderer.setPose(pose);
    return true;
  }

  // Hands the renderer the set that the split view's right side and the compare-angle view
  // compare with the file's tangents, as options.compare says: fresh (the renderer's
  // default), file (the file's own) or a second file, whose primitives must hold the same
  // triangles in the same order. False, with a message, when that file cannot be used.
  bool applyCompare() {
    const auto& items = renderer.scene().items;
    std::vector<std::vector<float>> sets;
    auto refuse = [&](const std::string& why) {
      const std::string text = "--compare " + options.compareFile.string() + ": " + why + "; compared with fresh tangents instead";
      messages.push_back(text);
      printError(text);
      options.compare = CompareSource::fresh;
      renderer.setCompareTangents({});
      return false;
    };
    if (options.compare == CompareSource::file) {
      for (const auto& item : items) sets.push_back(item.tangents);
    } else if (options.compare == CompareSource::otherFile) {
      tangent::gltf::Scene other;
      try {
        tangent::gltf::SceneOptions otherOptions;  // its TANGENT only: no verdicts
        otherOptions.judge = false;
        other = tangent::gltf::loadScene(options.compareFile, otherOptions);
      } catch (const std::exception& e) {
        return refuse(e.what());
      }
      if (other.items.size() != items.size())
        return refuse("it has " + std::to_string(other.items.size()) + " primitive(s) to show, " + loaded.filename().string() + " has " +
                      std::to_string(items.size()));
      // The same corners, up to a rounding of the positions: a baked copy keeps the triangles
      // and their order (vertices split or not).
      const float tolerance = 1e-4f * renderer.boundsRadius();
      for (std::size_t i = 0; i < items.size(); ++i) {
        const auto& mine = items[i].positions;
        const auto& theirs = other.items[i].positions;
        if (mine.size() != theirs.size())
          return refuse(other.items[i].label + " has " + std::to_string(theirs.size() / 9) + " triangle(s), " + items[i].label + " has " +
                        std::to_string(mine.size() / 9));
        for (std::size_t k = 0; k < mine.size(); ++k)
          if (!(std::abs(mine[k] - theirs[k]) <= tolerance))
            return refuse(other.items[i].label + "'s corner " + std::to_string(k / 3) + " is elsewhere than " + items[i].label + "'s");
        if (!other.items[i].tangentsFromFile)
          messages.push_back("--compare " + options.compareFile.string() + ": " + other.items[i].label + " has no TANGENT; its tangents were computed at load");
        sets.push_back(std::move(other.items[i].tangents));
      }
    }
    renderer.setCompareTangents(std::move(sets));
    return true;
  }

  bool load(const fs::path& file) {
    messages.clear();
    try {
      tangent::gltf::Scene scene = tangent::gltf::loadScene(file, sceneOptionsFor(options));
      if (options.stats) printSceneStats(file, scene);
      messages = scene.messages;
      renderer.setScene(std::move(scene), messages);
      loaded = file;
      const bool compared = applyCompare();
      // The viewer keeps the scene, not the scratch memory of computing its frames (tangent.hpp).
      tangent::releaseCachedWorkspaces();
      if (!compared && options.screenshot) return false;  // a screenshot of another comparison would mislead
      loadedDemo = -1;
      for (int i = 0; i < static_cast<int>(std::size(kDemoFiles)); ++i) {
        std::error_code ec;
        if (fs::equivalent(file, demoFolder() / (std::string(kDemoFiles[i]) + ".gltf"), ec)) loadedDemo = i;
      }
    } catch (const std::exception& e) {
      messages.push_back(std::string("cannot open: ") + e.what());
      printError(e.what());
      return false;
    }
    for (const auto& m : messages) printNote(m);
    if (!choosePose()) return false;
    camera.frame(options.frameBox ? options.frameBox->first : renderer.boundsMin(),
                 options.frameBox ? options.frameBox->second : renderer.boundsMax(), options.camera,
                 float(options.width) / float(options.height));
    camera.orthographic = options.orthographic;
    if (options.settings.reflectivity > 0 || options.sphereMapGiven || fs::exists(options.sphereMap)) {
      std::vector<std::string> sphereMessages;
      const bool sphereLoaded = renderer.loadSphereMap(options.sphereMap, sphereMessages);
      messages.insert(messages.end(), sphereMessages.begin(), sphereMessages.end());
      // One that --sphere-map names and that cannot be used is an error (a screenshot without it
      // would mislead); a default one that fails matters only when reflections are on.
      if (!sphereLoaded && options.sphereMapGiven) {
        for (const auto& m : sphereMessages) printError("--sphere-map: " + m);
        return false;
      }
      if (sphereLoaded || options.settings.reflectivity > 0)
        for (const auto& m : sphereMessages) printNote(m);
    }
    return true;
  }
};

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

std::string glErrors() {
  std::string errors;
  for (GLenum error = glGetError(); error != GL_NO_ERROR; error = glGetError()) {
    char hex[16];
    std::snprintf(hex, sizeof hex, " 0x%04x", error);
    errors += hex;
  }
  return errors;
}

// An offscreen framebuffer with a colour and a depth renderbuffer, multisampled when samples > 0.
struct OffscreenTarget {
  Framebuffer framebuffer;
  Renderbuffer color, depth;
};

bool makeOffscreenTarget(OffscreenTarget& target, int width, int height, int samples, bool withDepth) {
  target.framebuffer = makeFramebuffer();
  target.color = makeRenderbuffer();
  glBindRenderbuffer(GL_RENDERBUFFER, target.color.get());
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, target.color.get());
  if (withDepth) {
    target.depth = makeRenderbuffer();
    glBindRenderbuffer(GL_RENDERBUFFER, target.depth.get());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, target.depth.get());
  }
  return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

int screenshot(Viewer& viewer) {
  const Options& o = viewer.options;
  // Drawn into a multisampled target (as the window is), resolved into a plain one to read.
  GLint maxSamples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  const int samples = std::min(o.msaaSamples > 1 ? o.msaaSamples : 0, static_cast<int>(maxSamples));
  OffscreenTarget drawTarget, readTarget;
  if (!makeOffscreenTarget(drawTarget, o.width, o.height, samples, true) ||
      (samples > 0 && !makeOffscreenTarget(readTarget, o.width, o.height, 0, false))) {
    std::cerr << "error: offscreen framebuffer incomplete\n";
    return 1;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, drawTarget.framebuffer.get());
  const CameraMatrices matrices = viewer.camera.matrices(float(o.width) / float(o.height));
  std::vector<double> milliseconds, cpuMilliseconds;  // cpu: every thread of the process (std::clock)
  FrameStats stats;
  int shadowDrawCalls = 0;
  try {
    for (int frame = 0; frame < o.frames; ++frame) {
      const auto start = std::chrono::steady_clock::now();
      const std::clock_t cpuStart = std::clock();
      glBindFramebuffer(GL_FRAMEBUFFER, drawTarget.framebuffer.get());
      stats = viewer.renderer.render(matrices, o.settings, o.width, o.height);
      shadowDrawCalls += stats.shadowDrawCalls;
      if (samples > 0) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, drawTarget.framebuffer.get());
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, readTarget.framebuffer.get());
        glBlitFramebuffer(0, 0, o.width, o.height, 0, 0, o.width, o.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
      }
      glFinish();
      milliseconds.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      cpuMilliseconds.push_back(1000.0 * static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC);
    }
  } catch (const std::exception& e) {
    printError(e.what());
    return 1;
  }
  std::vector<unsigned char> pixels(static_cast<std::size_t>(o.width) * o.height * 4);
  glBindFramebuffer(GL_FRAMEBUFFER, samples > 0 ? readTarget.framebuffer.get() : drawTarget.framebuffer.get());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, o.width, o.height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  const std::string errors = glErrors();
  if (!errors.empty()) {
    std::cerr << "error: OpenGL errors:" << errors << "\n";
    return 1;
  }
  std::string error;
  if (!writePng(o.screenshot->string(), o.width, o.height, pixels, error)) {
    printError(error);
    return 1;
  }
  std::sort(milliseconds.begin(), milliseconds.end());
  std::sort(cpuMilliseconds.begin(), cpuMilliseconds.end());
  // Draw calls and triangles of the last frame's view; the shadow map's draws, made in the first
  // frame (and again only when something moves), are counted apart.
  std::printf("wrote %s (%dx%d, %d samples): %zu triangles, %d draw calls, %zu shader variants, %d shadow pass(es) of %d draw "
              "call(s), exposure %.4g, median frame %.2f ms (CPU %.2f ms) over %d frame(s)\n",
              shown(o.screenshot->string()).c_str(), o.width, o.height, std::max(samples, 1), stats.triangles, stats.drawCalls,
              viewer.shaders.variantsCompiled(), viewer.renderer.shadowPasses(), shadowDrawCalls, stats.exposure, milliseconds[milliseconds.size() / 2],
              cpuMilliseconds[cpuMilliseconds.size() / 2], o.frames);
  if (viewer.renderer.environmentMilliseconds() > 0)
    std::printf("image-based lighting prepared in %.1f ms\n", viewer.renderer.environmentMilliseconds());
  return 0;
}

#ifndef __EMSCRIPTEN__
// The heatmap of the error and compare-angle views: debug_views.glsl's heatmap() stops.
void drawHeatmapLegend() {
  for (const HeatmapStop& stop : kHeatmapStops) {
    ImGui::ColorButton(stop.label, ImVec4(stop.colour[0], stop.colour[1], stop.colour[2], 1), ImGuiColorEditFlags_NoTooltip, ImVec2(14, 14));
    ImGui::SameLine();
    ImGui::TextUnformatted(stop.label);
    ImGui::SameLine();
  }
  ImGui::NewLine();
}

// The handedness views' two colours, drawn from the same table as the shader's.
void drawHandednessLegend() {
  for (const auto& [colour, label] : {std::pair{kHandednessPositive, "+1"}, std::pair{kHandednessNegative, "-1"}}) {
    ImGui::ColorButton(label, ImVec4(colour[0], colour[1], colour[2], 1), ImGuiColorEditFlags_NoTooltip, ImVec2(14, 14));
    ImGui::SameLine();
    ImGui::TextUnformatted(label);
    ImGui::SameLine();
  }
  ImGui::NewLine();
}

// The views that show the tangent frame, and so the "no tangent" colour where a corner has none
// (mesh.frag).
bool showsTangentFrame(DebugView view) {
  return view == DebugView::tangent || view == DebugView::bitangent || view == DebugView::handedness ||
         view == DebugView::handednessWorld || view == DebugView::tangentError || view == DebugView::compareAngle ||
         view == DebugView::anisotropyDirection;
}

void drawNoTangentLegend() {
  ImGui::ColorButton("no tangent", ImVec4(kNoTangent[0], kNoTangent[1], kNoTangent[2], 1), ImGuiColorEditFlags_NoTooltip, ImVec2(14, 14));
  ImGui::SameLine();
  ImGui::TextWrapped("no tangent: no TANGENT and no UVs that define one (e.g. no TEXCOORD)");
}

void drawPanel(Viewer& viewer, GLFWwindow* window, const FrameStats& stats, double frameMs, char (&openPath)[1024], bool& focusOpen) {
  RenderSettings& s = viewer.options.settings;
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(360, 640), ImGuiCond_FirstUseEver);
  ImGui::Begin("tangent-view");
  ImGui::TextWrapped("%s", viewer.loaded.string().c_str());
  if (focusOpen) {
    ImGui::SetKeyboardFocusHere();
    focusOpen = false;
  }
  if (ImGui::InputText("open (o)", openPath, sizeof openPath, ImGuiInputTextFlags_EnterReturnsTrue)) viewer.load(openPath);
  // The combo shows the demo file that is loaded, and nothing for any other file.
  int primitive = viewer.loadedDemo;
  if (ImGui::Combo("demo", &primitive, kDemoFiles, static_cast<int>(std::size(kDemoFiles))))
    viewer.load(demoFolder() / (std::string(kDemoFiles[primitive]) + ".gltf"));
  ImGui::Text("%.1f fps, %.2f ms, %zu triangles, %d draw calls", frameMs > 0 ? 1000.0 / frameMs : 0.0, frameMs, stats.triangles, stats.drawCalls);
  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
    int view = static_cast<int>(s.view);
    const char* names[std::size(kDebugViews)];
    for (std::size_t i = 0; i < std::size(kDebugViews); ++i) names[i] = kDebugViews[i].name;
    if (ImGui::Combo("view (1-9, 0)", &view, names, static_cast<int>(std::size(kDebugViews)))) s.view = static_cast<DebugView>(view);
    if (s.view == DebugView::tangentError) {
      ImGui::TextWrapped("error vs freshly computed (%s), per corner, as tangent check --all judges it; magenta: fails tangent check",
                         tangent::gltf::toString(viewer.options.reference).c_str());
      drawHeatmapLegend();
      const auto& items = viewer.renderer.scene().items;
      if (std::none_of(items.begin(), items.end(), [](const auto& item) { return item.tangentsFromFile; }))
        ImGui::TextWrapped("This file has no TANGENT: the tangents shown were computed at load, so they are compared with "
                           "themselves and the view is all blue. Bake the file to judge stored tangents.");
    }
    if (s.view == DebugView::compareAngle) {
      ImGui::TextWrapped("angle per pixel between the file's tangent frames and the compare set's (Compare below)");
      drawHeatmapLegend();
    }
    if (s.view == DebugView::faceOrientation) ImGui::TextWrapped("blue: front face, red: back face (culling off in this view)");
    if (s.view == DebugView::handedness) {
      ImGui::TextWrapped("the file's TANGENT w:");
      drawHandednessLegend();
    }
    if (s.view == DebugView::handednessWorld) {
      ImGui::TextWrapped("w in world space, after the node's mirroring (a mirrored node swaps it):");
      drawHandednessLegend();
    }
    if (s.view == DebugView::tangent || s.view == DebugView::bitangent)
      ImGui::TextWrapped("the direction in world space as colour: (x, y, z) * 0.5 + 0.5");
    if (s.view == DebugView::anisotropyDirection)
      ImGui::TextWrapped("KHR_materials_anisotropy's direction (rotation and texture in the TANGENT frame) in world space as "
                         "colour: (x, y, z) * 0.5 + 0.5; grey where the material has no anisotropy");
    if (showsTangentFrame(s.view)) drawNoTangentLegend();
    ImGui::Checkbox("tangent frames (g)", &s.glyphs);
    ImGui::SliderInt("glyph count", &s.maxGlyphs, 100, 50000);
    ImGui::Checkbox("orthographic", &viewer.camera.orthographic);
  }
  if (const auto& animations = viewer.renderer.scene().animations; !animations.empty() && ImGui::CollapsingHeader("Animation", ImGuiTreeNodeFlags_DefaultOpen)) {
    std::vector<std::string> names{"none (rest pose)"};
    for (std::size_t a = 0; a < animations.size(); ++a)
      names.push_back(std::to_string(a) + (animations[a].name.empty() ? "" : " '" + animations[a].name + "'"));
    std::vector<const char*> pointers;
    for (const auto& name : names) pointers.push_back(name.c_str());
    int chosen = viewer.pose.animation + 1;
    if (ImGui::Combo("animation", &chosen, pointers.data(), static_cast<int>(pointers.size()))) {
      viewer.pose = PoseTime{chosen - 1, 0.0f};
      viewer.playing = chosen > 0;
    }
    if (viewer.pose.animation >= 0) {
      ImGui::Checkbox("play", &viewer.playing);
      ImGui::SliderFloat("time (s)", &viewer.pose.seconds, 0.0f, std::max(animations[viewer.pose.animation].duration, 1e-3f), "%.3f");
    }
  }
  if (ImGui::CollapsingHeader("Compare", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::Checkbox("split view (c)", &s.split);
    if (s.split) ImGui::SliderFloat("divider", &s.splitPosition, 0, 1, "%.2f");
    Options& o = viewer.options;
    static char otherFile[1024] = {};
    if (!otherFile[0] && !o.compareFile.empty()) std::snprintf(otherFile, sizeof otherFile, "%s", o.compareFile.string().c_str());
    static bool secondFileChosen = o.compare == CompareSource::otherFile;  // in the combo, also before a file is named
    int source = secondFileChosen ? static_cast<int>(CompareSource::otherFile) : static_cast<int>(o.compare);
    auto compareWithFile = [&] {
      o.compare = CompareSource::otherFile;
      o.compareFile = otherFile;
      viewer.applyCompare();
    };
    if (ImGui::Combo("compare with", &source, "fresh (--reference)\0" "the file itself\0" "a second file\0")) {
      secondFileChosen = static_cast<CompareSource>(source) == CompareSource::otherFile;
      if (!secondFileChosen) {
        o.compare = static_cast<CompareSource>(source);
        viewer.applyCompare();
      } else if (otherFile[0]) {
        compareWithFile();
      }
    }
    if (secondFileChosen && ImGui::InputText("second file", otherFile, sizeof otherFile, ImGuiInputTextFlags_EnterReturnsTrue))
      compareWithFile();
    const std::string right = o.compare == CompareSource::fresh  ? tangent::gltf::toString(o.reference) + " computed at load"
                              : o.compare == CompareSource::file ? "the file's TANGENT again"
                                                                 : o.compareFile.string() + "'s TANGENT";
    ImGui::TextWrapped("left: the file's TANGENT; right (and compare-angle, key a): %s", right.c_str());
    int mode = static_cast<int>(s.bitangent);
    const char* modeNames[std::size(kBitangentModes)];
    for (std::size_t i = 0; i < std::size(kBitangentModes); ++i) modeNames[i] = kBitangentModes[i].name;
    if (ImGui::Combo("bitangent (b)", &mode, modeNames, static_cast<int>(std::size(kBitangentModes)))) s.bitangent = static_cast<BitangentMode>(mode);
  }
  if (ImGui::CollapsingHeader("Shading", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::Checkbox("normal mapping (m)", &s.normalMapping);
    ImGui::Checkbox("flip green (f)", &s.flipGreen);
    ImGui::Checkbox("specular (s)", &s.specular);
    int shading = static_cast<int>(s.shading);
    const char* shadingNames[std::size(kShadings)];
    for (std::size_t i = 0; i < std::size(kShadings); ++i) shadingNames[i] = kShadings[i].name;
    if (ImGui::Combo("shading", &shading, shadingNames, static_cast<int>(std::size(kShadings)))) s.shading = static_cast<Shading>(shading);
    if (s.shading == Shading::pbr) ImGui::TextWrapped("glTF metallic-roughness (GGX), occlusion, emissive; sRGB output");
    else ImGui::SliderFloat("shininess", &s.shininess, 1, 256);
    int toneMapping = static_cast<int>(s.toneMapping);
    const char* toneNames[std::size(kToneMappings)];
    for (std::size_t i = 0; i < std::size(kToneMappings); ++i) toneNames[i] = kToneMappings[i].name;
    if (ImGui::Combo("tone mapping", &toneMapping, toneNames, static_cast<int>(std::size(kToneMappings))))
      s.toneMapping = static_cast<ToneMapping>(toneMapping);
    bool autoExposure = s.exposure <= 0;
    if (ImGui::Checkbox("auto exposure", &autoExposure)) s.exposure = autoExposure ? 0 : viewer.renderer.exposure(s);
    if (!autoExposure) ImGui::SliderFloat("exposure", &s.exposure, 1e-4f, 1e4f, "%.4g", ImGuiSliderFlags_Logarithmic);
    else ImGui::Text("exposure %.4g%s", stats.exposure, viewer.renderer.physicalLights(s) ? " (lights in lux / candela)" : "");
    ImGui::Checkbox("depth pre-pass", &s.depthPrePass);
    ImGui::Checkbox("image-based lighting", &s.ibl);
    if (s.ibl) ImGui::SliderFloat("environment", &s.iblIntensity, 0.0f, 4.0f);
    ImGui::SliderFloat("reflectivity", &s.reflectivity, 0, 1);
    ImGui::SliderFloat("UV scale", &s.uvScale, 0.25f, 8);
  }
  if (ImGui::CollapsingHeader("Shadows")) {
    ImGui::Checkbox("shadows (h)", &s.shadows);
    ImGui::SliderInt("PCF radius (p)", &s.pcfRadius, 0, 2);
    static const int sizes[] = {1024, 2048, 4096};
    int sizeIndex = s.shadowMapSize >= 4096 ? 2 : s.shadowMapSize >= 2048 ? 1 : 0;
    if (ImGui::Combo("map size", &sizeIndex, "1024\0" "2048\0" "4096\0")) s.shadowMapSize = sizes[sizeIndex];
    ImGui::SliderFloat("constant bias", &s.shadowBiasConstant, 0, 0.01f, "%.4f");
    ImGui::SliderFloat("slope bias", &s.shadowBiasSlope, 0, 0.01f, "%.4f");
  }
  if (ImGui::CollapsingHeader("Lights")) {
    auto& lights = viewer.renderer.lights();
    for (std::size_t i = 0; i < lights.size(); ++i) {
      ImGui::PushID(static_cast<int>(i));
      Light& light = lights[i];
      ImGui::Text("light %zu: %s%s", i, light.directional ? "directional" : "positional", i == 0 ? " (casts shadows)" : "");
      if (light.directional) ImGui::SliderFloat3("direction", &light.direction.x, -1, 1);
      else ImGui::DragFloat3("position", &light.position.x, 0.05f);
      ImGui::ColorEdit3("ambient", &light.ambient.x);
      ImGui::ColorEdit3("diffuse", &light.diffuse.x);
      ImGui::ColorEdit3("specular", &light.specular.x);
      if (!light.directional) ImGui::DragFloat3("k0 k1 k2", &light.attenuation.x, 0.01f, 0, 10);
      if (light.physical) {
        ImGui::TextWrapped("in pbr: colour x intensity, %s", light.directional ? "lux" : "candela, range window");
        ImGui::ColorEdit3("colour", &light.color.x);
        ImGui::DragFloat("intensity", &light.intensity, 0.01f * std::max(light.intensity, 1.0f), 0, 1e7f);
      }
      ImGui::PopID();
    }
  }
  if (ImGui::CollapsingHeader("Tangents", ImGuiTreeNodeFlags_DefaultOpen)) {
    for (const auto& item : viewer.renderer.scene().items) {
      ImGui::TextWrapped("%s: %s, %zu corners, %llu mirrored", item.label.c_str(),
                         item.tangentsFromFile ? "file TANGENT" : "computed at load (mikktspace)", item.positions.size() / 3,
                         static_cast<unsigned long long>(item.report.mirroredCorners));
    }
  }
  if (!viewer.messages.empty() && ImGui::CollapsingHeader("Messages", ImGuiTreeNodeFlags_DefaultOpen)) {
    for (const auto& m : viewer.messages) ImGui::TextWrapped("%s", m.c_str());
  }
  ImGui::End();
  (void)window;
}

struct Input {
  Viewer* viewer = nullptr;
  bool focusOpen = false;
  PointerDrags drags;
  GLFWcursorposfun previousCursorPos = nullptr;  // the panel's, where its backend has one
};

Input& inputOf(GLFWwindow* window) { return *static_cast<Input*>(glfwGetWindowUserPointer(window)); }

int windowWidth(GLFWwindow* window) {
  int width = 0, height = 0;
  glfwGetWindowSize(window, &width, &height);
  return width;
}

// --print-state: what the keys and the mouse change, as one JSON line after each key press and
// mouse button release and when the window closes.
void printState(const Viewer& viewer, GLFWwindow* window) {
  const RenderSettings& s = viewer.options.settings;
  const OrbitCamera& c = viewer.camera;
  const nlohmann::json state = {
      {"view", kDebugViews[static_cast<int>(s.view)].name},
      {"normalMapping", s.normalMapping},
      {"specular", s.specular},
      {"shadows", s.shadows},
      {"pcfRadius", s.pcfRadius},
      {"flipGreen", s.flipGreen},
      {"glyphs", s.glyphs},
      {"split", s.split},
      {"splitPosition", s.splitPosition},
      {"bitangent", kBitangentModes[static_cast<int>(s.bitangent)].name},
      {"camera", {{"yaw", c.yaw}, {"pitch", c.pitch}, {"distance", c.distance}, {"target", {c.target.x, c.target.y, c.target.z}}}},
      {"windowWidth", windowWidth(window)},
      {"messages", viewer.messages},
  };
  std::printf("state %s\n", tangent::text::dumpJson(state).c_str());
  std::fflush(stdout);
}

int interactive(Viewer& viewer, GLFWwindow* window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  // The panel's layout file (Dear ImGui's imgui.ini in the working folder), under the input
  // rule: where it is there but not a regular file of bounded size (a FIFO would block the
  // first frame), it is neither read nor written.
  if (const char* ini = ImGui::GetIO().IniFilename; ini && fs::exists(fs::symlink_status(ini))) {
    try {
      tangent::gltf::requireInputFile(ini, "a settings file");
    } catch (const std::exception& e) {
      ImGui::GetIO().IniFilename = nullptr;
      viewer.messages.push_back(std::string(e.what()) + "; the panel's layout is neither read nor saved");
      printNote(viewer.messages.back());
    }
  }
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  Input input;
  input.viewer = &viewer;
  glfwSetWindowUserPointer(window, &input);
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int scancode, int action, int mods) {
    ImGui_ImplGlfw_KeyCallback(w, key, scancode, action, mods);
    if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
    auto& in = inputOf(w);
    RenderSettings& s = in.viewer->options.settings;
    switch (key) {
      case GLFW_KEY_M: s.normalMapping = !s.normalMapping; break;
      case GLFW_KEY_S: s.specular = !s.specular; break;
      case GLFW_KEY_H: s.shadows = !s.shadows; break;
      case GLFW_KEY_P: s.pcfRadius = s.pcfRadius == 0 ? 1 : 0; break;
      case GLFW_KEY_F: s.flipGreen = !s.flipGreen; break;
      case GLFW_KEY_G: s.glyphs = !s.glyphs; break;
      case GLFW_KEY_C: s.split = !s.split; break;
      case GLFW_KEY_A: s.view = s.view == DebugView::compareAngle ? DebugView::lit : DebugView::compareAngle; break;
      case GLFW_KEY_B:
        s.bitangent = s.bitangent == BitangentMode::perFragment ? BitangentMode::perVertex : BitangentMode::perFragment;
        break;
      case GLFW_KEY_O: in.focusOpen = true; break;
      case GLFW_KEY_R:
        in.viewer->shaders.reload();
        in.viewer->messages.push_back("shaders reloaded");
        break;
      case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
      default:
        if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9 && key - GLFW_KEY_1 < static_cast<int>(std::size(kDebugViews)))
          s.view = static_cast<DebugView>(key - GLFW_KEY_1);
        else if (key == GLFW_KEY_0 && std::size(kDebugViews) > 9) s.view = static_cast<DebugView>(9);
    }
    if (in.viewer->options.printState) printState(*in.viewer, w);
  });
  // The mouse by its events, in order (viewer/pointer.hpp says why).
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int mods) {
    ImGui_ImplGlfw_MouseButtonCallback(w, button, action, mods);
    const auto which = button == GLFW_MOUSE_BUTTON_LEFT    ? PointerDrags::Button::left
                       : button == GLFW_MOUSE_BUTTON_RIGHT ? PointerDrags::Button::right
                       : button == GLFW_MOUSE_BUTTON_MIDDLE ? PointerDrags::Button::middle
                                                            : std::optional<PointerDrags::Button>{};
    if (!which) return;
    auto& in = inputOf(w);
    in.drags.button(*which, action == GLFW_PRESS, ImGui::GetIO().WantCaptureMouse, in.viewer->options.settings, windowWidth(w));
    if (action == GLFW_RELEASE && in.viewer->options.printState) printState(*in.viewer, w);
  });
  input.previousCursorPos = glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    auto& in = inputOf(w);
    if (in.previousCursorPos) in.previousCursorPos(w, x, y);
    in.drags.move(x, y, in.viewer->camera, in.viewer->options.settings, windowWidth(w));
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double x, double y) {
    ImGui_ImplGlfw_ScrollCallback(w, x, y);
    if (ImGui::GetIO().WantCaptureMouse) return;
    inputOf(w).viewer->camera.zoom(static_cast<float>(y));
  });
  glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
    if (count > 0) inputOf(w).viewer->load(paths[0]);
  });
  double startX = 0, startY = 0;  // where the pointer is before it first moves
  glfwGetCursorPos(window, &startX, &startY);
  input.drags.move(startX, startY, viewer.camera, viewer.options.settings, windowWidth(window));

  char openPath[1024] = {};
  FrameStats stats;
  double frameMs = 0;
  while (!glfwWindowShouldClose(window)) {
    const auto start = std::chrono::steady_clock::now();
    glfwPollEvents();
    if (viewer.playing && viewer.pose.animation >= 0) {
      const float duration = viewer.renderer.scene().animations[viewer.pose.animation].duration;
      viewer.pose.seconds = duration > 0 ? std::fmod(viewer.pose.seconds + static_cast<float>(frameMs) / 1000.0f, duration) : 0.0f;
    }
    viewer.renderer.setPose(viewer.pose);
    int width, height;
    glfwGetFramebufferSize(window, &width, &height);
    if (width > 0 && height > 0) {
      try {
        stats = viewer.renderer.render(viewer.camera.matrices(float(width) / float(height)), viewer.options.settings, width, height);
      } catch (const std::exception& e) {
        viewer.messages.push_back(e.what());
        printError(e.what());
        viewer.options.settings.view = DebugView::lit;
        viewer.shaders.reload();
      }
    }
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    drawPanel(viewer, window, stats, frameMs, openPath, input.focusOpen);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    glfwSwapBuffers(window);
    frameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  if (viewer.options.printState) printState(viewer, window);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  return 0;
}
#endif  // !__EMSCRIPTEN__

}  // namespace

#ifdef __EMSCRIPTEN__
#include "web/web.inc"
#else

namespace {

// The files the command line names, under the input rule of every reader (a regular file of
// bounded size; tangent/input_file.hpp), before any window opens: a folder, a FIFO or a device
// is a clean error naming the option and the file, where it would block or be ignored. False
// after printing the error.
bool commandLineFilesReadable(const Options& options) {
  auto readable = [](const char* option, const fs::path& file) {
    try {
      tangent::gltf::requireInputFile(file, "a glTF file");
      return true;
    } catch (const std::exception& e) {
      printError(std::string(option) + ": " + e.what());
      return false;
    }
  };
  if (!options.checkShaders && !readable("input", options.input)) return false;
  if (options.compare == CompareSource::otherFile && !readable("--compare", options.compareFile)) return false;
  if (options.sphereMapGiven) {
    tangent::gltf::ImageSource sphereMap;
    sphereMap.file = options.sphereMap;
    sphereMap.label = options.sphereMap.string();
    std::string error;
    if (!checkImageFile(sphereMap, error)) {
      printError("--sphere-map: " + error);
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (const int exit = parseOptions(argc, argv, options); exit >= 0) return exit;
  if (!commandLineFilesReadable(options)) return 1;
  if (options.stats && !options.screenshot && !options.checkShaders) {
    // The scene alone: no window, no GL.
    try {
      const tangent::gltf::Scene scene = tangent::gltf::loadScene(options.input, sceneOptionsFor(options));
      for (const auto& m : scene.messages) printNote(m);
      printSceneStats(options.input, scene);
      return 0;
    } catch (const std::exception& e) {
      printError(e.what());
      return 1;
    }
  }
  glfwSetErrorCallback([](int code, const char* text) { std::cerr << "GLFW error " << code << ": " << text << "\n"; });
  if (!glfwInit()) {
    std::cerr << "error: cannot initialize GLFW (no display? run under xvfb-run)\n";
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  if (std::getenv("TANGENT_GL_DEBUG")) glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
  if (options.screenshot || options.checkShaders) glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  else glfwWindowHint(GLFW_SAMPLES, options.msaaSamples < 0 ? 4 : options.msaaSamples > 1 ? options.msaaSamples : 0);
  GLFWwindow* window = glfwCreateWindow(options.screenshot ? 64 : options.width, options.screenshot ? 64 : options.height,
                                        "tangent-view", nullptr, nullptr);
  if (!window) {
    std::cerr << "error: cannot create an OpenGL 3.3 core context\n";
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(options.screenshot ? 0 : 1);
  if (std::getenv("TANGENT_GL_DEBUG") && epoxy_has_gl_extension("GL_KHR_debug")) {
    // Every GL error and warning on stderr, with what caused it.
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback([](GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message, const void*) {
      if (severity != GL_DEBUG_SEVERITY_NOTIFICATION) std::cerr << "GL debug (type 0x" << std::hex << type << std::dec << "): " << message << "\n";
    }, nullptr);
  }
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const bool msaaGiven = options.msaaSamples >= 0;
  applyRasteriserDefaults(options, softwareRasteriser(renderer ? renderer : ""));
  if (!msaaGiven && options.msaaSamples == 0) glDisable(GL_MULTISAMPLE);  // the window's samples, unused
  int exit = 0;
  if (options.checkShaders) {
    ShaderLibrary shaders(options.shaderDir);
    int checked = 0;
    const auto problems = checkShaderInputs(shaders, checked);
    for (const auto& problem : problems) printError(problem);
    std::printf("%d programs linked, vertex inputs %s the layout tables\n", checked, problems.empty() ? "agree with" : "DISAGREE with");
    exit = problems.empty() ? 0 : 1;
  } else {
    Viewer viewer(options);
    const bool loaded = viewer.load(options.input);
    if (options.screenshot) exit = loaded ? screenshot(viewer) : 1;
    else exit = interactive(viewer, window);
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return exit;
}
#endif  // !__EMSCRIPTEN__
