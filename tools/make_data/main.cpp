// SPDX-License-Identifier: MIT
// Generates the bundled demo asset in data/demo/: a UV sphere, two quads with a mirrored UV
// island, and a ground plane without a normal map, plus the bump normal map they use; the
// viewer's demo scene and primitives. On request (not committed): a skinned and a morphing
// asset, animated, for the README's images, a textured sphere for benchmarks, and the material
// scenes whose features read the tangent frame (anisotropy, clearcoat) or COLOR_0.
// Usage: tangent-make-data OUT_DIR | --animated OUT_DIR | --materials OUT_DIR | --sphere N OUT_DIR [--one-primitive]
// One file per family of data (families.hpp); shapes, textures and the glTF writer beneath them.
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>

#include "families.hpp"

namespace {

int run(int argc, char** argv) {
  if ((argc == 4 || (argc == 5 && std::string(argv[4]) == "--one-primitive")) && std::string(argv[1]) == "--sphere")
    return make_data::writeBenchmarkSphere(std::atoi(argv[2]), argv[3], argc == 5);
  if (argc == 3 && std::string(argv[1]) == "--materials") return make_data::writeMaterialScenes(argv[2]);
  if (argc == 3 && std::string(argv[1]) == "--animated") return make_data::writeAnimated(argv[2]);
  const char* usage =
      "usage: tangent-make-data OUT_DIR              the bundled demo data\n"
      "       tangent-make-data --animated OUT_DIR   a skinned and a morphing asset with a \"bend\" animation\n"
      "       tangent-make-data --materials OUT_DIR  an anisotropic brushed disc, a clearcoat sphere (its normal map on\n"
      "                                              TEXCOORD_1, rotated) and a vertex-coloured grid\n"
      "       tangent-make-data --sphere N OUT_DIR [--one-primitive]\n"
      "                                              a textured N x N UV sphere for benchmarks (split into\n"
      "                                              uint16-indexed meshes, or one uint32-indexed primitive)\n";
  // An argument that starts with '-' is an option, never the output folder ("--help" was
  // taken for one, and the data written into a folder named --help).
  if (argc == 2 && (std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help")) {
    std::cout << usage;
    return 0;
  }
  if (argc != 2 || argv[1][0] == '-') {
    if (argc == 2)
      std::cerr << "tangent-make-data: unknown option " << argv[1] << " (a folder starting with '-': write ./"
                << argv[1] << ")\n";
    std::cerr << usage;
    return 2;
  }
  return make_data::writeDemoData(argv[1]);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {  // a file that could not be written, named
    std::cerr << "tangent-make-data: " << e.what() << "\n";
    return 1;
  }
}
