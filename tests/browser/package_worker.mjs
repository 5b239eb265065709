// SPDX-License-Identifier: MIT
// The package test's module worker: the same cases as the page, off the main thread, computed as
// soon as the package has loaded (a message sent to a module worker while its imports' top-level
// await runs can arrive before any onmessage exists). The page passes the cases' folder as ?base=.
import * as api from 'libtangent-wasm';
import { computeCases } from './cases.mjs';

const base = new URL(new URLSearchParams(self.location.search).get('base'), self.location.href).href;
try {
  self.postMessage({ result: await computeCases(api, base) });
} catch (e) {
  self.postMessage({ error: e.message });
}
