// SPDX-License-Identifier: MIT
// --screenshot: frames rendered offscreen, the last one read back and written as PNG.
#include "gl_platform.hpp"  // before GLFW: epoxy (or GLES3 on the web) provides the GL declarations
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

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
              "call(s), %d mesh upload(s), exposure %.4g, median frame %.2f ms (CPU %.2f ms) over %d frame(s)\n",
              shown(o.screenshot->string()).c_str(), o.width, o.height, std::max(samples, 1), stats.triangles, stats.drawCalls,
              viewer.shaders.variantsCompiled(), viewer.renderer.shadowPasses(), shadowDrawCalls, viewer.renderer.meshUploads(), stats.exposure,
              milliseconds[milliseconds.size() / 2],
              cpuMilliseconds[cpuMilliseconds.size() / 2], o.frames);
  if (viewer.renderer.environmentMilliseconds() > 0)
    std::printf("image-based lighting prepared in %.1f ms\n", viewer.renderer.environmentMilliseconds());
  return 0;
}

}  // namespace tangent::viewer::app
