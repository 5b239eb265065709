// SPDX-License-Identifier: MIT
// How much resident memory a piece of work adds to the process at its peak: what `tangent
// bench` reports per triangle for the library and the peers alike (their own scratch, which
// none of them reports the same way). Linux only: the kernel's high-water mark of the resident
// set (VmHWM) is reset before the work (/proc/self/clear_refs, "5") and read after it.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>

namespace tangent::bench {

// The peak resident set during `work` less the resident set just before it, in bytes (0 where
// the work took nothing new). The heap's free pages are given back first (glibc's malloc_trim),
// so that what the work allocates is fresh memory, as in a new process, rather than pages an
// earlier call freed and the heap kept. nullopt, with `work` still run, where the system does
// not say (not Linux, /proc not writable) or the number would mislead (AddressSanitizer builds).
std::optional<std::size_t> peakResidentGrowth(const std::function<void()>& work);

}  // namespace tangent::bench
