// SPDX-License-Identifier: MIT
// The page of the package test (package_test.py): imports libtangent-wasm as a browser does
// (natively through an import map, or bundled by esbuild), computes the tangents of every case
// on the main thread and in a module worker (the page's data-worker), and reports them in
// document.body.dataset.result (state "done"), or the error in dataset.state ("error: ...").
import * as api from 'libtangent-wasm';
import { computeCases } from './cases.mjs';

function inWorker(url, base) {
  return new Promise((resolve, reject) => {
    const workerUrl = new URL(url, document.baseURI);
    workerUrl.searchParams.set('base', base);
    const worker = new Worker(workerUrl, { type: 'module' });
    worker.onmessage = (event) => (event.data.error ? reject(new Error(`worker: ${event.data.error}`)) : resolve(event.data.result));
    worker.onerror = (event) => reject(new Error(`worker: ${event.message || 'failed to load'}`));
  });
}

try {
  const base = new URL('.', document.baseURI).href;
  const mainThread = await computeCases(api, base);
  const worker = document.body.dataset.worker ? await inWorker(document.body.dataset.worker, base) : null;
  document.body.dataset.result = JSON.stringify({ mainThread, worker });
  document.body.dataset.state = 'done';
} catch (e) {
  document.body.dataset.state = `error: ${e.message}`;
}
