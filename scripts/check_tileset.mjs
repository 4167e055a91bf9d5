// Loads a baked 3D Tiles tileset the way a streaming client does and checks it:
//   node scripts/check_tileset.mjs WORLD_FOLDER
// The folder is served over HTTP on 127.0.0.1 (an ephemeral port, closed at the end) and read with
// loaders.gl's 3D Tiles loader (@loaders.gl/3d-tiles, pinned in scripts/package.json), which parses
// tileset.json, expands implicit tiling from its subtree files, and parses every tile's glTF content.
// Checks: the traversal finds every .glb on disk and nothing else; every content parses as glTF;
// every vertex (after the glTF node transforms and the y-up to z-up turn) lies in its tile's bounding
// box; children's boxes lie in their parent's; geometric errors decrease strictly from parent to child.
// Prints a summary; exits 0 when every check passes, 1 otherwise, 3 on bad usage.
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import {load} from '@loaders.gl/core';
import {Tiles3DLoader} from '@loaders.gl/3d-tiles';

const folder = process.argv[2];
if (!folder || !fs.existsSync(path.join(folder, 'tileset.json'))) {
  console.error('usage: node check_tileset.mjs WORLD_FOLDER (with a tileset.json)');
  process.exit(3);
}

const problems = [];
const problem = (text) => { if (problems.length < 50) problems.push(text); };
const TOLERANCE_M = 0.01;

function serve(root) {
  const server = http.createServer((req, res) => {
    const file = path.join(root, decodeURIComponent(new URL(req.url, 'http://localhost').pathname));
    if (!file.startsWith(path.resolve(root))) { res.writeHead(403); res.end(); return; }
    fs.readFile(file, (err, data) => {
      if (err) { res.writeHead(404); res.end(); return; }
      res.writeHead(200); res.end(data);
    });
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

function glbFilesOnDisk(root) {
  const out = [];
  const walk = (dir) => {
    for (const e of fs.readdirSync(dir, {withFileTypes: true})) {
      const p = path.join(dir, e.name);
      if (e.isDirectory()) walk(p);
      else if (e.name.endsWith('.glb')) out.push(path.relative(root, p));
    }
  };
  walk(path.join(root, 'tiles'));
  return out.sort();
}

// Box as [min x, min y, min z, max x, max y, max z] of an axis-aligned 3D Tiles box.
function boxExtent(box) {
  if (box[4] !== 0 || box[5] !== 0 || box[6] !== 0 || box[8] !== 0 || box[9] !== 0 || box[10] !== 0) {
    problem(`box ${JSON.stringify(box)} is not axis-aligned`);
  }
  return [box[0] - Math.abs(box[3]), box[1] - Math.abs(box[7]), box[2] - Math.abs(box[11]),
          box[0] + Math.abs(box[3]), box[1] + Math.abs(box[7]), box[2] + Math.abs(box[11])];
}

// The box of implicit tile (level, x, y) inside the root box: halved in x and y per level.
function implicitExtent(rootExtent, level, x, y) {
  const n = 2 ** level;
  const w = (rootExtent[3] - rootExtent[0]) / n, h = (rootExtent[4] - rootExtent[1]) / n;
  return [rootExtent[0] + x * w, rootExtent[1] + y * h, rootExtent[2],
          rootExtent[0] + (x + 1) * w, rootExtent[1] + (y + 1) * h, rootExtent[5]];
}

function inside(inner, outer, tol) {
  for (let k = 0; k < 3; ++k) {
    if (inner[k] < outer[k] - tol || inner[3 + k] > outer[3 + k] + tol) return false;
  }
  return true;
}

// Applies a glTF node's TRS (translation and uniform or per-axis scale; bakes write no rotation).
function nodeTransform(node, parent) {
  const t = node.translation || [0, 0, 0], s = node.scale || [1, 1, 1];
  if (node.rotation) problem('unexpected node rotation');
  return {t: [parent.t[0] + parent.s[0] * t[0], parent.t[1] + parent.s[1] * t[1], parent.t[2] + parent.s[2] * t[2]],
          s: [parent.s[0] * s[0], parent.s[1] * s[1], parent.s[2] * s[2]]};
}

// World (x east, y north, z up) extent of every POSITION of a glTF content, after its node
// transforms and 3D Tiles' y-up to z-up turn: (X, Y, Z) -> (X, -Z, Y).
function contentExtent(gltf, name) {
  const ext = [Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity];
  let vertices = 0;
  const visit = (node, parent) => {
    const xf = nodeTransform(node, parent);
    if (node.mesh) {
      for (const prim of node.mesh.primitives) {
        const acc = prim.attributes.POSITION;
        const v = acc.value;
        if (!v || v.length < 3 * acc.count) { problem(`${name}: POSITION not decoded`); continue; }
        for (let i = 0; i < acc.count; ++i) {
          const X = xf.t[0] + xf.s[0] * v[3 * i], Y = xf.t[1] + xf.s[1] * v[3 * i + 1], Z = xf.t[2] + xf.s[2] * v[3 * i + 2];
          const w = [X, -Z, Y];
          for (let k = 0; k < 3; ++k) { ext[k] = Math.min(ext[k], w[k]); ext[3 + k] = Math.max(ext[3 + k], w[k]); }
        }
        vertices += acc.count;
      }
    }
    for (const child of node.children || []) visit(child, xf);
  };
  const scene = gltf.scene || gltf.scenes[0];
  for (const node of scene.nodes) visit(node, {t: [0, 0, 0], s: [1, 1, 1]});
  return {ext, vertices};
}

const server = await serve(folder);
const base = `http://127.0.0.1:${server.address().port}`;
let exitCode = 0;
try {
  const tileset = await load(`${base}/tileset.json`, Tiles3DLoader);
  const raw = JSON.parse(fs.readFileSync(path.join(folder, 'tileset.json'), 'utf8'));
  const implicit = Boolean(raw.root.implicitTiling);
  if (raw.asset.version !== '1.1') problem(`asset.version ${raw.asset.version}, expected 1.1`);
  const rootExtent = boxExtent(raw.root.boundingVolume.box);

  // Walk the client's tree: every tile, its box, its error and its parent's.
  const found = [];
  let vertices = 0, tiles = 0;
  const walk = async (tile, parent) => {
    ++tiles;
    let ext = boxExtent(tile.boundingVolume.box);
    if (implicit && tile.contentUrl) {
      const m = tile.contentUrl.match(/tiles\/(\d+)\/(\d+)\/(\d+)\.glb$/);
      if (m) ext = implicitExtent(rootExtent, +m[1], +m[2], +m[3]);
    }
    if (parent) {
      if (!inside(ext, parent.ext, TOLERANCE_M)) problem(`${tile.contentUrl || 'tile'}: box outside its parent's`);
      if (!(tile.geometricError < parent.error)) {
        problem(`${tile.contentUrl || 'tile'}: geometric error ${tile.geometricError} not below its parent's ${parent.error}`);
      }
    }
    if (tile.contentUrl) {
      const relative = tile.contentUrl.slice(base.length + 1);
      found.push(relative);
      const content = await load(tile.contentUrl, Tiles3DLoader, {'3d-tiles': {loadGLTF: true}});
      if (content.type !== 'glTF' || !content.gltf) {
        problem(`${relative}: not parsed as glTF content`);
      } else {
        const c = contentExtent(content.gltf, relative);
        vertices += c.vertices;
        if (!inside(c.ext, ext, TOLERANCE_M)) {
          problem(`${relative}: vertices ${JSON.stringify(c.ext)} outside the box ${JSON.stringify(ext)}`);
        }
      }
    }
    for (const child of tile.children || []) await walk(child, {ext, error: tile.geometricError});
  };
  await walk(tileset.root, null);

  const onDisk = glbFilesOnDisk(folder);
  found.sort();
  const foundSet = new Set(found);
  for (const f of onDisk) if (!foundSet.has(f)) problem(`${f}: on disk but not reached by the traversal`);
  const diskSet = new Set(onDisk);
  for (const f of found) if (!diskSet.has(f)) problem(`${f}: in the tileset but not on disk`);
  console.log(`check_tileset: ${implicit ? 'implicit' : 'explicit'} tileset, ${tiles} tiles traversed, ` +
              `${found.length} contents loaded (${onDisk.length} .glb on disk), ${vertices} vertices checked, ` +
              `${problems.length} problems`);
} catch (e) {
  problem(`loading failed: ${e.stack || e}`);
}
for (const p of problems) console.log(`  problem: ${p}`);
exitCode = problems.length ? 1 : 0;
server.close();
process.exit(exitCode);
