// SPDX-License-Identifier: MIT
// The package's "require" export: libtangent-wasm is an ES module (its WebAssembly is
// instantiated by a top-level await), so require() gets this message instead of a stack.
throw new Error(
  "libtangent-wasm is an ES module package and cannot be loaded with require(): use " +
  "`import { generateTangents } from 'libtangent-wasm'`, or from CommonJS " +
  "`const { generateTangents } = await import('libtangent-wasm')`.");
