// SPDX-License-Identifier: MIT
// `tangent check --format html`: a page a reviewer opens from a CI artefact. Self-contained:
// the style is inline, thumbnails are data: PNGs, and the one link is relative (to a web viewer
// deployed beside the report), so nothing reaches the network. Thumbnails come from
// `tangent-view --screenshot` (error view, camera on the triangles the viewer's loader flags),
// run under xvfb-run where there is no display.
#include "check_html.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>
#include <sstream>
#include <tuple>

#include "check_names.hpp"
#include "tangent/framing.hpp"
#include "tangent/scene.hpp"
#include "tangent/text.hpp"

extern char** environ;

namespace tangent::cli {
namespace {

namespace fs = std::filesystem;

constexpr int kThumbnailWidth = 320, kThumbnailHeight = 240;
constexpr std::size_t kMaxThumbnails = 40;          // rendering one takes about a second
constexpr const char* kThumbnailTimeLimit = "120";  // seconds (coreutils' timeout): a hung viewer must not hang CI

// Text and attribute values: file-derived bytes through terminalSafe (valid UTF-8, control
// characters as \xHH), then the five markup characters as references.
std::string html(std::string_view raw) {
  std::string out;
  for (char c : text::terminalSafe(raw)) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string base64(std::string_view bytes) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? alphabet[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// Width and height from a PNG's IHDR chunk (PNG 1.2, 11.2.2); nullopt when it is no PNG.
std::optional<std::pair<std::uint32_t, std::uint32_t>> pngSize(const std::string& png) {
  static const std::string signature = "\x89PNG\r\n\x1a\n";
  if (png.size() < 24 || png.compare(0, 8, signature) != 0 || png.compare(12, 4, "IHDR") != 0) return std::nullopt;
  auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 4; ++k) v = v << 8 | static_cast<unsigned char>(png[at + k]);
    return v;
  };
  return std::pair{be32(16), be32(20)};
}

bool isExecutable(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec) && ::access(path.c_str(), X_OK) == 0;
}

std::optional<fs::path> onPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path ? path : "");
  for (std::string folder; std::getline(folders, folder, ':');) {
    if (!folder.empty() && isExecutable(fs::path(folder) / name)) return fs::path(folder) / name;
  }
  return std::nullopt;
}

// How thumbnails get rendered: the command line before the viewer's own arguments, or why not.
struct Renderer {
  std::vector<std::string> prefix;  // [xvfb-run -a -s ...] tangent-view
  std::string unavailable;          // why there are no thumbnails ("" when there are)
};

// tangent-view: $TANGENT_VIEW (empty: thumbnails off), else beside this `tangent`, else on PATH.
// A display: $DISPLAY, else xvfb-run.
Renderer findRenderer() {
  Renderer renderer;
  fs::path viewer;
  if (const char* chosen = std::getenv("TANGENT_VIEW")) {
    if (*chosen == '\0') return {{}, "thumbnails are turned off (TANGENT_VIEW is set and empty)"};
    viewer = chosen;
    if (!isExecutable(viewer)) return {{}, "TANGENT_VIEW=" + viewer.string() + " is not an executable file"};
  } else {
    std::error_code ec;
    const fs::path beside = fs::read_symlink("/proc/self/exe", ec).parent_path() / "tangent-view";
    if (!ec && isExecutable(beside))
      viewer = beside;
    else if (const auto found = onPath("tangent-view"))
      viewer = *found;
    else
      return {{},
              "tangent-view was found neither beside tangent" +
                  (ec ? std::string() : " (" + beside.parent_path().string() + ")") +
                  " nor on PATH (set TANGENT_VIEW to its path)"};
  }
  if (const auto timeout = onPath("timeout")) renderer.prefix = {timeout->string(), kThumbnailTimeLimit};
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display) {
    const auto xvfbRun = onPath("xvfb-run");
    if (!xvfbRun) return {{}, "no display: DISPLAY is unset and xvfb-run is not installed (Debian package xvfb)"};
    renderer.prefix.insert(renderer.prefix.end(), {xvfbRun->string(), "-a", "-s", "-screen 0 1280x1024x24"});
  }
  renderer.prefix.push_back(viewer.string());
  return renderer;
}

// Runs `argv` with standard output and error into `log`; the exit status, -1 when it did not start.
int runLogged(const std::vector<std::string>& argv, const fs::path& log) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The last non-empty line of a log: what a failed render says about itself.
std::string lastLine(const std::string& log) {
  std::string last, line;
  std::istringstream lines(log);
  while (std::getline(lines, line)) {
    if (!line.empty()) last = line;
  }
  return last.empty() ? "no message" : last;
}

// A folder for the renders, removed with everything in it.
struct ScratchFolder {
  fs::path path;
  ScratchFolder() {
    std::random_device random;
    path = fs::temp_directory_path() /
           ("tangent-check-html-" + std::to_string(::getpid()) + "-" + std::to_string(random()));
    fs::create_directories(path);
  }
  ~ScratchFolder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
};

using Vec3 = std::array<float, 3>;

struct Thumbnail {
  std::string png;  // empty when there is none
  std::uint32_t width = 0, height = 0;
  std::string caption;  // how it was framed
  std::string missing;  // why there is none
};

std::string numberList(const Vec3& lo, const Vec3& hi) {
  char text[256];
  std::snprintf(text, sizeof text, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  return text;
}

// The file's scene judged as check judged it (the flagged triangles are those of its
// findings), or nothing and why the viewer's loader refuses it.
std::optional<gltf::Scene> judgedScene(const gltf::FileCheck& file, const gltf::CheckOptions& options, std::string& error) {
  try {
    gltf::SceneOptions sceneOptions;
    sceneOptions.check = options;
    sceneOptions.assetRoot = options.assetRoot;
    return gltf::loadScene(file.file, sceneOptions);
  } catch (const std::exception& e) {
    error = std::string("the viewer's loader refuses the file: ") + e.what();
    return std::nullopt;
  }
}

// The camera box on a primitive's flagged triangles, as its first instance places them, or
// nothing and why.
std::optional<gltf::Framing> framePrimitive(const gltf::Scene& scene, const gltf::PrimitiveCheck& p, std::string& missing) {
  std::optional<std::size_t> item;
  for (std::size_t k = 0; k < scene.items.size() && !item; ++k)
    if (scene.items[k].primitive == gltf::PrimitiveIndex{p.mesh, p.primitive}) item = k;
  const auto instance = std::find_if(scene.instances.begin(), scene.instances.end(),
                                     [&](const gltf::DrawInstance& d) { return item && d.item == *item; });
  if (!item || instance == scene.instances.end()) {
    missing = "no node of the scene shows this primitive";
    return std::nullopt;
  }
  const gltf::DrawItem& shown = scene.items[*item];
  std::optional<gltf::Framing> framing = gltf::frameTriangles(shown, instance->world, gltf::flaggedTriangles(shown, std::nullopt));
  if (!framing) missing = "the primitive has no finite position to frame";
  return framing;
}

// tangent-view's error view of the file framed on `framing`, as thumbnail `number` of the
// scratch folder; without a PNG, why.
Thumbnail renderThumbnail(const gltf::FileCheck& file, const gltf::CheckOptions& options, const Renderer& renderer,
                          const ScratchFolder& scratch, const gltf::Framing& framing, std::size_t number) {
  Thumbnail thumbnail;
  const fs::path png = scratch.path / ("thumbnail-" + std::to_string(number) + ".png");
  const fs::path log = scratch.path / ("thumbnail-" + std::to_string(number) + ".log");
  std::vector<std::string> command = renderer.prefix;
  for (const std::string& arg :
       {fs::absolute(file.file).string(), std::string("--screenshot"), png.string(), std::string("--size"),
        std::to_string(kThumbnailWidth) + "x" + std::to_string(kThumbnailHeight), std::string("--view"),
        std::string("error"), std::string("--camera"), framing.camera, std::string("--frame-box"),
        numberList(framing.lo, framing.hi), std::string("--no-shadows"), std::string("--reference"),
        gltf::toString(gltf::Generator{options.method, options.weighting})})
    command.push_back(arg);
  if (!options.assetRoot.empty()) command.insert(command.end(), {"--asset-root", options.assetRoot.string()});
  const int status = runLogged(command, log);
  thumbnail.png = status == 0 ? readFile(png) : std::string();
  const auto size = pngSize(thumbnail.png);
  if (!size) {
    thumbnail.png.clear();
    thumbnail.missing =
        status < 0 ? "tangent-view could not be started"
                   : "tangent-view failed (exit status " + std::to_string(status) + "): " + lastLine(readFile(log));
    return thumbnail;
  }
  std::tie(thumbnail.width, thumbnail.height) = *size;
  thumbnail.caption = "error view, " + framing.camera + " camera, framed on " +
                      (framing.flaggedTriangles ? std::to_string(framing.flaggedTriangles) + " flagged triangle(s)"
                                                : "the primitive");
  return thumbnail;
}

// Thumbnails of one file's failing primitives, in the order of file.primitives (empty entries
// for passing ones). `budget` counts down the report's thumbnails.
std::vector<Thumbnail> renderFile(const gltf::FileCheck& file, const gltf::CheckOptions& options,
                                  const Renderer& renderer, const ScratchFolder* scratch, std::size_t& budget) {
  std::vector<Thumbnail> thumbnails(file.primitives.size());
  const bool anyFailing =
      std::any_of(file.primitives.begin(), file.primitives.end(), [](const auto& p) { return !p.findings.empty(); });
  if (!anyFailing) return thumbnails;
  std::optional<gltf::Scene> scene;
  std::string sceneError;
  if (renderer.unavailable.empty()) scene = judgedScene(file, options, sceneError);
  for (std::size_t i = 0; i < file.primitives.size(); ++i) {
    const gltf::PrimitiveCheck& p = file.primitives[i];
    Thumbnail& thumbnail = thumbnails[i];
    if (p.findings.empty()) continue;
    if (!renderer.unavailable.empty() || !scratch) {
      thumbnail.missing = renderer.unavailable;
      continue;
    }
    if (!scene) {
      thumbnail.missing = sceneError;
      continue;
    }
    if (budget == 0) {
      thumbnail.missing =
          "the report has its first " + std::to_string(kMaxThumbnails) + " thumbnails; this one is left out";
      continue;
    }
    const std::optional<gltf::Framing> framing = framePrimitive(*scene, p, thumbnail.missing);
    if (!framing) continue;
    --budget;
    thumbnail = renderThumbnail(file, options, renderer, *scratch, *framing, budget);
  }
  return thumbnails;
}

// The web viewer's link for a file: build-web/index.html beside the report, the file's path
// relative to build-web/; "" when the file has no path relative to it.
std::string webViewerLink(const std::string& file, const fs::path& reportFolder) {
  std::error_code ec;
  const fs::path asset = fs::weakly_canonical(fs::absolute(file), ec);
  if (ec) return "";
  const fs::path relative = asset.lexically_relative(reportFolder / "build-web");
  if (relative.empty()) return "";
  return "build-web/index.html?url=" + text::uriQueryValue(relative.generic_string()) + "&view=error";
}

const char* kStyle =
    "body{font:14px/1.45 system-ui,sans-serif;margin:1.5rem auto;max-width:72rem;padding:0 1rem;color:#222}"
    "h1{font-size:1.5rem}h2{font-size:1.15rem;margin-top:2rem;border-bottom:1px solid #ccc;word-break:break-all}"
    "h3{font-size:1rem;margin:1rem 0 .4rem}.ok{color:#176f2c}.fail{color:#b3261e}.note{color:#666}"
    "table{border-collapse:collapse;margin:.3rem 0}td,th{border:1px solid #ddd;padding:.2rem "
    ".45rem;text-align:left;vertical-align:top}"
    "td.n{text-align:right;font-variant-numeric:tabular-nums}figure{float:right;margin:0 0 .5rem 1rem}"
    "figure img{border:1px solid #999;display:block}figcaption{font-size:12px;color:#666;max-width:320px}"
    ".primitive{overflow:auto;border-left:3px solid #ddd;padding-left:.8rem;margin:.6rem 0}"
    ".primitive.failing{border-color:#b3261e}pre{white-space:pre-wrap;margin:0;font-size:12px}";

void writePrimitive(std::ostream& out, const gltf::PrimitiveCheck& p, const Thumbnail& thumbnail,
                    const std::string& link) {
  const bool failing = !p.findings.empty();
  out << "<div class=\"primitive" << (failing ? " failing" : "") << "\">\n<h3>" << html(primitiveName(p))
      << " <span class=\"note\">(TEXCOORD_" << p.texCoord << ", " << p.vertices << " vertices, " << p.triangles
      << " triangles)</span> "
      << (failing ? "<span class=\"fail\">" + std::to_string(p.findings.size()) + " finding(s)</span>"
                  : std::string("<span class=\"ok\">ok</span>"))
      << "</h3>\n";
  if (failing) {
    out << "<figure>";
    if (!thumbnail.png.empty())
      out << "<img alt=\"" << html("error view of " + primitiveName(p)) << "\" width=\"" << thumbnail.width
          << "\" height=\"" << thumbnail.height << "\" src=\"data:image/png;base64," << base64(thumbnail.png) << "\">";
    out << "<figcaption>" << html(thumbnail.png.empty() ? "no thumbnail: " + thumbnail.missing : thumbnail.caption);
    if (!link.empty()) out << "<br><a href=\"" << html(link) << "\">open in the web viewer</a>";
    out << "</figcaption></figure>\n";
    out << "<table><tr><th>check</th><th>failed</th><th>what</th><th>worst</th></tr>\n";
    for (const auto& f : p.findings) {
      out << "<tr><td class=\"fail\">" << html(f.check) << "</td><td class=\"n\">"
          << html(findingSummary(f).substr(0, findingSummary(f).find(": "))) << "</td><td>" << html(f.message)
          << "</td><td><pre>";
      for (const auto& s : f.worst) out << html(s.detail) << "\n";
      out << "</pre></td></tr>\n";
    }
    out << "</table>\n";
  }
  auto list = [&](const char* label, const std::vector<std::string>& names) {
    if (names.empty()) return;
    out << "<p class=\"note\">" << label << ":";
    for (const auto& name : names) out << " " << html(name);
    out << "</p>\n";
  };
  list("passed", p.passed);
  list("not run (an earlier check failed)", p.notRun);
  list("ignored", p.ignored);
  for (const auto& warning : p.warnings) out << "<p>warning: " << html(warning) << "</p>\n";
  if (!p.generator.empty()) out << "<p class=\"note\">generator: " << html(p.generator) << "</p>\n";
  if (p.referenceUnresolved)
    out << "<p class=\"note\">" << p.referenceUnresolved
        << " corners have a UV orientation their rounded positions/UVs leave open; not compared</p>\n";
  if (p.handednessUndecided || p.referenceWUndecided)
    out << "<p class=\"note\">" << p.handednessUndecided
        << " triangles have a UV orientation their rounded positions/UVs leave open: handedness "
        << "skips them, reference compares the angle but not w at their " << p.referenceWUndecided << " corners</p>\n";
  if (p.referenceUndefined)
    out << "<p class=\"note\">" << p.referenceUndefined
        << " corners have no defined reference frame; not compared</p>\n";
  out << "</div>\n";
}

}  // namespace

std::string htmlReport(const std::vector<gltf::FileCheck>& checks, const gltf::CheckOptions& options,
                       const std::string& reportPath) {
  std::size_t primitives = 0, failing = 0, findings = 0, unreadable = 0;
  for (const auto& file : checks) {
    unreadable += !file.error.empty();
    primitives += file.primitives.size();
    for (const auto& p : file.primitives) failing += !p.findings.empty(), findings += p.findings.size();
  }
  const Renderer renderer = failing ? findRenderer() : Renderer{};
  std::optional<ScratchFolder> scratch;
  if (failing && renderer.unavailable.empty()) scratch.emplace();
  const fs::path reportFolder =
      reportPath == "-" ? fs::current_path() : fs::weakly_canonical(fs::absolute(reportPath)).parent_path();
  std::size_t budget = kMaxThumbnails;

  std::ostringstream body;
  for (std::size_t i = 0; i < checks.size(); ++i) {
    const gltf::FileCheck& file = checks[i];
    body << "<section id=\"file-" << i << "\">\n<h2>" << html(file.file) << "</h2>\n";
    if (!file.error.empty()) {
      body << "<p class=\"fail\">unreadable: " << html(file.error) << "</p>\n</section>\n";
      continue;
    }
    const std::vector<Thumbnail> thumbnails =
        renderFile(file, options, renderer, scratch ? &*scratch : nullptr, budget);
    const std::string link = webViewerLink(file.file, reportFolder);
    for (std::size_t k = 0; k < file.primitives.size(); ++k)
      writePrimitive(body, file.primitives[k], thumbnails[k], link);
    for (const auto& s : file.skipped) body << "<p class=\"note\">skipped " << html(s) << "</p>\n";
    if (file.primitives.empty() && file.skipped.empty()) body << "<p class=\"note\">no primitive needs tangents</p>\n";
    body << "</section>\n";
  }

  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>tangent check: " << findings
      << " finding(s)</title>\n"
      << "<style>" << kStyle << "</style>\n</head>\n<body>\n<h1>tangent check</h1>\n<p class=\""
      << (findings || unreadable ? "fail" : "ok") << "\">" << checks.size() << " file(s), " << primitives
      << " primitive(s) checked, " << failing << " with findings, " << findings << " finding(s)"
      << (unreadable ? ", " + std::to_string(unreadable) + " unreadable" : "") << "</p>\n<p class=\"note\">method "
      << html(toString(options.method)) << ", tolerance orthogonal " << options.orthogonalToleranceDegrees
      << " deg, reference " << options.referenceToleranceDegrees << " deg, min coverage " << options.minCoverage;
  if (!options.configFile.empty()) out << ", settings from " << html(options.configFile);
  out << ".</p>\n";
  if (failing) {
    out << "<p class=\"note\">"
        << html(renderer.unavailable.empty()
                    ? "Thumbnails: tangent-view's error view (the angle to freshly computed tangents: blue 0 deg, "
                      "green 1, yellow 5, red 20 or more; corners that fail the checks magenta), the camera "
                      "framed on the triangles it flags."
                    : "No thumbnails: " + renderer.unavailable + ".")
        << " The links open a file in the web viewer when this report sits beside a deployed build-web/ "
           "(scripts/web.sh).</p>\n";
  }
  out << body.str() << "</body>\n</html>\n";
  return out.str();
}

}  // namespace tangent::cli
