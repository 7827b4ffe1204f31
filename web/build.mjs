// Builds the page into OUT (default: dist/): src/main.js bundled by esbuild with three.js and
// uPlot from node_modules (pinned by package-lock.json; no CDN), the HTML and the styles.
// Usage: node build.mjs [OUT]
import { copyFileSync, existsSync, mkdirSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
if (!existsSync(join(here, "node_modules/esbuild"))) {
  console.error("web/node_modules is missing: run `npm ci --prefix web` (scripts/setup does)");
  process.exit(1);
}
const { build } = await import("esbuild");
const out = resolve(process.argv[2] ?? join(here, "dist"));
mkdirSync(out, { recursive: true });
await build({
  entryPoints: [join(here, "src/main.js")],
  bundle: true,
  minify: true,
  format: "esm",
  target: "es2020",
  outfile: join(out, "app.js"),
  logLevel: "warning",
});
copyFileSync(join(here, "src/index.html"), join(out, "index.html"));
copyFileSync(join(here, "src/style.css"), join(out, "style.css"));
copyFileSync(join(here, "node_modules/uplot/dist/uPlot.min.css"), join(out, "uPlot.min.css"));
console.log(`page built into ${out}`);
