// SPDX-License-Identifier: MIT
// libtangent's WebAssembly package in CPU time (process.cpuUsage: user + system, every thread
// of the process), the calls interleaved round by round on the benchmark's UV sphere, so that
// a shared machine's load (which stretches wall time several-fold when other jobs run) falls on
// each call alike:
//   deindexed     generateTangents(position, normal, texcoord): a new array per call, as
//                 glTF-Transform calls it; shares the corners' vertices first (the native
//                 equivalent: tangent::shareVertices, then computeCornerTangents)
//   deindexedOut  the same into options.output, reused (no first touch of a new 48 MB array
//                 at 1e6 triangles)
//   indexed       generateTangentsIndexed on the sphere's shared vertices and indices: the
//                 input of the native kernel bench's library/t1/sphere-1eN (which makes no
//                 vertex split; this call does)
// Each call's first run in the process is left out. Prints JSON: per call the median and
// fastest CPU milliseconds and the median in microseconds per triangle.
// Usage: node wasm_cpu.mjs [ROUNDS [TRIANGLES...]]   (defaults: 9 rounds; 1e5 1e6)
import fs from 'node:fs';
import { indexedSphere, sphere } from './sphere.mjs';

if (!fs.existsSync(new URL('../../wasm/package/dist/tangent_wasm.cjs', import.meta.url))) {
  console.error('wasm/package is not built (wasm/build.sh)');
  process.exit(1);
}
const { generateTangents, generateTangentsIndexed } = await import('../../wasm/package/index.mjs');
const rounds = Number(process.argv[2] ?? 9);
const targets = process.argv.length > 3 ? process.argv.slice(3).map(Number) : [1e5, 1e6];
const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];
const results = [];
for (const target of targets) {
  const { position, normal, texcoord } = sphere(target);
  const shared = indexedSphere(target);
  const triangles = position.length / 9;
  const output = new Float32Array(4 * triangles * 3);
  const calls = {
    deindexed: () => generateTangents(position, normal, texcoord),
    deindexedOut: () => generateTangents(position, normal, texcoord, { output }),
    indexed: () => generateTangentsIndexed(shared.position, shared.normal, shared.texcoord, shared.indices, { uvOrigin: 'bottom-left' }),
  };
  const samples = Object.fromEntries(Object.keys(calls).map((name) => [name, []]));
  // A smaller sphere is called several times per sample (about 1e6 triangles of work each).
  const repeat = Math.max(1, Math.round(1e6 / triangles / 2));
  for (const call of Object.values(calls)) call();
  for (let round = 0; round < rounds; ++round) {
    for (const [name, call] of Object.entries(calls)) {
      const start = process.cpuUsage();
      for (let r = 0; r < repeat; ++r) call();
      const used = process.cpuUsage(start);
      samples[name].push((used.user + used.system) / 1e3 / repeat);
    }
  }
  const entry = { triangles, rounds, callsPerSample: repeat };
  for (const [name, values] of Object.entries(samples)) {
    entry[name] = { cpuMedianMs: +median(values).toFixed(2), cpuFastestMs: +Math.min(...values).toFixed(2),
      usPerTriangle: +(median(values) * 1e3 / triangles).toFixed(4) };
  }
  results.push(entry);
}
console.log(JSON.stringify(results));
