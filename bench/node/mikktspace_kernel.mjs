// SPDX-License-Identifier: MIT
// The reference MikkTSpace kernel (npm `mikktspace`, WebAssembly) and libtangent's own
// WebAssembly package (wasm/package, when built by wasm/build.sh) on the same de-indexed arrays
// in one process, runs alternating: the UV sphere the library is measured on
// (tools/bench/analytic_surfaces.cpp, "sphere"), or the largest normal-mapped primitive of a
// .glb. Prints the medians in milliseconds as JSON, and libtangent-wasm's first call in the
// process apart (it also pays the first touch of its memory: a page fault per 4 KiB, and the
// module's memory growing), out of its median. libtangent-wasm runs at least 3 times more,
// whatever RUNS is (RUNS = 1 spares the npm package's minutes at 4e6 triangles), so that its
// median is one of the same kind at every size.
// Usage: node mikktspace_kernel.mjs TRIANGLES|FILE.glb [RUNS]
import fs from 'node:fs';
import { generateTangents } from 'mikktspace';
import { sphere } from './sphere.mjs';

const ours = fs.existsSync(new URL('../../wasm/package/dist/tangent_wasm.cjs', import.meta.url))
  ? (await import('../../wasm/package/index.mjs')).generateTangents
  : null;
const runs = Number(process.argv[3] ?? 3);
let position, normal, texcoord;
if (String(process.argv[2]).endsWith('.glb')) {
  ({ position, normal, texcoord } = await fromAsset(process.argv[2]));
} else {
  ({ position, normal, texcoord } = sphere(Number(process.argv[2] ?? 1000000)));
}
const times = { mikktspace: [], libtangentWasm: [] };
const runsOf = { mikktspace: runs, libtangentWasm: 1 + Math.max(3, runs) };
for (let r = 0; r < Math.max(...Object.values(runsOf)); ++r) {
  for (const [name, generate] of [['mikktspace', generateTangents], ['libtangentWasm', ours]]) {
    if (!generate || r >= runsOf[name]) continue;
    const start = process.hrtime.bigint();
    generate(position, normal, texcoord);
    times[name].push(Number(process.hrtime.bigint() - start) / 1e6);
  }
}
const median = (values) => (values.length ? [...values].sort((x, y) => x - y)[Math.floor(values.length / 2)] : null);
console.log(JSON.stringify({ triangles: position.length / 9, medianMs: median(times.mikktspace),
  libtangentWasmMs: median(times.libtangentWasm.slice(1)), libtangentWasmFirstMs: times.libtangentWasm[0] ?? null, runs,
  libtangentWasmRuns: Math.max(0, times.libtangentWasm.length - 1) }));

// The largest normal-mapped triangle-list primitive of a GLB, de-indexed.
async function fromAsset(file) {
  const { NodeIO } = await import('@gltf-transform/core');
  const document = await new NodeIO().read(file);
  let best = null;
  for (const mesh of document.getRoot().listMeshes()) {
    for (const primitive of mesh.listPrimitives()) {
      const info = primitive.getMaterial()?.getNormalTextureInfo();
      const uv = primitive.getAttribute(`TEXCOORD_${info ? info.getTexCoord() : 0}`);
      if (primitive.getMode() !== 4 || !uv || !primitive.getAttribute('NORMAL')) continue;
      const count = primitive.getIndices() ? primitive.getIndices().getCount() : primitive.getAttribute('POSITION').getCount();
      if (!best || count > best.count) best = { primitive, uv, count };
    }
  }
  const { primitive, uv, count } = best;
  const indices = primitive.getIndices()?.getArray() ?? Uint32Array.from({ length: count }, (_, i) => i);
  const gather = (accessor, width) => {
    const out = new Float32Array(count * width), element = [];
    for (let c = 0; c < count; ++c) out.set(accessor.getElement(indices[c], element), width * c);
    return out;
  };
  return { position: gather(primitive.getAttribute('POSITION'), 3), normal: gather(primitive.getAttribute('NORMAL'), 3),
    texcoord: gather(uv, 2) };
}
