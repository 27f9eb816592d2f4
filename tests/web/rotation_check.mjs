// Runs the page's SH rotation (web/src/sh.js, the module bundled into prt-web.js) on the cases
// in INPUT.json: { cases: [{ bands, euler: [x, y, z] degrees, light: [B²·3 numbers] }] } and
// prints { cases: [{ rotated: [...] }] } on stdout. Driven by tests/web/test_web.cpp, which
// compares with the C++ sh::Rotation.  Usage: node rotation_check.mjs INPUT.json
import fs from 'node:fs';
import { rotateLight, rotationEulerXYZ } from '../../web/src/sh.js';

const input = JSON.parse(fs.readFileSync(process.argv[2], 'utf8'));
const cases = input.cases.map((c) => {
  const R = rotationEulerXYZ(c.euler[0], c.euler[1], c.euler[2]);
  const out = rotateLight(c.bands, R, Float64Array.from(c.light), new Float64Array(c.bands * c.bands * 3));
  return { rotated: Array.from(out) };
});
process.stdout.write(JSON.stringify({ cases }));
