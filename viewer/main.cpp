// SPDX-License-Identifier: MIT
// tangent-view: shows a glTF asset with shadowed normal and specular mapping and the views that
// validate its tangent frames; renders headless screenshots for tests and reports. This file:
// the window, its event loop and main(); the rest of the program is in the files app.hpp names.
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

#include "app.hpp"
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
using namespace tangent::viewer;
using namespace tangent::viewer::app;

namespace {

#ifndef __EMSCRIPTEN__
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

// A key: the panel's first (where it has the keyboard), then the toggles and views the help
// lists.
void onKey(GLFWwindow* w, int key, int scancode, int action, int mods) {
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
    case GLFW_KEY_D:
      s.view = s.view == DebugView::anisotropyDirection ? DebugView::lit : DebugView::anisotropyDirection;
      break;
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
}

// Pointer and keys: the panel's backend first, then the camera, the divider and the keys.
void installInputCallbacks(GLFWwindow* window, Input& input) {
  glfwSetWindowUserPointer(window, &input);
  glfwSetKeyCallback(window, onKey);
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
}

// The panel's context; its layout file (Dear ImGui's imgui.ini in the working folder) under the
// input rule: where it is there but not a regular file of bounded size (a FIFO would block the
// first frame), it is neither read nor written.
void startPanel(Viewer& viewer, GLFWwindow* window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
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
}

int interactive(Viewer& viewer, GLFWwindow* window) {
  startPanel(viewer, window);
  Input input;
  input.viewer = &viewer;
  installInputCallbacks(window, input);
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
