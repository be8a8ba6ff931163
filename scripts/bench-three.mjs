// Peer baseline for BENCHMARKS.md "Bake speed and memory (issue 15)"; run by scripts/bench-peers.sh.
//
//     node bench-three.mjs THREE_PACKAGE_DIR MESH.ply
//
// Loads the PLY with three.js's PLYLoader (not timed), then times `new EdgesGeometry(geometry, 30)`,
// three.js's feature-edge extraction (edges whose faces meet at 30 degrees or more). Prints JSON.
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

const [threeDir, mesh] = process.argv.slice(2);
const THREE = await import(pathToFileURL(join(threeDir, 'build/three.module.js')).href);
const { PLYLoader } = await import(pathToFileURL(join(threeDir, 'examples/jsm/loaders/PLYLoader.js')).href);
const version = JSON.parse(readFileSync(join(threeDir, 'package.json'), 'utf8')).version;

const bytes = readFileSync(mesh);
const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
let start = performance.now();
const geometry = new PLYLoader().parse(buffer);
const load = (performance.now() - start) / 1e3;
start = performance.now();
const edges = new THREE.EdgesGeometry(geometry, 30);
const edgesSeconds = (performance.now() - start) / 1e3;
console.log(JSON.stringify({
  version,
  load,
  edges_geometry: edgesSeconds,
  triangles: geometry.index ? geometry.index.count / 3 : geometry.attributes.position.count / 3,
  edge_segments: edges.attributes.position.count / 2,
}));
