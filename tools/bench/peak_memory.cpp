// SPDX-License-Identifier: MIT
#include "peak_memory.hpp"

#include <fstream>
#include <sstream>
#include <string>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace tangent::bench {

namespace {

// A field of /proc/self/status in bytes ("VmRSS", "VmHWM": kB there), or nullopt.
std::optional<std::size_t> statusBytes(const std::string& field) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.compare(0, field.size() + 1, field + ":") != 0) continue;
    std::istringstream value(line.substr(field.size() + 1));
    std::size_t kib = 0;
    if (value >> kib) return kib * 1024;
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::size_t> peakResidentGrowth(const std::function<void()>& work) {
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer's allocator keeps freed blocks in quarantine and pads every block: the
  // resident set says nothing about what the work itself needs.
  work();
  return std::nullopt;
#else
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
  bool reset = false;
  {
    std::ofstream clearRefs("/proc/self/clear_refs");
    reset = static_cast<bool>(clearRefs << "5" << std::flush);  // 5: the peak (VmHWM) set to the resident set now
  }
  const std::optional<std::size_t> before = statusBytes("VmRSS");
  work();
  const std::optional<std::size_t> peak = statusBytes("VmHWM");
  if (!reset || !before || !peak) return std::nullopt;
  return *peak > *before ? *peak - *before : 0;
#endif
}

}  // namespace tangent::bench
