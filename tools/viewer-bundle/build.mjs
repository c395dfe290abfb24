// Rebuild the vendored viewer bundle: `npm ci && npm run build` in this folder (node >= 18).
// Writes ../../geargen/report/viewer/three-bundle.min.js and three's licence beside it.
import { build } from "esbuild";
import { copyFileSync, readFileSync } from "node:fs";

const out = new URL("../../geargen/report/viewer/", import.meta.url);
const three = JSON.parse(readFileSync(new URL("node_modules/three/package.json", import.meta.url)));
await build({
  entryPoints: [new URL("entry.js", import.meta.url).pathname],
  outfile: new URL("three-bundle.min.js", out).pathname,
  bundle: true,
  minify: true,
  format: "iife",
  target: "es2020",
  legalComments: "eof",
  banner: { js: `/* three.js ${three.version} (MIT licence, see three-LICENSE.txt): ` +
                "WebGLRenderer, GLTFLoader, OrbitControls and the classes geargen's review.js uses, " +
                "as the global THREE; built by tools/viewer-bundle */" },
});
copyFileSync(new URL("node_modules/three/LICENSE", import.meta.url), new URL("three-LICENSE.txt", out));
console.log(`three ${three.version} bundled into ${out.pathname}`);
