// SPDX-License-Identifier: MIT
// The families of data tangent-make-data writes, one file each; each writes into `dir` (made if
// missing) and returns the process's exit code (1: a texture could not be written).
#pragma once

#include <filesystem>

namespace make_data {

// demo_data.cpp: the bundled demo data (data/demo/).
int writeDemoData(const std::filesystem::path& dir);
// animated.cpp (--animated): skinned.gltf and morphing.gltf, each with a "bend" animation.
int writeAnimated(const std::filesystem::path& dir);
// material_scenes.cpp (--materials): anisotropy_disc, clearcoat_sphere and vertex_colors.gltf.
int writeMaterialScenes(const std::filesystem::path& dir);
// benchmark_sphere.cpp (--sphere N): sphere-N.gltf; 2 where `segments` is outside 3..4000.
int writeBenchmarkSphere(int segments, const std::filesystem::path& dir, bool onePrimitive);

}  // namespace make_data
