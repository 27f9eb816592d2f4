// Bundles the browser viewer into OUTDIR (default dist/): index.html, prt-web.js (one classic
// script: three.js, lil-gui, src/*.js and the GLSL of ../shaders, no ES-module imports, so the
// page works from file://) and THIRD_PARTY_LICENSES.txt.  Usage: node build.mjs [OUTDIR]
// GLSL files are imported as text with `#include "NAME"` lines replaced by ../shaders/NAME,
// the same rule as cmake/EmbedShaders.cmake for the desktop viewer.
import * as esbuild from 'esbuild';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const out = path.resolve(process.argv[2] ?? path.join(here, 'dist'));
const shared = path.join(here, '..', 'shaders');

const glsl = {
  name: 'glsl',
  setup(build) {
    build.onLoad({ filter: /\.(glsl|vert|frag)$/ }, (args) => {
      const text = fs.readFileSync(args.path, 'utf8').replace(
        /^#include "([A-Za-z0-9_.]+)"\s*$/gm, (_, name) => {
          const p = path.join(shared, name);
          if (!fs.existsSync(p)) throw new Error(`${args.path}: #include "${name}" not found in shaders/`);
          return fs.readFileSync(p, 'utf8');
        });
      return { contents: text, loader: 'text' };
    });
  },
};

fs.mkdirSync(out, { recursive: true });
await esbuild.build({
  entryPoints: [path.join(here, 'src', 'main.js')],
  bundle: true,
  format: 'iife',
  target: 'es2020',
  minify: true,
  legalComments: 'none',
  outfile: path.join(out, 'prt-web.js'),
  plugins: [glsl],
  logLevel: 'warning',
});
fs.copyFileSync(path.join(here, 'src', 'index.html'), path.join(out, 'index.html'));
const licences = ['three', 'lil-gui'].map((p) => {
  const dir = path.join(here, 'node_modules', p);
  const pkg = JSON.parse(fs.readFileSync(path.join(dir, 'package.json'), 'utf8'));
  const file = fs.readdirSync(dir).find((f) => /^licen[cs]e/i.test(f));
  return `== ${p} ${pkg.version} (${pkg.license}) ==\n` + (file ? fs.readFileSync(path.join(dir, file), 'utf8') : '');
});
fs.writeFileSync(path.join(out, 'THIRD_PARTY_LICENSES.txt'),
  'prt-web.js bundles the following packages.\n\n' + licences.join('\n'));
