// Bundles the page's script (src/main.js with three.js) into one file for `nodus view` to inline:
//   node web/build.mjs OUTFILE
// Run by the build (cmake/viewer.cmake) from web/node_modules, which scripts/setup.sh installs (npm ci).
import { build } from 'esbuild';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const here = path.dirname(fileURLToPath(import.meta.url));
const outfile = process.argv[2] || path.join(here, 'dist', 'viewer.js');
await build({
  entryPoints: [path.join(here, 'src', 'main.js')],
  bundle: true,
  minify: true,
  format: 'iife',
  target: 'es2020',
  charset: 'ascii',  // the bundle goes into a C++ string literal and an HTML page
  legalComments: 'eof',  // three.js's MIT notice stays with its code in every page
  outfile,
  logLevel: 'warning',
});
