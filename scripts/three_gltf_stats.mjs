// What a three.js application draws from a glTF file: loads it with three's GLTFLoader (Node, no
// browser) and prints one JSON line: the visible meshes of the scene, their vertices, the scene's
// world bounds (glTF frame: Y up, metres), the file's node count, and how many lower LOD nodes that
// MSFT_lod names the loader can still reach (parser.getDependency) although it does not draw them.
//
//   node scripts/three_gltf_stats.mjs file.glb
import { readFileSync } from 'node:fs';
import { Box3 } from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

const file = process.argv[2];
const bytes = readFileSync(file);
const data = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const gltf = await new GLTFLoader().parseAsync(data, '');

let meshes = 0, vertices = 0;
gltf.scene.updateMatrixWorld(true);
gltf.scene.traverseVisible((o) => {
  if (!o.isMesh) return;
  meshes += 1;
  vertices += o.geometry.attributes.position.count;
});
const box = new Box3().setFromObject(gltf.scene);
const json = gltf.parser.json;
let lodNodes = 0;
for (const node of json.nodes) {
  for (const id of node.extensions?.MSFT_lod?.ids ?? []) {
    const lower = await gltf.parser.getDependency('node', id);
    if (lower) lodNodes += 1;
  }
}
console.log(JSON.stringify({
  meshes, vertices, min: box.min.toArray(), max: box.max.toArray(), nodes: json.nodes.length, lodNodes,
}));
