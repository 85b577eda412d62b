// Bundle the viewer (js/src) and the parts of three.js it uses into one ES module, the
// anywidget front end shipped as package data: puma_course/viz/static/viewer.js.
// Run `npm ci && npm run build` here after editing js/src; tests/viz/test_viewer_js.py checks
// that the committed bundle was built from the current sources (the hash in its first line).
import { createHash } from "node:crypto";
import { readFileSync, readdirSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

import { build } from "esbuild";

const here = dirname(fileURLToPath(import.meta.url));
const src = join(here, "src");

/** sha256 over the sources (name and text of each file, sorted) and the pinned three.js version. */
export function sourceHash() {
  const h = createHash("sha256");
  for (const name of readdirSync(src).filter((n) => n.endsWith(".js")).sort()) {
    h.update(`${name}\n${readFileSync(join(src, name), "utf8")}\n`);
  }
  h.update(`three ${JSON.parse(readFileSync(join(here, "package.json"), "utf8")).devDependencies.three}\n`);
  return h.digest("hex");
}

const three = JSON.parse(readFileSync(join(here, "node_modules/three/package.json"), "utf8")).version;
await build({
  entryPoints: [join(src, "viewer.js")],
  outfile: join(here, "..", "puma_course", "viz", "static", "viewer.js"),
  bundle: true,
  format: "esm",
  minify: true,
  target: "es2020",
  legalComments: "eof",
  banner: { js: `// puma_course viewer: built by js/build.mjs from js/src (sources sha256 ${sourceHash()}) with three.js ${three} (MIT)` },
});
console.log(`built puma_course/viz/static/viewer.js (three.js ${three})`);
