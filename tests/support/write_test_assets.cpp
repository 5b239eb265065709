// SPDX-License-Identifier: MIT
// tangent-test-assets OUT_DIR: writes every generated test asset as .gltf and as .glb.
#include <iostream>

#include "test_assets.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: tangent-test-assets OUT_DIR\n";
    return 2;
  }
  for (const auto& asset : tangent::testing::makeTestAssets()) {
    std::cout << tangent::testing::writeAsset(asset, argv[1], false).string() << "\n";
    std::cout << tangent::testing::writeAsset(asset, argv[1], true).string() << "\n";
  }
  return 0;
}
