// SPDX-License-Identifier: MIT
/** Resolves once the module is ready (it is by the time the module has loaded). */
export declare const ready: Promise<void>;

/** The command line's names (`tangent bake --method`, `--weighting`). */
export type Method = 'mikktspace' | 'lengyel' | 'flat' | 'meshopt';
export type Weighting = 'angle' | 'area' | 'uniform';
/** Where UV (0, 0) is; it decides the sign of w. */
export type UvOrigin = 'top-left' | 'bottom-left';

/**
 * Every option's choices, the first the default: the option table every front end shares
 * (the `tangent` command's --method, --weighting; Python's uv_origin). An unknown option is a
 * TypeError, a value not among its choices a RangeError.
 */
export declare const optionChoices: {
  readonly method: readonly Method[];
  readonly weighting: readonly Weighting[];
  readonly uvOrigin: readonly UvOrigin[];
};

export interface MethodOptions {
  /** 'mikktspace' (default), 'lengyel', 'flat' or 'meshopt' (meshoptimizer's default weighting). */
  method?: Method;
  /** Lengyel's weighting: 'angle' (default), 'area' or 'uniform'. */
  weighting?: Weighting;
  /**
   * Threads the call runs on: 0 (default) for maxThreads; more than maxThreads runs on
   * maxThreads. Only the threaded build (`libtangent-wasm/threads`) has more than 1. The output
   * is the same for any count. A number that is not a whole number from 0 is a RangeError.
   */
  threads?: number;
}

/**
 * The most threads a call runs on: 1 from `libtangent-wasm`; from `libtangent-wasm/threads`
 * (Node, or a cross-origin isolated page), its pool of workers and the calling thread: one
 * fewer workers than the machine's cores, at most 15, or in Node LIBTANGENT_WASM_THREADS
 * threads in all where that variable is set as the module loads.
 */
export declare const maxThreads: number;

export interface DeindexedOptions extends MethodOptions {
  /**
   * Receives the tangents (4 floats per vertex) and is returned, instead of a new array: an
   * array reused from call to call saves the new array's first touch of its memory.
   */
  output?: Float32Array;
}

/**
 * Tangents of a de-indexed triangle list, xyzw per vertex, w in MikkTSpace's own convention
 * (as the npm `mikktspace` package returns it; glTF-Transform's tangents() negates it). The
 * drop-in for that package; every other function returns glTF's w.
 */
export declare function generateTangents(position: Float32Array, normal: Float32Array, texcoord: Float32Array,
  options?: DeindexedOptions): Float32Array;

export interface GltfDeindexedOptions extends DeindexedOptions {
  /** 'top-left' (glTF; default) or 'bottom-left' (MikkTSpace's own w). */
  uvOrigin?: UvOrigin;
}

/** The same tangents with w in glTF's convention (what a glTF TANGENT stores). */
export declare function generateGltfTangents(position: Float32Array, normal: Float32Array, texcoord: Float32Array,
  options?: GltfDeindexedOptions): Float32Array;

/** The core's Report, as `tangent bake --report` writes it (the `tangents` object). */
export interface TangentReport {
  method: Method;
  /** '' for flat. */
  weighting: Weighting | '';
  triangles: number;
  corners: number;
  degenerateTriangles: number;
  zeroUvAreaTriangles: number;
  nonFiniteTriangles: number;
  mirroredCorners: number;
  splitVertices: number;
  nonManifoldFaces: number;
  invalidNormals: number;
  inheritedCorners: number;
  fallbackFromNeighbours: number;
  fallbackFixed: number;
  outputVertices: number;
}

export interface IndexedTangents {
  /** Output vertices: the input vertices, then the copies the split adds. */
  vertexCount: number;
  /** xyzw per output vertex. */
  tangents: Float32Array;
  /** The input vertex each output vertex copies. */
  source: Uint32Array;
  /** The triangle list over the output vertices. */
  indices: Uint32Array;
  report: TangentReport;
}

export interface IndexedOptions extends MethodOptions {
  /** 'top-left' (glTF; default) or 'bottom-left' (MikkTSpace's own w). */
  uvOrigin?: UvOrigin;
}

export declare function generateTangentsIndexed(position: Float32Array, normal: Float32Array, texcoord: Float32Array,
  indices: Uint32Array | ArrayLike<number>, options?: IndexedOptions): IndexedTangents;
