// SPDX-License-Identifier: MIT
// libtangent's tangents in WebAssembly (MikkTSpace by default; Lengyel and flat on request): a
// drop-in `generateTangents` for glTF-Transform's tangents(), and an indexed call that returns
// the vertex split. Method, weighting and UV origin names are the command line's, checked by
// the core.
import createTangentModule from './dist/tangent_wasm.cjs';

const wasm = await createTangentModule();

// The threaded build (the "./threads" export, dist/threads.mjs) starts its pool of workers as it
// loads; the single-threaded build has none. An idle worker would keep Node running after the
// program's last line: the pool's are unreferenced, so only the program's own work does.
const workers = wasm.PThread ? [...wasm.PThread.unusedWorkers] : [];
for (const worker of workers) worker.unref?.();

/**
 * The most threads a call runs on: 1 in the single-threaded build; in the threaded build its
 * pool's workers and the calling thread (one fewer workers than the machine's cores, at most
 * 15; the environment variable LIBTANGENT_WASM_THREADS, read as the module loads, sets the
 * total instead).
 */
export const maxThreads = workers.length + 1;

/** Resolves once the module is ready (it is by the time this module has loaded). */
export const ready = Promise.resolve();

function requireFloat32(name, array, width) {
  if (!(array instanceof Float32Array)) throw new TypeError(`${name}: expected a Float32Array`);
  if (array.length % width !== 0) throw new RangeError(`${name}: length ${array.length} is not a multiple of ${width}`);
}

// Copies the inputs that are not null into the module's memory, runs the core (null position,
// normal and texcoord: on the corners shared already, see generateTangents), frees the inputs;
// returns the core's report. Throws an Error with the core's message when it refuses the
// arrays or a name. vertexSplit: also make the per-vertex outputs (generateTangentsIndexed's).
function run(position, normal, texcoord, indices, vertexCount, cornerCount, names, vertexSplit) {
  const arrays = [position, normal, texcoord, indices];
  const strings = [names.method, names.weighting, names.uvOrigin].map(String);
  const sizes = [...arrays.map((a) => (a === null ? 0 : Math.max(4, a.byteLength))), ...strings.map((s) => wasm.lengthBytesUTF8(s) + 1)];
  const pointers = [];
  try {
    for (const size of sizes) {
      if (size === 0) {
        pointers.push(0);
        continue;
      }
      const p = wasm._malloc(size);
      if (p === 0) throw new RangeError('libtangent: out of WebAssembly memory');
      pointers.push(p);
    }
    // Views are taken after every allocation: growing memory replaces the buffer.
    arrays.forEach((a, i) => a !== null && view(Uint8Array, pointers[i], a.byteLength)
      .set(new Uint8Array(a.buffer, a.byteOffset, a.byteLength)));
    const text = pointers.slice(arrays.length);
    strings.forEach((s, i) => wasm.stringToUTF8(s, text[i], sizes[arrays.length + i]));
    const status = wasm._tangent_run(pointers[0], pointers[1], pointers[2], pointers[3],
      vertexCount, cornerCount, text[0], text[1], text[2], vertexSplit ? 1 : 0, names.threads);
    if (status !== 0) throw new Error(`libtangent: ${wasm.UTF8ToString(wasm._tangent_error())}`);
  } finally {
    pointers.forEach((p) => p !== 0 && wasm._free(p));
  }
  return JSON.parse(wasm.UTF8ToString(wasm._tangent_report()));
}

// Shares the vertices of `corners` de-indexed corners a staging buffer at a time (the input is
// never copied into the module's memory whole: each run is shared while it is in cache).
function shareCorners(position, normal, texcoord, corners) {
  const fail = () => new Error(`libtangent: ${wasm.UTF8ToString(wasm._tangent_error())}`);
  const stage = wasm._tangent_share_begin(corners) >>> 0;
  if (stage === 0) throw fail();
  const runLength = wasm._tangent_stage_corners(), at = stage / 4;
  for (let first = 0; first < corners; first += runLength) {
    const last = Math.min(corners, first + runLength), heap = wasm.HEAPF32;  // replaced when memory grows
    heap.set(position.subarray(3 * first, 3 * last), at);
    heap.set(normal.subarray(3 * first, 3 * last), at + 3 * runLength);
    heap.set(texcoord.subarray(2 * first, 2 * last), at + 6 * runLength);
    if (wasm._tangent_share_add(last - first) !== 0) throw fail();
  }
}

// A view of `length` elements of type `Type` at `pointer` in the module's memory (valid until
// the next call). The module returns addresses as signed 32-bit numbers: from 2 GiB up they
// come back negative, hence `>>> 0` (memory may grow to 4 GiB).
function view(Type, pointer, length) {
  return new Type(wasm.HEAPU8.buffer, pointer >>> 0, length);
}

// The same elements in an array of the caller's own.
function copyOut(Type, pointer, length) {
  const copy = new Type(length);
  copy.set(view(Type, pointer, length));
  return copy;
}

// The options of the core on arrays as the option table (libtangent/core/src/option_table.cpp)
// gives them to npm: choices, the first the default. tests/python/test_option_table.py compares
// this object, index.d.ts and the table, so that they cannot drift apart.
export const optionChoices = Object.freeze({
  method: Object.freeze(['mikktspace', 'lengyel', 'flat', 'meshopt']),
  weighting: Object.freeze(['angle', 'area', 'uniform']),
  uvOrigin: Object.freeze(['top-left', 'bottom-left']),
});

function describe(choices) {
  return choices.length < 2 ? choices.join('') : `${choices.slice(0, -1).join(', ')} or ${choices[choices.length - 1]}`;
}

// options.threads checked: a whole number from 0 (every thread of maxThreads, the default) up;
// more than maxThreads runs on maxThreads (the same bits for any count).
function threadsOf(value) {
  if (value === undefined || value === 0) return maxThreads;
  if (!Number.isInteger(value) || value < 0) throw new RangeError(`libtangent: threads: ${value} is not a whole number from 0 (0: all ${maxThreads})`);
  return Math.min(value, maxThreads);
}

// The options of a call, checked: an unknown name is a TypeError (a misspelt option would
// otherwise be ignored), a value not among its choices a RangeError; unset ones take the
// table's defaults. `taken`: the names this function accepts besides threads.
function names(options, taken) {
  taken = [...taken, 'threads'];
  for (const key of Object.keys(options)) {
    if (!taken.includes(key)) throw new TypeError(`libtangent: unknown option '${key}' (options: ${taken.join(', ')})`);
  }
  const chosen = { threads: threadsOf(options.threads) };
  for (const [key, choices] of Object.entries(optionChoices)) {
    const value = options[key] ?? choices[0];
    if (!choices.includes(value)) throw new RangeError(`libtangent: ${key}: '${value}' is not ${describe(choices)}`);
    chosen[key] = value;
  }
  return chosen;
}

function deindexed(position, normal, texcoord, output, chosen) {
  requireFloat32('position', position, 3);
  requireFloat32('normal', normal, 3);
  requireFloat32('texcoord', texcoord, 2);
  const n = position.length / 3;
  if (normal.length !== n * 3) throw new RangeError(`normal: expected ${n * 3} floats, got ${normal.length}`);
  if (texcoord.length !== n * 2) throw new RangeError(`texcoord: expected ${n * 2} floats, got ${texcoord.length}`);
  if (n % 3 !== 0) throw new RangeError(`position: ${n} vertices are not whole triangles`);
  if (output !== undefined) {
    requireFloat32('output', output, 4);
    if (output.length !== n * 4) throw new RangeError(`output: expected ${n * 4} floats, got ${output.length}`);
  }
  // The corners are shared a staging run at a time as they are copied in, unless the module
  // shares this many on several threads (shareVertices' threads): from whole copies then.
  if (chosen.threads > 1 && wasm._tangent_shares_on_threads(n, chosen.threads)) {
    run(position, normal, texcoord, null, n, n, chosen, false);
  } else {
    shareCorners(position, normal, texcoord, n);
    run(null, null, null, null, n, n, chosen, false);
  }
  // A new array is memory the process has not touched yet (a page fault per 4 KiB as the copy
  // writes it, on every call); the caller's own array, reused from call to call, is not.
  if (output === undefined) return copyOut(Float32Array, wasm._tangent_corner_tangents(), n * 4);
  output.set(view(Float32Array, wasm._tangent_corner_tangents(), n * 4));
  return output;
}

/**
 * Tangents of a de-indexed triangle list (every 3 vertices one triangle), as the npm
 * `mikktspace` package computes them: xyzw per vertex, w in MikkTSpace's own convention, which
 * glTF-Transform's tangents() negates into glTF's. Pass it there as `generateTangents`.
 * options.method: 'mikktspace' (default) | 'lengyel' | 'flat' | 'meshopt'; options.weighting (lengyel):
 * 'angle' (default) | 'area' | 'uniform'. options.output: a Float32Array of 4 floats per vertex
 * that receives the tangents and is returned, instead of a new array (reused from call to call,
 * it saves the new array's first touch).
 */
export function generateTangents(position, normal, texcoord, options = {}) {
  // The npm mikktspace package's w: its function takes no uvOrigin.
  const chosen = { ...names(options, ['method', 'weighting', 'output']), uvOrigin: 'bottom-left' };
  return deindexed(position, normal, texcoord, options.output, chosen);
}

/**
 * The same de-indexed tangents with w in glTF's convention (options.uvOrigin 'top-left', the
 * default), as generateTangentsIndexed returns it: what to store as a glTF TANGENT directly.
 * Options as for generateTangentsIndexed, and options.output as for generateTangents.
 */
export function generateGltfTangents(position, normal, texcoord, options = {}) {
  const chosen = names(options, ['method', 'weighting', 'uvOrigin', 'output']);
  return deindexed(position, normal, texcoord, options.output, chosen);
}

/**
 * Tangents of an indexed triangle list. Vertices whose corners need different tangents (UV
 * seams, mirrored islands) are split: the result has `vertexCount` output vertices, each a copy
 * of input vertex `source[v]` with tangent `tangents[4v..4v+3]`, and new `indices`.
 * options.uvOrigin: 'top-left' (glTF, default: w as glTF stores it) or 'bottom-left'
 * (MikkTSpace's own w); options.method and options.weighting as for generateTangents.
 */
export function generateTangentsIndexed(position, normal, texcoord, indices, options = {}) {
  requireFloat32('position', position, 3);
  requireFloat32('normal', normal, 3);
  requireFloat32('texcoord', texcoord, 2);
  const index = indices instanceof Uint32Array ? indices : Uint32Array.from(indices);
  const vertexCount = position.length / 3;
  const report = run(position, normal, texcoord, index, vertexCount, index.length, names(options, ['method', 'weighting', 'uvOrigin']), true);
  const outputVertices = report.outputVertices;
  return {
    vertexCount: outputVertices,
    tangents: copyOut(Float32Array, wasm._tangent_vertex_tangents(), outputVertices * 4),
    source: copyOut(Uint32Array, wasm._tangent_vertex_sources(), outputVertices),
    indices: copyOut(Uint32Array, wasm._tangent_corner_vertices(), index.length),
    report,
  };
}

// V8 (Node, Chrome, Edge) runs a WebAssembly function as baseline code until it has done some
// work, then compiles an optimized version that its next call uses: a loop that is entered once
// per call, as the core's passes over every corner are, runs as baseline code to its end. So
// the first call on a large mesh took 1.3-1.7 times as long as the next one (1e6 triangles,
// Node 20, its memory already touched). Twenty calls on a small UV sphere at load, de-indexed
// and indexed, get the default method's hot functions optimized before the caller's first
// call (they cost about 35 ms of CPU at import on two busy cores).
warmUp();
function warmUp() {
  const segments = 8, calls = 20;  // 128 triangles: a seam, and degenerate ones at the poles
  const rows = segments + 1, vertices = rows * rows;
  const position = new Float32Array(3 * vertices), texcoord = new Float32Array(2 * vertices);
  for (let j = 0; j < rows; ++j) {
    for (let i = 0; i < rows; ++i) {
      const v = j * rows + i, phi = (2 * Math.PI * i) / segments, theta = (Math.PI * j) / segments;
      position.set([Math.sin(theta) * Math.cos(phi), Math.cos(theta), -Math.sin(theta) * Math.sin(phi)], 3 * v);
      texcoord.set([i / segments, j / segments], 2 * v);
    }
  }
  const indices = new Uint32Array(6 * segments * segments);
  for (let j = 0, k = 0; j < segments; ++j) {
    for (let i = 0; i < segments; ++i, k += 6) {
      const a = j * rows + i, c = a + rows;
      indices.set([a, c + 1, a + 1, a, c, c + 1], k);
    }
  }
  const corners = (array, width) => {
    const out = new Float32Array(width * indices.length);
    indices.forEach((v, c) => out.set(array.subarray(width * v, width * v + width), width * c));
    return out;
  };
  const flat = [corners(position, 3), corners(position, 3), corners(texcoord, 2)];
  for (let call = 0; call < calls; ++call) {
    if (call % 2) generateTangentsIndexed(position, position, texcoord, indices);
    else generateTangents(...flat);
  }
}
