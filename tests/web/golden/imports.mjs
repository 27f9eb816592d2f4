// Node resolve hook for the page's generated imports (web/build.mjs maps the same names for
// esbuild): 'prt:constants' → GENDIR/constants.js, 'prt:shaders/NAME' → GENDIR/shaders/NAME.
// Registered by check.mjs with { data: { gen: GENDIR } }.
import path from 'node:path';
import { pathToFileURL } from 'node:url';

let gen = null;
export function initialize(data) {
  gen = data.gen;
}
export async function resolve(specifier, context, next) {
  if (!specifier.startsWith('prt:')) return next(specifier, context);
  const name = specifier.slice(4);
  const file = path.join(gen, name === 'constants' ? 'constants.js' : name);
  return { url: pathToFileURL(file).href, shortCircuit: true };
}
