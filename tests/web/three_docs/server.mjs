// The network docs/three.md's reader has, without a network (tests/web/three_docs/run.sh):
// one local http server that is both
//   * an npm registry for the packages named on the command line (`npm pack`ed from local
//     folders: three from web/node_modules), so the doc's `npm install three` runs as written
//     with npm_config_registry pointing here — /NAME is the packument, /-/tarballs/FILE the .tgz;
//   * a static file server for the app folder (what `python3 -m http.server` does for the
//     reader), which puts tests/web/three_docs/probe.js at the start of every HTML page's <head>
//     (the file on disk stays the doc's, byte for byte).
//
//   node server.mjs APP_DIR TARBALL_DIR PORT_FILE PKG_DIR...
// Writes the port to PORT_FILE once listening; runs until killed.
import crypto from 'node:crypto';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const [app, tarballs, portFile, ...pkgDirs] = process.argv.slice(2);
if (!app || !tarballs || !portFile) {
  console.error('usage: node server.mjs APP_DIR TARBALL_DIR PORT_FILE PKG_DIR...');
  process.exit(2);
}

// The packages: each folder packed once (npm pack of an installed package gives the files its
// package.json publishes, as the registry would).
fs.mkdirSync(tarballs, { recursive: true });
const packages = new Map();
for (const dir of pkgDirs) {
  const manifest = JSON.parse(fs.readFileSync(path.join(dir, 'package.json'), 'utf8'));
  const file = execFileSync('npm', ['pack', dir, '--ignore-scripts', '--pack-destination', tarballs, '--silent'],
                            { encoding: 'utf8', env: process.env }).trim().split('\n').pop();
  const bytes = fs.readFileSync(path.join(tarballs, file));
  packages.set(manifest.name, { manifest, file, bytes });
}

const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json',
                '.glb': 'model/gltf-binary', '.css': 'text/css', '.png': 'image/png' };
const probe = '<script src="/__prt_probe.js"></script>';

const server = http.createServer((req, res) => {
  const url = new URL(req.url, 'http://localhost');
  const send = (status, type, body) => {
    res.writeHead(status, { 'content-type': type, 'cache-control': 'no-store' });
    res.end(body);
  };
  const name = decodeURIComponent(url.pathname.slice(1));
  if (url.pathname.startsWith('/-/tarballs/')) {
    const p = [...packages.values()].find((q) => q.file === path.basename(url.pathname));
    return p ? send(200, 'application/octet-stream', p.bytes) : send(404, 'text/plain', 'no such tarball');
  }
  if (packages.has(name)) {
    const { manifest, file, bytes } = packages.get(name);
    const version = {
      ...manifest,
      _id: `${manifest.name}@${manifest.version}`,
      dist: {
        tarball: `http://127.0.0.1:${server.address().port}/-/tarballs/${file}`,
        shasum: crypto.createHash('sha1').update(bytes).digest('hex'),
        integrity: `sha512-${crypto.createHash('sha512').update(bytes).digest('base64')}`,
      },
    };
    return send(200, 'application/json', JSON.stringify({
      name: manifest.name, 'dist-tags': { latest: manifest.version }, versions: { [manifest.version]: version },
    }));
  }
  if (url.pathname === '/__prt_probe.js') return send(200, 'text/javascript', fs.readFileSync(path.join(here, 'probe.js')));
  if (url.pathname.startsWith('/-/') || req.method !== 'GET') return send(404, 'application/json', '{}');
  // Static files of the app folder.
  let file = path.join(path.resolve(app), path.normalize(url.pathname === '/' ? '/index.html' : url.pathname));
  if (!file.startsWith(path.resolve(app))) return send(403, 'text/plain', 'outside the app');
  try {
    if (fs.statSync(file).isDirectory()) file = path.join(file, 'index.html');
    let body = fs.readFileSync(file);
    const ext = path.extname(file);
    if (ext === '.html') {
      const text = body.toString('utf8');
      // After <head>, else after the doctype (a page without <head> stays in standards mode).
      const m = /<head[^>]*>/i.exec(text) || /<!doctype[^>]*>/i.exec(text);
      const end = m ? m.index + m[0].length : 0;
      body = text.slice(0, end) + probe + text.slice(end);
    }
    send(200, types[ext] || 'application/octet-stream', body);
  } catch {
    send(404, 'text/plain', `not found: ${url.pathname}`);
  }
});
server.listen(0, '127.0.0.1', () => fs.writeFileSync(portFile, String(server.address().port)));
