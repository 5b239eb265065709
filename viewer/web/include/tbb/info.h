// SPDX-License-Identifier: MIT
// The web build has no oneTBB (TANGENT_SERIAL): the one call outside the core's serial
// workspace, tbb::info::default_concurrency(), answers one thread.
#pragma once
namespace tbb::info {
inline int default_concurrency() { return 1; }
}  // namespace tbb::info
