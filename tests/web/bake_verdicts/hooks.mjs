// Node module hooks for verdicts.mjs: the page's generated imports resolved into GENDIR as
// web/build.mjs resolves them for esbuild ('prt:constants' → constants.js, 'prt:NAME' → NAME),
// and the flattened GLSL stages (.vert, .frag) loaded as text, so prtkit-three's sources run as
// they are bundled. Registered with { data: { gen: GENDIR } }.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

let gen = null;
export function initialize(data) {
  gen = data.gen;
}
export async function resolve(specifier, context, next) {
  if (!specifier.startsWith('prt:')) return next(specifier, context);
  const name = specifier.slice(4);
  return { url: pathToFileURL(path.join(gen, name === 'constants' ? 'constants.js' : name)).href, shortCircuit: true };
}
export async function load(url, context, next) {
  if (!/\.(vert|frag)$/.test(url)) return next(url, context);
  const text = fs.readFileSync(fileURLToPath(url), 'utf8');
  return { format: 'module', source: `export default ${JSON.stringify(text)};`, shortCircuit: true };
}
