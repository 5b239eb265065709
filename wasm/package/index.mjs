// SPDX-License-Identifier: MIT
// libtangent's MikkTSpace tangents in WebAssembly: a drop-in `generateTangents` for
// glTF-Transform's tangents(), and an indexed call that returns the vertex split.
import createTangentModule from './dist/tangent_wasm.cjs';

const wasm = await createTangentModule();

/** Resolves once the module is ready (it is by the time this module has loaded). */
export const ready = Promise.resolve();

const REPORT_FIELDS = ['triangles', 'outputVertices', 'splitVertices', 'degenerateTriangles', 'zeroUvAreaTriangles',
  'nonFiniteTriangles', 'inheritedCorners', 'fallbackFromNeighbours', 'fallbackFixed', 'mirroredCorners'];

function requireFloat32(name, array, width) {
  if (!(array instanceof Float32Array)) throw new TypeError(`${name}: expected a Float32Array`);
  if (array.length % width !== 0) throw new RangeError(`${name}: length ${array.length} is not a multiple of ${width}`);
}

// Copies the inputs into the module's memory, runs the core, frees the inputs. Throws an
// Error with the core's message when it refuses the arrays.
function run(position, normal, texcoord, indices, vertexCount, cornerCount, topLeft) {
  const arrays = [position, normal, texcoord, indices].filter((a) => a !== null);
  const pointers = arrays.map((a) => {
    const p = wasm._malloc(Math.max(4, a.byteLength));
    if (p === 0) throw new RangeError('libtangent: out of WebAssembly memory');
    return p;
  });
  try {
    // Views are taken after every allocation: growing memory replaces the buffer.
    arrays.forEach((a, i) => new Uint8Array(wasm.HEAPU8.buffer, pointers[i], a.byteLength)
      .set(new Uint8Array(a.buffer, a.byteOffset, a.byteLength)));
    const status = wasm._tangent_run(pointers[0], pointers[1], pointers[2], indices ? pointers[3] : 0,
      vertexCount, cornerCount, topLeft ? 1 : 0);
    if (status !== 0) throw new Error(`libtangent: ${wasm.UTF8ToString(wasm._tangent_error())}`);
  } finally {
    pointers.forEach((p) => wasm._free(p));
  }
  const values = new Float64Array(wasm.HEAPF64.buffer, wasm._tangent_report(), REPORT_FIELDS.length);
  return Object.fromEntries(REPORT_FIELDS.map((name, i) => [name, values[i]]));
}

/**
 * Tangents of a de-indexed triangle list (every 3 vertices one triangle), as the npm
 * `mikktspace` package computes them: xyzw per vertex, w in MikkTSpace's own convention, which
 * glTF-Transform's tangents() negates into glTF's. Pass it there as `generateTangents`.
 */
export function generateTangents(position, normal, texcoord) {
  requireFloat32('position', position, 3);
  requireFloat32('normal', normal, 3);
  requireFloat32('texcoord', texcoord, 2);
  const n = position.length / 3;
  if (normal.length !== n * 3) throw new RangeError(`normal: expected ${n * 3} floats, got ${normal.length}`);
  if (texcoord.length !== n * 2) throw new RangeError(`texcoord: expected ${n * 2} floats, got ${texcoord.length}`);
  if (n % 3 !== 0) throw new RangeError(`position: ${n} vertices are not whole triangles`);
  run(position, normal, texcoord, null, n, n, false);
  return new Float32Array(wasm.HEAPF32.buffer, wasm._tangent_corner_tangents(), n * 4).slice();
}

/**
 * Tangents of an indexed triangle list. Vertices whose corners need different tangents (UV
 * seams, mirrored islands) are split: the result has `vertexCount` output vertices, each a copy
 * of input vertex `source[v]` with tangent `tangents[4v..4v+3]`, and new `indices`.
 * options.uvOrigin: 'top-left' (glTF, default: w as glTF stores it) or 'bottom-left'
 * (MikkTSpace's own w).
 */
export function generateTangentsIndexed(position, normal, texcoord, indices, options = {}) {
  requireFloat32('position', position, 3);
  requireFloat32('normal', normal, 3);
  requireFloat32('texcoord', texcoord, 2);
  const uvOrigin = options.uvOrigin ?? 'top-left';
  if (uvOrigin !== 'top-left' && uvOrigin !== 'bottom-left')
    throw new RangeError(`uvOrigin: expected 'top-left' or 'bottom-left', got ${uvOrigin}`);
  const index = indices instanceof Uint32Array ? indices : Uint32Array.from(indices);
  const vertexCount = position.length / 3;
  const report = run(position, normal, texcoord, index, vertexCount, index.length, uvOrigin === 'top-left');
  const outputVertices = report.outputVertices;
  return {
    vertexCount: outputVertices,
    tangents: new Float32Array(wasm.HEAPF32.buffer, wasm._tangent_vertex_tangents(), outputVertices * 4).slice(),
    source: new Uint32Array(wasm.HEAPU32.buffer, wasm._tangent_vertex_sources(), outputVertices).slice(),
    indices: new Uint32Array(wasm.HEAPU32.buffer, wasm._tangent_corner_vertices(), index.length).slice(),
    report,
  };
}
