// The terrain meshers MRSV's reconstructors are measured against, run by node
// for tools/bench/terrain_mesh_bench: Delatin (greedy Delaunay insertion) and
// MARTINI (right-triangulated irregular networks, grids of 2^k + 1 only).
//
//   node terrain_peers.mjs PEERS_DIR delatin|martini HEIGHTS.f32 W H E1,E2,... OUT_PREFIX
//
// HEIGHTS.f32 holds W x H float32 heights, x fastest. For each maximum error E
// it writes OUT_PREFIX<E>.bin (u32 vertex count, u32 triangle count, then u32
// x, y per vertex and u32 corners per triangle) and prints one JSON line with
// the time of the mesher's own calls (best of up to three runs under 1 s):
// Delatin's constructor and run, MARTINI's createTile and getMesh.
import { readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { pathToFileURL } from 'node:url';
import path from 'node:path';

const [peersDir, tool, heightsPath, w, h, errors, outPrefix] = process.argv.slice(2);
const width = Number(w), height = Number(h);
const buf = readFileSync(heightsPath);
const heights = new Float32Array(buf.buffer, buf.byteOffset, width * height);

const modules = path.join(peersDir, 'node_modules');
const Delatin = (await import(pathToFileURL(path.join(modules, 'delatin', 'index.js')))).default;
const Martini = createRequire(path.join(modules, 'x.js'))('@mapbox/martini');

// MARTINI's generator for the grid size is made once, outside the timing:
// its README makes one per size and reuses it for every tile, and it costs
// more than createTile + getMesh (13 ms of about 20 at 257^2, 280 of 420 ms
// at 1025^2), which is what issue 22 measures against.
const martini = tool === 'martini' ? new Martini(width) : null;

function runOnce(maxError) {
  const start = process.hrtime.bigint();
  let coords, triangles;
  if (tool === 'delatin') {
    const tin = new Delatin(heights, width, height);
    tin.run(maxError);
    coords = tin.coords;
    triangles = tin.triangles;
  } else {
    const tile = martini.createTile(heights);
    const mesh = tile.getMesh(maxError);
    coords = mesh.vertices;
    triangles = mesh.triangles;
  }
  const ms = Number(process.hrtime.bigint() - start) / 1e6;
  return { ms, coords, triangles };
}

// JIT warm-up on the same data, so that the first measured run is not the
// interpreter's.
runOnce(Math.max(...errors.split(',').map(Number)) * 4);
for (const e of errors.split(',').map(Number)) {
  let best = runOnce(e);
  for (let k = 1; k < 3 && best.ms < 1000; ++k) {
    const again = runOnce(e);
    if (again.ms < best.ms) best = again;
  }
  const nv = best.coords.length / 2, nt = best.triangles.length / 3;
  const out = new Uint32Array(2 + 2 * nv + 3 * nt);
  out[0] = nv;
  out[1] = nt;
  out.set(best.coords, 2);
  out.set(best.triangles, 2 + 2 * nv);
  writeFileSync(`${outPrefix}${e}.bin`, out);
  console.log(JSON.stringify({ tool, maxError: e, ms: best.ms, vertices: nv, triangles: nt }));
}
