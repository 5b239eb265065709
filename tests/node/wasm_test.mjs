// SPDX-License-Identifier: MIT
// Tests of the WebAssembly package (wasm/package) against the C++ library and the Khronos
// validator. Usage: node wasm_test.mjs ARRAYS_TOOL WORK_DIR ASSET...
//   ARRAYS_TOOL: tangent-arrays-tool (the C++ library on raw arrays, tests/support)
//   ASSET: .gltf/.glb files put through glTF-Transform's tangents() with our generateTangents
// Every corner: within 0.01 degrees of the C++ library and the same w; every output tangent
// finite, unit and never zero; every written file free of validator errors. Exits 1 on failure.
import { execFileSync, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { tangents, unweld } from '@gltf-transform/functions';
import validator from 'gltf-validator';
import { generateGltfTangents, generateTangents, generateTangentsIndexed, optionChoices } from '../../wasm/package/index.mjs';
import createTangentModule from '../../wasm/package/dist/tangent_wasm.cjs';
import { deindex, generated, random } from './meshes.mjs';

const [tool, workDir, ...assets] = process.argv.slice(2);
if (!tool || !workDir) {
  console.error('usage: node wasm_test.mjs ARRAYS_TOOL WORK_DIR ASSET...');
  process.exit(2);
}
fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(workDir, { recursive: true });
let failures = 0;
const fail = (message) => {
  console.log(`FAIL ${message}`);
  failures++;
};

// The C++ library on the same arrays: per-corner tangents and vertex split.
let runs = 0;
function library(position, normal, texcoord, indices, origin, method = 'mikktspace', weighting = 'angle') {
  const dir = path.join(workDir, `arrays-${runs++}`);
  fs.mkdirSync(dir);
  const write = (name, array) => fs.writeFileSync(path.join(dir, name), Buffer.from(array.buffer, array.byteOffset, array.byteLength));
  write('positions.f32', position);
  write('normals.f32', normal);
  write('uvs.f32', texcoord);
  write('indices.u32', indices);
  execFileSync(tool, [dir, method, origin, weighting]);
  const read = (name, Type) => {
    const bytes = fs.readFileSync(path.join(dir, name));
    return new Type(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength));
  };
  return { tangents: read('tangents.f32', Float32Array), cornerVertex: read('corner_vertex.u32', Uint32Array) };
}

// Compares per-corner tangents (ours: a function of the corner) with the library's; exact: every
// corner must have the library's bits.
function compare(label, cornerCount, ours, theirs, exact = false) {
  let worst = 0, wrongW = 0, identical = 0;
  for (let c = 0; c < cornerCount; ++c) {
    const a = ours(c), b = theirs.subarray(4 * c, 4 * c + 4);
    const la = Math.hypot(a[0], a[1], a[2]), lb = Math.hypot(b[0], b[1], b[2]);
    if (!(Math.abs(la - 1) < 1e-5) || !a.every(Number.isFinite) || Math.abs(Math.abs(a[3]) - 1) !== 0) {
      fail(`${label}: corner ${c}: not a finite unit tangent with w = +-1: ${Array.from(a)}`);
      return;
    }
    const cos = Math.min(1, Math.max(-1, (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb)));
    worst = Math.max(worst, (Math.acos(cos) * 180) / Math.PI);
    if (a[3] !== b[3]) wrongW++;
    if (a[0] === b[0] && a[1] === b[1] && a[2] === b[2] && a[3] === b[3]) identical++;
  }
  const ok = worst <= 0.01 && wrongW === 0 && (!exact || identical === cornerCount);
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${label}: ${cornerCount} corners, worst ${worst.toExponential(2)} deg, ` +
    `${wrongW} with another w, ${identical} bit-identical`);
  if (!ok) failures++;
}

// 1. Generated meshes, indexed (glTF's w) and de-indexed (MikkTSpace's w, as glTF-Transform
// expects it), against the library's bits on the same arrays; the vertex split too.
for (const [segments, seed] of [[8, 1], [24, 2], [64, 3]]) {
  const mesh = generated(segments, seed);
  const label = `generated sphere ${segments}x${segments} (seed ${seed})`;
  const ours = generateTangentsIndexed(mesh.position, mesh.normal, mesh.texcoord, mesh.indices);
  const theirs = library(mesh.position, mesh.normal, mesh.texcoord, mesh.indices, 'top-left');
  compare(`${label}, indexed`, mesh.indices.length, (c) => ours.tangents.subarray(4 * ours.indices[c], 4 * ours.indices[c] + 4), theirs.tangents, true);
  // The library's split, each output vertex a copy of its corners' input vertex, and every
  // input vertex kept in its place.
  const inputVertices = mesh.position.length / 3;
  const sameSplit = ours.indices.every((v, c) => v === theirs.cornerVertex[c] && ours.source[v] === mesh.indices[c]) &&
    ours.source.every((s, v) => v >= inputVertices || s === v);
  if (!sameSplit) fail(`${label}: the vertex split differs from the library's`);
  for (let v = 0; v < ours.vertexCount; ++v) {
    const t = ours.tangents.subarray(4 * v, 4 * v + 4);
    if (!(Math.abs(Math.hypot(t[0], t[1], t[2]) - 1) < 1e-5)) fail(`${label}: output vertex ${v} has no unit tangent`);
  }
  const flat = deindex(mesh);
  const sequence = Uint32Array.from({ length: mesh.indices.length }, (_, i) => i);
  const plain = generateTangents(flat.position, flat.normal, flat.texcoord);
  const plainTheirs = library(flat.position, flat.normal, flat.texcoord, sequence, 'bottom-left');
  compare(`${label}, de-indexed`, mesh.indices.length, (c) => plain.subarray(4 * c, 4 * c + 4), plainTheirs.tangents, true);
}

// How many of `n` corners' tangents differ in their bits (a byte comparison: -0 === 0 in
// JavaScript).
function cornersWithOtherBits(ours, theirs, n) {
  const oursBits = new Uint32Array(ours.buffer, ours.byteOffset, ours.length), theirBits = new Uint32Array(theirs.buffer, theirs.byteOffset, theirs.length);
  let differ = 0;
  for (let c = 0; c < n; ++c) {
    for (let k = 0; k < 4; ++k) {
      if (oursBits[4 * c + k] !== theirBits[4 * c + k]) {
        differ++;
        break;
      }
    }
  }
  return differ;
}

// 1d. generateTangents passes the corners through a staging buffer of 16,384 corners
// (index.mjs shareCorners): a de-indexed sphere of 60,000 corners, three whole runs and part
// of a fourth, whose vertices are shared across the runs' boundaries, has the library's bits.
{
  const mesh = generated(100, 4), flat = deindex(mesh), n = mesh.indices.length;
  const ours = generateTangents(flat.position, flat.normal, flat.texcoord);
  const theirs = library(flat.position, flat.normal, flat.texcoord, Uint32Array.from({ length: n }, (_, i) => i), 'bottom-left').tangents;
  const differ = cornersWithOtherBits(ours, theirs, n);
  const label = `de-indexed sphere of ${n} corners through the staging buffer`;
  if (differ) fail(`${label}: ${differ} corners differ in their bits from the library's`);
  else console.log(`ok   ${label}: every corner bit-identical`);
}

// 1c. De-indexed corners whose values are equal but whose bits are not (+0 and -0), and
// corners with the same NaN bits: generateTangents shares a vertex between corners of the
// same bits only (wasm/src/shared_vertices.hpp) and leaves the weld by value to the core, so
// every output must have the library's bits on the same de-indexed arrays, sign of zero
// included (hence a byte comparison: -0 === 0 in JavaScript).
{
  const rand = random(7), grid = 12, flatCorners = [];
  const zero = () => (rand() < 0.5 ? -0 : 0);
  for (let j = 0; j < grid; ++j) {
    for (let i = 0; i < grid; ++i) {
      const quad = [[i, j], [i + 1, j + 1], [i + 1, j], [i, j], [i, j + 1], [i + 1, j + 1]];
      for (const [x, y] of quad) flatCorners.push([x / grid, y / grid]);
    }
  }
  const n = flatCorners.length;
  const position = new Float32Array(3 * n), normal = new Float32Array(3 * n), texcoord = new Float32Array(2 * n);
  flatCorners.forEach(([x, y], c) => {
    position.set([x === 0 ? zero() : x, y === 0 ? zero() : y, zero()], 3 * c);
    normal.set([zero(), zero(), 1], 3 * c);
    texcoord.set([x, c % 6 < 3 ? y : 2 - y], 2 * c);  // a UV seam along every quad's diagonal
  });
  // The vertex at (0.5, 0.5): every corner there gets the same NaN u.
  flatCorners.forEach(([x, y], c) => {
    if (x === 0.5 && y === 0.5) texcoord[2 * c] = NaN;
  });
  const ours = generateTangents(position, normal, texcoord);
  const theirs = library(position, normal, texcoord, Uint32Array.from({ length: n }, (_, i) => i), 'bottom-left').tangents;
  const differ = cornersWithOtherBits(ours, theirs, n);
  const label = `de-indexed plane with +0/-0, UV seams and a NaN vertex, ${n} corners`;
  if (differ) fail(`${label}: ${differ} corners differ in their bits from the library's`);
  else console.log(`ok   ${label}: every corner bit-identical (sign of zero included)`);
}

// 1b. Every method and weighting, by the command line's names: the library's bits exactly, its
// vertex split, and a report naming the method.
for (const [segments, seed] of [[24, 2], [64, 3]]) {
  const mesh = generated(segments, seed);
  for (const [method, weighting] of [['mikktspace', 'angle'], ['lengyel', 'angle'], ['lengyel', 'area'], ['lengyel', 'uniform'], ['flat', 'angle'], ['meshopt', 'angle']]) {
    const label = `generated sphere ${segments}x${segments}, ${method} (${weighting})`;
    const ours = generateTangentsIndexed(mesh.position, mesh.normal, mesh.texcoord, mesh.indices, { method, weighting });
    const theirs = library(mesh.position, mesh.normal, mesh.texcoord, mesh.indices, 'top-left', method, weighting);
    const bits = new Uint32Array(theirs.tangents.buffer);
    const oursBits = new Uint32Array(ours.tangents.buffer);
    let differing = 0;
    ours.indices.forEach((v, c) => {
      for (let i = 0; i < 4; ++i) differing += oursBits[4 * v + i] !== bits[4 * c + i] ? 1 : 0;
    });
    const sameSplit = ours.indices.every((v, c) => v === theirs.cornerVertex[c]);
    const ok = differing === 0 && sameSplit && ours.report.method === method && ours.report.corners === mesh.indices.length;
    console.log(`${ok ? 'ok  ' : 'FAIL'} ${label}: ${differing} values differ from the library's bits, split ${sameSplit ? 'the same' : 'differs'}`);
    if (!ok) failures++;
  }
}
try {
  generateTangentsIndexed(new Float32Array(9), new Float32Array(9), new Float32Array(6), [0, 1, 2], { method: 'smooth' });
  fail('an unknown method was accepted');
} catch (e) {
  if (!/method: 'smooth' is not mikktspace, lengyel, flat or meshopt/.test(e.message)) fail(`unexpected error message: ${e.message}`);
  else console.log(`ok   unknown method refused: ${e.message}`);
}

// 1d'. The w conventions and the options' checks: generateGltfTangents is generateTangents with
// w negated (glTF's sign), and the indexed call's w at every corner; a misspelt option
// (Python's uv_origin) is a TypeError, not ignored; optionChoices lead with the defaults.
{
  const flat = deindex(generated(24, 2));
  const mikk = generateTangents(flat.position, flat.normal, flat.texcoord);
  const gltf = generateGltfTangents(flat.position, flat.normal, flat.texcoord);
  const bottom = generateGltfTangents(flat.position, flat.normal, flat.texcoord, { uvOrigin: 'bottom-left' });
  let differing = 0;
  for (let i = 0; i < mikk.length; i++) {
    const expected = i % 4 === 3 ? -mikk[i] : mikk[i];
    if (!Object.is(gltf[i], expected) || !Object.is(bottom[i], mikk[i])) differing++;
  }
  if (differing) fail(`generateGltfTangents: ${differing} values are not generateTangents's with w negated`);
  else console.log('ok   generateGltfTangents is generateTangents with glTF\'s w');
  for (const [options, error] of [[{ uv_origin: 'top-left' }, TypeError], [{ uvOrigin: 'top-left' }, TypeError],
                                  [{ weighting: 'heavy' }, RangeError]]) {
    try {
      generateTangents(flat.position, flat.normal, flat.texcoord, options);
      fail(`generateTangents accepted ${JSON.stringify(options)}`);
    } catch (e) {
      if (!(e instanceof error)) fail(`${JSON.stringify(options)}: ${e.constructor.name} ${e.message}`);
      else console.log(`ok   ${JSON.stringify(options)} refused: ${e.message}`);
    }
  }
  if (optionChoices.method[0] !== 'mikktspace' || optionChoices.uvOrigin[0] !== 'top-left') fail('optionChoices: defaults not first');
}

// 1e. generateTangents's `output` option: the tangents written into the caller's array, which is
// returned, with the same bits as without it; one of the wrong length or type refused.
{
  const mesh = generated(24, 5), flat = deindex(mesh), n = mesh.indices.length;
  const plain = generateTangents(flat.position, flat.normal, flat.texcoord);
  const output = new Float32Array(4 * n).fill(NaN);  // untouched floats would stay NaN
  const returned = generateTangents(flat.position, flat.normal, flat.texcoord, { output });
  const differ = cornersWithOtherBits(output, plain, n);
  if (returned !== output) fail('output: generateTangents returned another array than the one given');
  else if (differ) fail(`output: ${differ} corners differ in their bits from the call without it`);
  else console.log(`ok   output: the ${n} corners' tangents written into the given array, the same bits`);
  for (const [label, bad, expected] of [['too short', new Float32Array(4 * n - 4), /output: expected \d+ floats, got \d+/],
    ['not a Float32Array', new Float64Array(4 * n), /output: expected a Float32Array/]]) {
    try {
      generateTangents(flat.position, flat.normal, flat.texcoord, { output: bad });
      fail(`output ${label}: accepted`);
    } catch (e) {
      if (!expected.test(e.message)) fail(`output ${label}: unexpected error message: ${e.message}`);
      else console.log(`ok   output ${label} refused: ${e.message}`);
    }
  }
}

// 1f. The module's tangent_run refuses null arrays (0 from JavaScript) other than the shared
// corners' (all three null, no indices, no vertex split) with a message, instead of reading
// the module's memory from address 0 as the mesh. On a module of its own, through its exports.
{
  const module = await createTangentModule();
  const text = (s) => {
    const p = module._malloc(module.lengthBytesUTF8(s) + 1);
    module.stringToUTF8(s, p, module.lengthBytesUTF8(s) + 1);
    return p;
  };
  const [method, weighting, origin] = ['mikktspace', 'angle', 'top-left'].map(text);
  const floats = module._malloc(4 * 9), index = module._malloc(4 * 3);
  module.HEAPU32.set([0, 1, 2], index >>> 2);
  const cases = [
    ['positions null', [0, floats, floats, index, 0], /positions: null; positions, normals and uvs are given together/],
    ['normals and uvs null', [floats, 0, 0, index, 0], /normals, uvs: null; positions, normals and uvs are given together/],
    ['all null with indices', [0, 0, 0, index, 0], /positions, normals, uvs: null, which only the shared corners/],
    ['all null with the vertex split', [0, 0, 0, 0, 1], /positions, normals, uvs: null, which only the shared corners/],
  ];
  for (const [label, [p, nrm, t, i, split], expected] of cases) {
    const status = module._tangent_run(p, nrm, t, i, 3, 3, method, weighting, origin, split);
    const message = module.UTF8ToString(module._tangent_error());
    if (status === 0 || !expected.test(message)) fail(`tangent_run, ${label}: status ${status}, '${message}'`);
    else console.log(`ok   tangent_run, ${label}: refused: ${message}`);
  }
}

// 1g. The threaded build (wasm_threads_test.mjs), in a process of its own with a pool of three
// threads, which must end by itself (an idle worker referenced would keep it running).
{
  const script = new URL('./wasm_threads_test.mjs', import.meta.url).pathname;
  const done = spawnSync(process.execPath, [script], { env: { ...process.env, LIBTANGENT_WASM_THREADS: '3' }, encoding: 'utf8', timeout: 240000 });
  process.stdout.write(done.stdout ?? '');
  if (done.status === null) fail(`the threaded build's test did not end by itself in 240 s (${done.signal}): ${done.stderr}`);
  else if (done.status !== 0) fail(`the threaded build's test exited ${done.status}: ${done.stderr}`);
}

// 2. Errors surface as exceptions with the core's message.
try {
  generateTangentsIndexed(new Float32Array(9), new Float32Array(9), new Float32Array(6), [0, 1, 3]);
  fail('an index out of range was accepted');
} catch (e) {
  if (!/indices\[2\] = 3 is out of range/.test(e.message)) fail(`unexpected error message: ${e.message}`);
  else console.log(`ok   error surfaces: ${e.message}`);
}

// 3. glTF-Transform's tangents() with our generateTangents on real files; the validator on
// what it writes.
const io = new NodeIO().registerExtensions(ALL_EXTENSIONS);
for (const asset of assets) {
  const name = path.basename(asset);
  const document = await io.read(asset);
  await document.transform(unweld(), tangents({ generateTangents, overwrite: true }));
  let compared = 0, strips = 0, withoutNormal = 0;
  for (const mesh of document.getRoot().listMeshes()) {
    mesh.listPrimitives().forEach((primitive, p) => {
      const material = primitive.getMaterial();
      const info = material?.getNormalTextureInfo();
      const semantic = info && material.getNormalTexture() ? `TEXCOORD_${info.getTexCoord()}` : null;
      const position = primitive.getAttribute('POSITION'), normal = primitive.getAttribute('NORMAL');
      const texcoord = semantic && primitive.getAttribute(semantic), tangent = primitive.getAttribute('TANGENT');
      if (position && texcoord && !normal) withoutNormal++;  // glTF-Transform's tangents() needs NORMAL (tangent bake generates it)
      if (!position || !normal || !texcoord) return;
      if (primitive.getMode() !== 4) {
        strips++;  // glTF-Transform's tangents() takes triangle lists only
        return;
      }
      if (!tangent) {
        fail(`${name} mesh "${mesh.getName()}" primitive ${p}: normal-mapped, but glTF-Transform wrote no TANGENT`);
        return;
      }
      const f32 = (accessor) => Float32Array.from(accessor.getArray());
      const n = position.getCount();
      const theirs = library(f32(position), f32(normal), f32(texcoord), Uint32Array.from({ length: n }, (_, i) => i), 'top-left');
      const stored = f32(tangent);
      compare(`${name} mesh "${mesh.getName()}" primitive ${p} through glTF-Transform`, n, (c) => stored.subarray(4 * c, 4 * c + 4), theirs.tangents);
      compared++;
    });
  }
  if (compared === 0 && strips === 0 && withoutNormal === 0) fail(`${name}: no normal-mapped primitive got tangents`);
  if (strips > 0) console.log(`note ${name}: ${strips} normal-mapped strip/fan primitives left alone by glTF-Transform's tangents()`);
  const out = path.join(workDir, `${path.parse(name).name}.glb`);
  fs.writeFileSync(out, await io.writeBinary(document));
  const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(out)), { uri: path.basename(out) });
  if (report.issues.numErrors > 0) {
    fail(`${out}: ${report.issues.numErrors} validator errors: ` +
      report.issues.messages.filter((m) => m.severity === 0).slice(0, 3).map((m) => `${m.code} ${m.pointer}`).join('; '));
  } else {
    console.log(`ok   ${name}: written by glTF-Transform with our tangents, 0 validator errors`);
  }
}
console.log(failures === 0 ? 'all passed' : `${failures} failed`);
process.exit(failures === 0 ? 0 : 1);
