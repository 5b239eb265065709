// SPDX-License-Identifier: MIT
// Which threads the core runs on, chosen when it is built:
//   TANGENT_SERIAL       none: one thread, in order (the single-threaded WebAssembly package,
//                        the web viewer)
//   TANGENT_STD_THREADS  the standard library's, in a pool of the core's own (thread_pool.hpp:
//                        the threaded WebAssembly package, on emscripten's pthreads)
//   neither              oneTBB's (every native build); TANGENT_ONETBB is defined then.
#pragma once

#if defined(TANGENT_SERIAL) && defined(TANGENT_STD_THREADS)
#error "TANGENT_SERIAL and TANGENT_STD_THREADS: choose one"
#endif
#if !defined(TANGENT_SERIAL) && !defined(TANGENT_STD_THREADS)
#define TANGENT_ONETBB 1
#endif
