// SPDX-License-Identifier: MIT
/** Resolves once the module is ready (it is by the time the module has loaded). */
export declare const ready: Promise<void>;

/** The command line's names (`tangent bake --method`, `--weighting`). */
export type Method = 'mikktspace' | 'lengyel' | 'flat' | 'meshopt';
export type Weighting = 'angle' | 'area' | 'uniform';

export interface MethodOptions {
  /** 'mikktspace' (default), 'lengyel', 'flat' or 'meshopt' (meshoptimizer's default weighting). */
  method?: Method;
  /** Lengyel's weighting: 'angle' (default), 'area' or 'uniform'. */
  weighting?: Weighting;
}

export interface DeindexedOptions extends MethodOptions {
  /**
   * Receives the tangents (4 floats per vertex) and is returned, instead of a new array: an
   * array reused from call to call saves the new array's first touch of its memory.
   */
  output?: Float32Array;
}

/**
 * Tangents of a de-indexed triangle list, xyzw per vertex, w in MikkTSpace's own convention
 * (as the npm `mikktspace` package returns it; glTF-Transform's tangents() negates it).
 */
export declare function generateTangents(position: Float32Array, normal: Float32Array, texcoord: Float32Array,
  options?: DeindexedOptions): Float32Array;

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
  uvOrigin?: 'top-left' | 'bottom-left';
}

export declare function generateTangentsIndexed(position: Float32Array, normal: Float32Array, texcoord: Float32Array,
  indices: Uint32Array | ArrayLike<number>, options?: IndexedOptions): IndexedTangents;
