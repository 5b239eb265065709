// SPDX-License-Identifier: MIT
// The threaded build of the WebAssembly package (`libtangent-wasm/threads`: the core's pool of
// standard threads on emscripten's pthreads, Node workers) against the single-threaded build:
// the same bits for every method, weighting and thread count, indexed and de-indexed; its
// pool as big as LIBTANGENT_WASM_THREADS says and really used; `threads` checked. Run by
// wasm_test.mjs in a process of its own (LIBTANGENT_WASM_THREADS=3), which must also end by
// itself: the pool's idle workers may not keep Node alive. Exits 1 on failure.
import * as single from '../../wasm/package/index.mjs';
import * as threaded from '../../wasm/package/dist/threads.mjs';
import createThreadedModule from '../../wasm/package/dist/tangent_wasm_threads.cjs';
import { deindex, generated } from './meshes.mjs';

let failures = 0;
const check = (ok, message) => {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${message}`);
  if (!ok) failures++;
};
const bytes = (a) => Buffer.from(a.buffer, a.byteOffset, a.byteLength);
const same = (a, b) => a.length === b.length && bytes(a).equals(bytes(b));

const expected = Number(process.env.LIBTANGENT_WASM_THREADS);
check(single.maxThreads === 1, `the single-threaded build's maxThreads is 1 (${single.maxThreads})`);
check(threaded.maxThreads === expected, `the threaded build's maxThreads is LIBTANGENT_WASM_THREADS (${threaded.maxThreads}, ${expected})`);

// A sphere of 2 x 160 x 160 triangles with a seam, a mirrored half and slivers: each of the
// core's passes cuts it into several pieces, so that every thread takes some; de-indexed, its
// 153,600 corners are shared on the call's threads (more than 131,072: shareVertices runs in
// parallel from there).
const mesh = generated(160, 5);
const flat = deindex(mesh);
for (const [method, weighting] of [['mikktspace', 'angle'], ['lengyel', 'angle'], ['lengyel', 'area'], ['flat', 'angle'], ['meshopt', 'angle']]) {
  const options = { method, weighting };
  const one = single.generateTangentsIndexed(mesh.position, mesh.normal, mesh.texcoord, mesh.indices, options);
  const oneFlat = single.generateGltfTangents(flat.position, flat.normal, flat.texcoord, options);
  for (const threads of [1, 2, 3, 0, 64]) {
    const other = threaded.generateTangentsIndexed(mesh.position, mesh.normal, mesh.texcoord, mesh.indices, { ...options, threads });
    const otherFlat = threaded.generateGltfTangents(flat.position, flat.normal, flat.texcoord, { ...options, threads });
    const ok = same(one.tangents, other.tangents) && same(one.indices, other.indices) && same(one.source, other.source) &&
      JSON.stringify(one.report) === JSON.stringify(other.report) && same(oneFlat, otherFlat);
    check(ok, `${method} (${weighting}), threads ${threads}: the single-threaded build's bits, split and report`);
  }
}

// `threads`: a whole number from 0 up; anything else is a RangeError naming it.
for (const threads of [-1, 1.5, '2', NaN]) {
  try {
    threaded.generateTangents(flat.position, flat.normal, flat.texcoord, { threads });
    check(false, `threads ${String(threads)} was accepted`);
  } catch (e) {
    check(e instanceof RangeError && /threads: .* is not a whole number from 0/.test(e.message), `threads ${String(threads)} refused: ${e.message}`);
  }
}

// The pool really runs the core: after a call on 2 threads, a worker of a module of its own
// is running one of the pool's threads (none before).
{
  const module = await createThreadedModule();
  for (const worker of module.PThread.unusedWorkers) worker.unref?.();
  const before = module.PThread.runningWorkers.length;
  const put = (array) => {
    const p = module._malloc(array.byteLength);
    module.HEAPU8.set(bytes(array), p);
    return p;
  };
  const text = (s) => put(new TextEncoder().encode(`${s}\0`));
  const status = module._tangent_run(put(mesh.position), put(mesh.normal), put(mesh.texcoord), put(mesh.indices),
    mesh.position.length / 3, mesh.indices.length, text('mikktspace'), text('angle'), text('top-left'), 0, 2);
  for (const worker of module.PThread.runningWorkers) worker.unref?.();
  check(status === 0 && before === 0 && module.PThread.runningWorkers.length >= 1,
    `a call on 2 threads starts the pool's threads (running workers ${before} before, ${module.PThread.runningWorkers.length} after)`);
}
process.exitCode = failures ? 1 : 0;
