// SPDX-License-Identifier: MIT
// Runs the Khronos glTF validator on each file given; prints one JSON line per file and
// exits 1 when any file has errors. Usage: node validate.mjs FILE...
import fs from 'node:fs';
import path from 'node:path';
import validator from 'gltf-validator';

let failed = 0;
for (const file of process.argv.slice(2)) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 50,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.join(path.dirname(file), decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(new Uint8Array(data)));
      }),
  });
  const errors = report.issues.messages.filter((m) => m.severity === 0);
  console.log(JSON.stringify({
    file,
    errors: report.issues.numErrors,
    warnings: report.issues.numWarnings,
    firstErrors: errors.slice(0, 5).map((m) => `${m.code} ${m.pointer ?? ''}: ${m.message}`),
  }));
  if (report.issues.numErrors > 0) failed++;
}
process.exit(failed ? 1 : 0);
