// Serves a baked 3D Tiles world (/world/), CesiumJS from scripts/node_modules (/cesium/) and the
// viewer page (/) on 127.0.0.1 only.
//
//   node scripts/viewer/serve.mjs WORLD_DIR [--port 8080] [--open]
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const cesiumBuild = path.join(here, '..', 'node_modules', 'cesium', 'Build', 'Cesium');
const types = {
  '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.css': 'text/css',
  '.json': 'application/json', '.glb': 'model/gltf-binary', '.gltf': 'model/gltf+json', '.png': 'image/png',
  '.jpg': 'image/jpeg', '.svg': 'image/svg+xml', '.wasm': 'application/wasm', '.subtree': 'application/octet-stream',
};

// The file `urlPath` names under `root`, or null when it leaves root.
function under(root, urlPath) {
  const file = path.resolve(root, '.' + path.posix.normalize('/' + urlPath));
  return file === root || file.startsWith(root + path.sep) ? file : null;
}

export function serveWorld(worldDir, port = 8080) {
  const world = path.resolve(worldDir);
  const routes = [['/world/', world], ['/cesium/', cesiumBuild], ['/', here]];
  const server = http.createServer((request, response) => {
    const url = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
    const [prefix, root] = routes.find(([p]) => url.startsWith(p));
    const file = under(root, url === '/' ? 'index.html' : url.slice(prefix.length));
    fs.readFile(file ?? '', (error, data) => {
      if (error || !file) {
        response.writeHead(404, { 'Content-Type': 'text/plain' });
        response.end('not found: ' + url + '\n');
        return;
      }
      response.writeHead(200, { 'Content-Type': types[path.extname(file).toLowerCase()] ?? 'application/octet-stream' });
      response.end(data);
    });
  });
  return new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(port, '127.0.0.1', () => resolve({ server, url: `http://127.0.0.1:${server.address().port}/` }));
  });
}

// Run as a program (not imported by screenshot.mjs): node resolves links in import.meta.url, not in
// argv[1], so a checkout reached through a link must compare real paths (else nothing is served).
if (process.argv[1] && fs.realpathSync(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const args = process.argv.slice(2);
  const world = args[0];
  const portAt = args.indexOf('--port');
  const { url } = await serveWorld(world, portAt >= 0 ? Number(args[portAt + 1]) : 8080);
  console.log(`serving ${path.resolve(world)} at ${url} (Ctrl-C stops)`);
  if (args.includes('--open')) {
    const opener = spawn('xdg-open', [url], { stdio: 'ignore', detached: true });
    opener.on('error', () => console.log('no xdg-open: open the address in a browser'));
    opener.unref();
  }
}
