// SPDX-License-Identifier: MIT
// The threaded WebAssembly build (`libtangent-wasm/threads`) against the single-threaded one,
// in wall time (threads only shorten the wall), on the benchmark's UV spheres: the indexed call
// (generateTangentsIndexed on the sphere's shared vertices, the native kernel bench's
// library/t1 input, the vertex split included) and the de-indexed one (generateTangents into a
// reused options.output, as glTF-Transform's tangents() would with it), each on the
// single-threaded build, the threaded build on 1 thread and on 2. The calls are interleaved
// round by round, so that a busy host's phases fall on each alike; each call's first run is left
// out. Run with LIBTANGENT_WASM_THREADS unset or at least 2.
// Prints JSON: per size and call the median and fastest wall milliseconds, and the speed-up of 2
// threads over 1 (medians).
// Usage: node wasm_threads.mjs [ROUNDS [TRIANGLES...]]   (defaults: 7 rounds; 1e5 1e6 4e6)
import fs from 'node:fs';
import { indexedSphere, sphere } from './sphere.mjs';

if (!fs.existsSync(new URL('../../wasm/package/dist/threads.mjs', import.meta.url))) {
  console.error('wasm/package is not built (wasm/build.sh)');
  process.exit(1);
}
const single = await import('../../wasm/package/index.mjs');
const threaded = await import('../../wasm/package/dist/threads.mjs');
if (threaded.maxThreads < 2) {
  console.error(`the threaded build has ${threaded.maxThreads} thread (LIBTANGENT_WASM_THREADS, or a one-core machine)`);
  process.exit(1);
}
const rounds = Number(process.argv[2] ?? 7);
const targets = process.argv.length > 3 ? process.argv.slice(3).map(Number) : [1e5, 1e6, 4e6];
const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];
const results = [];
for (const target of targets) {
  const shared = indexedSphere(target);
  const corners = sphere(target);
  const triangles = shared.indices.length / 3;
  const output = new Float32Array(4 * 3 * triangles);
  const indexed = (module, threads) => () =>
    module.generateTangentsIndexed(shared.position, shared.normal, shared.texcoord, shared.indices, { threads });
  const deindexed = (module, threads) => () =>
    module.generateTangents(corners.position, corners.normal, corners.texcoord, { output, threads });
  const calls = {
    indexedSingle: indexed(single, 1), indexedT1: indexed(threaded, 1), indexedT2: indexed(threaded, 2),
    deindexedSingle: deindexed(single, 1), deindexedT1: deindexed(threaded, 1), deindexedT2: deindexed(threaded, 2),
  };
  const samples = Object.fromEntries(Object.keys(calls).map((name) => [name, []]));
  const repeat = Math.max(1, Math.round(1e6 / triangles / 2));  // small spheres: several calls per sample
  for (const call of Object.values(calls)) call();
  for (let round = 0; round < rounds; ++round) {
    for (const [name, call] of Object.entries(calls)) {
      const start = process.hrtime.bigint();
      for (let r = 0; r < repeat; ++r) call();
      samples[name].push(Number(process.hrtime.bigint() - start) / 1e6 / repeat);
    }
  }
  const entry = { triangles, rounds, callsPerSample: repeat };
  for (const [name, values] of Object.entries(samples)) {
    entry[name] = { medianMs: +median(values).toFixed(2), fastestMs: +Math.min(...values).toFixed(2) };
  }
  entry.indexedSpeedup = +(entry.indexedT1.medianMs / entry.indexedT2.medianMs).toFixed(2);
  entry.deindexedSpeedup = +(entry.deindexedT1.medianMs / entry.deindexedT2.medianMs).toFixed(2);
  results.push(entry);
}
console.log(JSON.stringify(results));
