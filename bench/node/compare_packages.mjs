// SPDX-License-Identifier: MIT
// Two or more builds of libtangent's WebAssembly package (each a directory holding index.mjs
// and dist/, as wasm/build.sh leaves wasm/package) in one Node process: generateTangents on the
// de-indexed UV sphere of mikktspace_kernel.mjs, calls alternating between the packages (the
// order rotating each round), so that load on the machine falls on all of them alike. Each
// package's first call of a size is timed apart (it pays the first touch of new memory) and
// left out of the medians. Prints one JSON line per size: per package the median wall and CPU
// (user + system of this process) milliseconds, wall microseconds per triangle, the first
// call, and whether its output has the same bits as the first package's.
// --output: every call passes { output } with one array per package and size, reused from call
// to call (packages without the option ignore it and return a new array: `wroteOutput` says
// which wrote into it).
// Usage: node compare_packages.mjs DIR [DIR...] [--sizes 1e5,1e6,4e6] [--runs 5] [--output]
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { sphere } from './sphere.mjs';

const args = process.argv.slice(2);
const option = (name, fallback) => {
  const i = args.indexOf(name);
  return i < 0 ? fallback : args.splice(i, 2)[1];
};
const sizes = option('--sizes', '1e5,1e6,4e6').split(',').map(Number);
const runs = Number(option('--runs', '5'));
const outputIndex = args.indexOf('--output'), reuseOutput = outputIndex >= 0;
if (reuseOutput) args.splice(outputIndex, 1);
if (args.length === 0) {
  console.error('usage: node compare_packages.mjs DIR [DIR...] [--sizes 1e5,1e6,4e6] [--runs 5] [--output]');
  process.exit(2);
}
const packages = [];
for (const dir of args) {
  const module = await import(pathToFileURL(path.resolve(dir, 'index.mjs')).href);
  packages.push({ name: dir, generate: module.generateTangents });
}
// Builds older than ef9eac8 do not warm up at load: a few small calls get V8's optimized code
// for every package before anything is timed.
const small = sphere(2000);
for (const { generate } of packages) {
  for (let call = 0; call < 20; ++call) generate(small.position, small.normal, small.texcoord);
}

const median = (values) => [...values].sort((x, y) => x - y)[Math.floor(values.length / 2)];
function timed(generate, mesh, output) {
  const cpu = process.cpuUsage(), start = process.hrtime.bigint();
  const tangents = output ? generate(mesh.position, mesh.normal, mesh.texcoord, { output }) : generate(mesh.position, mesh.normal, mesh.texcoord);
  const wallMs = Number(process.hrtime.bigint() - start) / 1e6;
  const used = process.cpuUsage(cpu);
  return { wallMs, cpuMs: (used.user + used.system) / 1e3, tangents };
}
const sameBits = (a, b) => a.length === b.length && Buffer.compare(
  Buffer.from(a.buffer, a.byteOffset, a.byteLength), Buffer.from(b.buffer, b.byteOffset, b.byteLength)) === 0;

for (const size of sizes) {
  const mesh = sphere(size);
  const triangles = mesh.position.length / 9;
  const results = packages.map(() => ({ wall: [], cpu: [], firstMs: null, sameBits: true, wroteOutput: false }));
  const outputs = packages.map(() => (reuseOutput ? new Float32Array(mesh.position.length / 3 * 4) : null));
  let reference = null;
  for (let round = 0; round <= runs; ++round) {
    for (let k = 0; k < packages.length; ++k) {
      const p = (k + round) % packages.length;
      const { wallMs, cpuMs, tangents } = timed(packages[p].generate, mesh, outputs[p]);
      results[p].wroteOutput = outputs[p] !== null && tangents === outputs[p];
      if (round === 0) {
        results[p].firstMs = wallMs;
        if (p === 0) reference = tangents.slice();
      } else {
        results[p].wall.push(wallMs);
        results[p].cpu.push(cpuMs);
      }
      if (round === 0 && p !== 0) results[p].pending = tangents.slice();
    }
    if (round === 0) {
      for (const r of results) {
        if (r.pending) r.sameBits = sameBits(reference, r.pending);
        delete r.pending;
      }
    }
  }
  console.log(JSON.stringify({
    triangles, runs,
    packages: packages.map(({ name }, p) => ({
      name,
      wallMs: +median(results[p].wall).toFixed(1),
      cpuMs: +median(results[p].cpu).toFixed(1),
      usPerTriangle: +(1e3 * median(results[p].wall) / triangles).toFixed(3),
      cpuUsPerTriangle: +(1e3 * median(results[p].cpu) / triangles).toFixed(3),
      firstMs: +results[p].firstMs.toFixed(1),
      sameBits: results[p].sameBits,
      ...(reuseOutput ? { wroteOutput: results[p].wroteOutput } : {}),
    })),
  }));
}
