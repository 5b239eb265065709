// SPDX-License-Identifier: MIT
// Builds the reference page into OUT_DIR: page.js (page.mjs and the Khronos engine bundled by
// esbuild), index.html, the engine's libs/ (libktx, mikktspace) beside it.
// The engine prefilters its environment at start-up with 1024-2048 samples per texel on 256^2
// cube faces and a 1024^2 BRDF table: minutes under SwiftShader. The tests draw with the
// punctual light only (IBL off: the environment's weight is zero), so the bundle lowers those
// sizes and counts; each replacement must match once, or the build fails (a new engine version
// that renamed them would otherwise be silently slow).
// Usage: node build_page.mjs OUT_DIR   (run from anywhere; modules resolve from tests/node)
import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";
import { fileURLToPath } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const out = path.resolve(process.argv[2]);
const require = createRequire(path.join(here, "../node/package.json"));
const { build } = require("esbuild");
const engineFolder = path.dirname(require.resolve("@khronosgroup/gltf-viewer/package.json"));

const lowered = [
  ["this.textureSize = 256;", "this.textureSize = 32;"],
  ["this.ggxSampleCount = 1024;", "this.ggxSampleCount = 8;"],
  ["this.lambertianSampleCount = 2048;", "this.lambertianSampleCount = 8;"],
  ["this.sheenSamplCount = 64;", "this.sheenSamplCount = 8;"],
  ["this.lutResolution = 1024;", "this.lutResolution = 32;"],
  ['shader.updateUniform("u_sampleCount", 512);', 'shader.updateUniform("u_sampleCount", 8);'],
];
const lowerSampling = {
  name: "lower-ibl-sampling",
  setup(b) {
    b.onLoad({ filter: /gltf-viewer[\\/]dist[\\/].*\.js$/ }, async (args) => {
      let text = await fs.promises.readFile(args.path, "utf8");
      for (const [from, to] of lowered) {
        const count = text.split(from).length - 1;
        if (count !== 1) throw new Error(`${args.path}: expected "${from}" once, found it ${count} times`);
        text = text.replace(from, to);
      }
      return { contents: text, loader: "js" };
    });
  },
};

fs.mkdirSync(path.join(out, "libs"), { recursive: true });
await build({
  entryPoints: [path.join(here, "page.mjs")],
  bundle: true,
  format: "esm",
  outfile: path.join(out, "page.js"),
  nodePaths: [path.join(here, "../node/node_modules")],
  plugins: [lowerSampling],
  logLevel: "warning",
});
fs.copyFileSync(path.join(here, "index.html"), path.join(out, "index.html"));
for (const lib of fs.readdirSync(path.join(engineFolder, "dist/libs")))
  fs.copyFileSync(path.join(engineFolder, "dist/libs", lib), path.join(out, "libs", lib));
