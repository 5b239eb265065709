// SPDX-License-Identifier: MIT
// The threaded build's page of the package test (package_test.py): served cross-origin
// isolated, it imports `libtangent-wasm/threads` through an import map, computes the cases of
// threads.json on all of maxThreads, and reports them with crossOriginIsolated and maxThreads
// in document.body.dataset.result (state "done"), or the error in dataset.state.
import * as api from 'libtangent-wasm/threads';
import { computeCases } from './cases.mjs';

try {
  const base = new URL('.', document.baseURI).href;
  const cases = await computeCases(api, base, 'threads.json', { threads: api.maxThreads });
  document.body.dataset.result = JSON.stringify({ isolated: self.crossOriginIsolated, maxThreads: api.maxThreads, cases });
  document.body.dataset.state = 'done';
} catch (e) {
  document.body.dataset.state = `error: ${e.message}`;
}
