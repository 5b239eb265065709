// SPDX-License-Identifier: MIT
// The Dear ImGui panel of the desktop viewer: views, lights, shadows, exposure, animation, the
// file's notes, with the legends of the debug views.
#include "gl_platform.hpp"  // before GLFW: epoxy (or GLES3 on the web) provides the GL declarations
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

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

namespace {

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
         view == DebugView::anisotropyDirection || view == DebugView::clearcoatNormal;
}

void drawNoTangentLegend() {
  ImGui::ColorButton("no tangent", ImVec4(kNoTangent[0], kNoTangent[1], kNoTangent[2], 1), ImGuiColorEditFlags_NoTooltip, ImVec2(14, 14));
  ImGui::SameLine();
  ImGui::TextWrapped("no tangent: no TANGENT and no UVs that define one (e.g. no TEXCOORD)");
}

}  // namespace

namespace {

// The panel's section: the view, its legend and notes, glyphs, projection.
void panelView(Viewer& viewer, RenderSettings& s) {
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
  if (s.view == DebugView::clearcoatNormal)
    ImGui::TextWrapped("KHR_materials_clearcoat's normal (its normal map, on its own UVs, through the TANGENT frame) in world "
                       "space as colour: (x, y, z) * 0.5 + 0.5; grey where the material has no coat");
  if (showsTangentFrame(s.view)) drawNoTangentLegend();
  ImGui::Checkbox("tangent frames (g)", &s.glyphs);
  ImGui::SliderInt("glyph count", &s.maxGlyphs, 100, 50000);
  ImGui::Checkbox("orthographic", &viewer.camera.orthographic);
}

// The panel's section: the animation and its time.
void panelAnimation(Viewer& viewer, const std::vector<tangent::gltf::Animation>& animations) {
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

// The panel's section: the split view's compare set and the bitangent mode.
void panelCompare(Viewer& viewer, RenderSettings& s) {
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

// The panel's section: normal map, specular, shading model, tone mapping, exposure, IBL.
void panelShading(Viewer& viewer, RenderSettings& s, const FrameStats& stats) {
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

// The panel's section: shadows, PCF, map size, biases.
void panelShadows(RenderSettings& s) {
  ImGui::Checkbox("shadows (h)", &s.shadows);
  ImGui::SliderInt("PCF radius (p)", &s.pcfRadius, 0, 2);
  static const int sizes[] = {1024, 2048, 4096};
  int sizeIndex = s.shadowMapSize >= 4096 ? 2 : s.shadowMapSize >= 2048 ? 1 : 0;
  if (ImGui::Combo("map size", &sizeIndex, "1024\0" "2048\0" "4096\0")) s.shadowMapSize = sizes[sizeIndex];
  ImGui::SliderFloat("constant bias", &s.shadowBiasConstant, 0, 0.01f, "%.4f");
  ImGui::SliderFloat("slope bias", &s.shadowBiasSlope, 0, 0.01f, "%.4f");
}

// The panel's section: each light's colours, direction or position, attenuation, intensity.
void panelLights(Viewer& viewer) {
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

// The panel's section: where each primitive's tangents come from.
void panelTangents(const Viewer& viewer) {
  for (const auto& item : viewer.renderer.scene().items) {
    ImGui::TextWrapped("%s: %s, %zu corners, %llu mirrored", item.label.c_str(),
                       item.tangentsFromFile ? "file TANGENT" : "computed at load (mikktspace)", item.positions.size() / 3,
                       static_cast<unsigned long long>(item.report.mirroredCorners));
  }
}

// The panel's section: the file's notes.
void panelMessages(const Viewer& viewer) {
  for (const auto& m : viewer.messages) ImGui::TextWrapped("%s", m.c_str());
}

}  // namespace

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
  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) panelView(viewer, s);
  if (const auto& animations = viewer.renderer.scene().animations;
      !animations.empty() && ImGui::CollapsingHeader("Animation", ImGuiTreeNodeFlags_DefaultOpen))
    panelAnimation(viewer, animations);
  if (ImGui::CollapsingHeader("Compare", ImGuiTreeNodeFlags_DefaultOpen)) panelCompare(viewer, s);
  if (ImGui::CollapsingHeader("Shading", ImGuiTreeNodeFlags_DefaultOpen)) panelShading(viewer, s, stats);
  if (ImGui::CollapsingHeader("Shadows")) panelShadows(s);
  if (ImGui::CollapsingHeader("Lights")) panelLights(viewer);
  if (ImGui::CollapsingHeader("Tangents", ImGuiTreeNodeFlags_DefaultOpen)) panelTangents(viewer);
  if (!viewer.messages.empty() && ImGui::CollapsingHeader("Messages", ImGuiTreeNodeFlags_DefaultOpen)) panelMessages(viewer);
  ImGui::End();
  (void)window;
}

}  // namespace tangent::viewer::app
