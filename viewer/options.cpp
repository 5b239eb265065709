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

}  // namespace

const char* const kDemoFiles[] = {"scene", "quad", "cube", "sphere", "torus"};
const fs::path& demoFolder() {
  static const fs::path folder = resourceFolder("data") / "demo";
  return folder;
}

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
