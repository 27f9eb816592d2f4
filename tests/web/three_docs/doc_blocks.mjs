// The code blocks of docs/three.md that make its first app, as files: each fenced block whose
// info string names a file after the language (```html index.html, ```js main.js,
// ```sh install) is written to OUT_DIR under that name (a shell block as NAME.sh), byte for
// byte; the names are printed one a line. So the test runs what the doc says, and the two
// cannot drift.   node doc_blocks.mjs DOC OUT_DIR
import fs from 'node:fs';
import path from 'node:path';

const [doc, out] = process.argv.slice(2);
const lines = fs.readFileSync(doc, 'utf8').split('\n');
const written = [];
for (let i = 0; i < lines.length; ++i) {
  const open = /^```(\w+)\s+(\S+)\s*$/.exec(lines[i]);
  if (!open) continue;
  const end = lines.indexOf('```', i + 1);
  if (end < 0) throw new Error(`${doc}:${i + 1}: the block is not closed`);
  const name = open[1] === 'sh' ? `${open[2]}.sh` : open[2];
  if (written.includes(name)) throw new Error(`${doc}:${i + 1}: a second block named ${name}`);
  fs.writeFileSync(path.join(out, name), lines.slice(i + 1, end).join('\n') + '\n');
  written.push(name);
  i = end;
}
console.log(written.join('\n'));
