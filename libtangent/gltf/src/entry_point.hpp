// SPDX-License-Identifier: MIT
// The one translation of failures at the public entry points of the glTF layer (bakeFile,
// describeFile, checkFile, loadScene). Code below them throws what it meets: InputError with
// a message naming file and element, nlohmann's JSON exceptions where a document has a shape
// validation did not foresee, std::invalid_argument / std::out_of_range from a number
// conversion. An entry point runs its work through throwingInputError() and its callers see
// InputError alone for bad input.
#pragma once

#include <filesystem>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "tangent/gltf.hpp"

namespace tangent::gltf::detail {

template <typename Work>
auto throwingInputError(const std::filesystem::path& input, Work&& work) -> decltype(std::forward<Work>(work)()) {
  try {
    return std::forward<Work>(work)();
  } catch (const InputError&) {
    throw;
  } catch (const nlohmann::json::exception& e) {
    // A document shape validateDocument() did not foresee: an input error, never a crash.
    throw InputError(input.string(), "", std::string("unexpected glTF structure: ") + e.what());
  } catch (const std::logic_error& e) {
    // A conversion (stoi and the like) or a size the input drove out of range.
    throw InputError(input.string(), "", std::string("malformed input: ") + e.what());
  } catch (const std::bad_alloc&) {
    // Loading bounds what a file can make us allocate (kImpliedValuesFree and the byte
    // checks); what is left is a file too big for this machine's memory, named as such.
    throw InputError(input.string(), "", "out of memory: the file needs more memory than this process could get");
  }
}

}  // namespace tangent::gltf::detail
