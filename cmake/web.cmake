# SPDX-License-Identifier: MIT
# The web build (emcmake cmake, scripts/web.sh): stand-ins for the find_package() targets of
# the native build. Debian ships its header-only dependencies for every compiler; they are
# reached through one folder of links (not /usr/include, whose C library headers would shadow
# emscripten's). tinygltf, whose Debian package is a compiled library, is compiled from its
# header (viewer/web/tinygltf.cpp); oneTBB is left out (TANGENT_SERIAL: each
# include of it is behind that define). Draco and meshoptimizer are native libraries only: the
# glTF layer's decoders that need them are swapped for stand-ins that refuse such files
# (libtangent/CMakeLists.txt, libtangent/gltf/src/read/compression_web.cpp). The core is
# arrays-only and OBJ, PLY and OFF are read by our own readers, so every method (lengyel and
# flat too) and every input format but compressed glTF links and runs. README.md lists what is left out.
set(web_include ${PROJECT_BINARY_DIR}/web-include)
file(MAKE_DIRECTORY ${web_include}/stb)
foreach(entry nlohmann glm tiny_gltf.h stb/stb_image.h stb/stb_image_write.h stb/stb_image_resize.h)
  get_filename_component(name ${entry} NAME)
  if(NOT EXISTS /usr/include/${entry})
    message(FATAL_ERROR "web build: /usr/include/${entry} is missing (scripts/install-deps.sh installs it)")
  endif()
  file(CREATE_LINK /usr/include/${entry} ${web_include}/${name} SYMBOLIC)
endforeach()
add_library(tangent_web_headers INTERFACE)
target_include_directories(tangent_web_headers SYSTEM INTERFACE ${web_include} ${PROJECT_SOURCE_DIR}/viewer/web/include)
target_compile_definitions(tangent_web_headers INTERFACE TANGENT_SERIAL)
foreach(target TBB::tbb TinyGLTF::TinyGLTF nlohmann_json::nlohmann_json glm::glm draco::draco
               meshoptimizer::meshoptimizer)
  add_library(${target} INTERFACE IMPORTED)
  set_target_properties(${target} PROPERTIES INTERFACE_LINK_LIBRARIES tangent_web_headers)
endforeach()
add_compile_options(-fexceptions)
add_link_options(-fexceptions)
add_compile_options("SHELL:-include ${PROJECT_SOURCE_DIR}/viewer/web/include/tangent_web_compat.hpp")
