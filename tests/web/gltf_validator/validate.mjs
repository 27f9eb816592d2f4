// The Khronos glTF validator (npm gltf-validator, pinned by web/package-lock.json) on each file
// named: prints one JSON object, {FILE: {errors, warnings, infos, hints, messages: [[severity,
// code, pointer], ...]}}. Severity: 0 error, 1 warning, 2 information, 3 hint.
//
//   node validate.mjs A.glb B.glb ...
import fs from 'node:fs';
import { createRequire } from 'node:module';

const require = createRequire(new URL('../../../web/package.json', import.meta.url));
const validator = require('gltf-validator');
const out = {};
for (const file of process.argv.slice(2)) {
  const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
    maxIssues: 1000,
  });
  const i = report.issues;
  out[file] = {
    errors: i.numErrors, warnings: i.numWarnings, infos: i.numInfos, hints: i.numHints,
    messages: i.messages.map((m) => [m.severity, m.code, m.pointer || '']),
  };
}
console.log(JSON.stringify(out));
