// SPDX-License-Identifier: MIT
// How libtangent's WebAssembly package scales with size: time per triangle of
// generateTangents on the benchmark's UV spheres (sphere.mjs) of several sizes, in one Node
// process with the sizes interleaved round by round, so that a slow phase of the host falls on
// every size alike instead of on whichever size ran then (mikktspace_kernel.mjs runs each size
// in a process of its own, minutes apart). A smaller sphere is called several times per sample,
// so every sample is about the same amount of work. One round first, left out: each size's
// first call grows the module's memory and touches it.
// Prints JSON: per size the triangles, the median and fastest microseconds per triangle over
// ROUNDS rounds, and the spread (slowest median over fastest median).
// Usage: node wasm_scaling.mjs [ROUNDS [TRIANGLES...]]   (defaults: 7 rounds; 1e5 1e6 4e6)
import fs from 'node:fs';
import { sphere } from './sphere.mjs';

const packageFile = new URL('../../wasm/package/index.mjs', import.meta.url);
if (!fs.existsSync(new URL('../../wasm/package/dist/tangent_wasm.cjs', import.meta.url))) {
  console.error('wasm/package is not built (wasm/build.sh)');
  process.exit(1);
}
const { generateTangents } = await import(packageFile);
const rounds = Number(process.argv[2] ?? 7);
const targets = process.argv.length > 3 ? process.argv.slice(3).map(Number) : [1e5, 1e6, 4e6];
const largest = Math.max(...targets);
const sizes = targets.map((target) => {
  const arrays = sphere(target);
  const triangles = arrays.position.length / 9;
  return { target, triangles, arrays, calls: Math.max(1, Math.round(largest / target / 4)), samples: [] };
});
for (let round = 0; round <= rounds; ++round) {
  for (const size of sizes) {
    const { position, normal, texcoord } = size.arrays;
    const start = process.hrtime.bigint();
    for (let call = 0; call < size.calls; ++call) generateTangents(position, normal, texcoord);
    const us = Number(process.hrtime.bigint() - start) / 1e3 / size.calls / size.triangles;
    if (round > 0) size.samples.push(us);
  }
}
const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];
const result = sizes.map(({ target, triangles, calls, samples }) => ({
  target, triangles, callsPerSample: calls, medianUsPerTriangle: median(samples), fastestUsPerTriangle: Math.min(...samples),
}));
const medians = result.map((r) => r.medianUsPerTriangle);
console.log(JSON.stringify({ rounds, sizes: result, spread: Math.max(...medians) / Math.min(...medians) }));
