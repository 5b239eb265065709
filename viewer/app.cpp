// SPDX-License-Identifier: MIT
// The loaded asset: the scene, its pose, the comparison set and the sphere map (Viewer).

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

// The pose the options ask for: --animation and --time, else the rest pose. False (with a
// message) for an animation the file does not have.
bool Viewer::choosePose() {
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
bool Viewer::applyCompare() {
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

bool Viewer::load(const fs::path& file) {
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

}  // namespace tangent::viewer::app
