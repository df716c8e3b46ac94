// m4mesh's glTF against gltfpack's, as a viewer meets them (docs/gltf.md,
// "Against gltfpack"): each sequence as gltfpack -cc (the file
// scripts/anchor_bench.mjs chose at KG 0.5 % and 0.1 %) and as `m4mesh gltf`
// of the same rest-pose file at the same KG and at gltfpack's max error.
// For each file: bytes, brotli bytes, KG and max error; then in Chromium,
// the file served brotli-encoded over a link throttled to 10 and 100
// Mbit/s, three.js's GLTFLoader (meshopt decoder, M4MeshGLTFPlugin) from
// the request to the animation loaded, to its first frame drawn and to its
// last frame drawn (WebGL, read back); and the GPU memory the mesh takes:
// its vertex buffers and its morph-target texture (three.js keeps every
// target as RGBA32F texels, one per vertex per target for each of position
// and normal).
// Usage (after scripts/decode_corpus.sh and scripts/anchor_bench.mjs):
//   node scripts/gltf_bench.mjs [BUILD (default build)] [DATA (default ../shared/data)] [SEQUENCE …]
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { join, normalize, resolve } from 'node:path';
import { brotliCompressSync, constants } from 'node:zlib';
import { installPackage, launch } from '../web/tests/harness.mjs';

const root = resolve(new URL('..', import.meta.url).pathname);
const build = resolve(process.argv[2] || join(root, 'build'));
const data = resolve(process.argv[3] || join(root, '..', 'shared', 'data'));
const m4mesh = join(build, 'cli', 'm4mesh');
const anchors = join(build, 'anchor-bench');
const work = join(build, 'gltf-bench');
const BANDWIDTHS = [10, 100];  // Mbit/s
const chosen = process.argv.length > 4 ? process.argv.slice(4) : ['horse', 'cow', 'flag'];

if (!existsSync(data)) {
  console.log(`skipped: no ${data}`);
  process.exit(0);
}
if (!existsSync(join(anchors, 'results.json'))) throw new Error(`no ${anchors}/results.json: run scripts/anchor_bench.mjs first`);
mkdirSync(work, { recursive: true });
const rows = JSON.parse(readFileSync(join(anchors, 'results.json'), 'utf8')).filter((r) => r.gltfpack && chosen.includes(r.sequence));

const brotliOf = (bytes) => brotliCompressSync(bytes, { params: { [constants.BROTLI_PARAM_QUALITY]: 11 } });

// `m4mesh gltf` of the rest-pose file at a target; its stream's codec, KG and max error as the tool reports them.
function compressed(name, label, target) {
  const path = join(work, `${name}-m4mesh-${label}.glb`);
  const run = spawnSync(m4mesh, ['-y', 'gltf', join(anchors, `${name}-rest.glb`), '-o', path, ...target], { encoding: 'utf8' });
  const report = (run.stdout + run.stderr).match(/bytes \((\S+)\), KG ([\d.]+) %, max error ([\d.e+-]+)/);
  if (run.status !== 0 || !report) throw new Error(`m4mesh gltf ${name} ${target.join(' ')}: ${run.stderr}`);
  return { path, codec: report[1], kg: Number(report[2]), maxError: Number(report[3]) };
}

const files = [];  // { row, kind, path, kg, maxError }
for (const row of rows) {
  process.stderr.write(`${row.sequence} at KG ${row.target}\n`);
  files.push({ row, kind: `gltfpack -cc -vp ${row.gltfpack.setting}`, path: join(anchors, `${row.sequence}-gltfpack-vp${row.gltfpack.setting}.glb`),
               kg: row.gltfpack.kg, maxError: row.gltfpack.maxError });
  const atKg = compressed(row.sequence, `kg${row.target}`, ['--target-kg', String(row.target)]);
  files.push({ row, kind: `m4mesh gltf --target-kg ${row.target} (${atKg.codec})`, ...atKg });
  const atError = compressed(row.sequence, `me${row.target}`, ['--max-error', row.gltfpack.maxError.toPrecision(4)]);
  files.push({ row, kind: `m4mesh gltf --max-error ${row.gltfpack.maxError.toPrecision(4)} (${atError.codec})`, ...atError });
}
for (const file of files) {
  const bytes = readFileSync(file.path);
  file.bytes = bytes.length;
  file.served = brotliOf(bytes);
}

// Chromium: the package, three.js and its meshopt decoder through an import map; each file over HTTP, brotli-encoded.
const scratch = mkdtempSync(join(tmpdir(), 'm4mesh-gltf-bench-'));
const app = installPackage(join(build, 'web', 'package'), root, scratch);
writeFileSync(join(app, 'index.html'), `<!doctype html><canvas width="256" height="256"></canvas><script type="importmap">
{"imports": {"three": "/node_modules/three/build/three.module.js", "three/addons/": "/node_modules/three/examples/jsm/", "m4mesh": "/node_modules/m4mesh/index.js"}}
</script><script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { MeshoptDecoder } from 'three/addons/libs/meshopt_decoder.module.js';
import { M4MeshGLTFPlugin, M4MeshLoader } from 'm4mesh';
const renderer = new THREE.WebGLRenderer({ canvas: document.querySelector('canvas') });
const decoders = new M4MeshLoader();  // one, as an application keeps it
const pixel = new Uint8Array(4);
// From the request to loaded, to the first key drawn, to the last key drawn (ms), and the mesh's GPU bytes.
window.measure = async (url) => {
  const start = performance.now();
  const gltf = await new GLTFLoader().setMeshoptDecoder(MeshoptDecoder).register((parser) => new M4MeshGLTFPlugin(parser, { loader: decoders })).loadAsync(url);
  const loaded = performance.now() - start;
  const mesh = gltf.scene.getObjectByProperty('isMesh', true);
  const clip = gltf.animations[0];
  const times = clip.tracks.find((t) => t.name.endsWith('.morphTargetInfluences')).times;
  const scene = new THREE.Scene().add(gltf.scene);
  const sphere = new THREE.Box3().setFromObject(gltf.scene).getBoundingSphere(new THREE.Sphere());
  const camera = new THREE.PerspectiveCamera(45, 1, sphere.radius / 100, sphere.radius * 100);
  camera.position.copy(sphere.center).add(new THREE.Vector3(0, 0, 3 * sphere.radius));
  const mixer = new THREE.AnimationMixer(gltf.scene);
  mixer.clipAction(clip).setLoop(THREE.LoopOnce, 1).play().clampWhenFinished = true;
  const gl = renderer.getContext();
  const draw = (t) => {
    mixer.setTime(t);
    renderer.render(scene, camera);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);  // waits for the drawing
    return performance.now() - start;
  };
  const first = draw(times[0]), last = draw(times[times.length - 1]);
  const g = mesh.geometry;
  let buffers = g.index ? g.index.array.byteLength : 0;
  for (const a of Object.values(g.attributes)) buffers += a.array.byteLength;
  const targets = g.morphAttributes.position?.length ?? 0;
  const kinds = ['position', 'normal', 'color'].filter((k) => g.morphAttributes[k]?.length).length;
  const texture = g.attributes.position.count * targets * kinds * 16;
  g.dispose();
  return { loaded, first, last, buffers, texture };
};
window.ready = true;
</script>`);
const served = new Map(files.map((f, i) => [`/files/${i}.glb`, f.served]));
const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.wasm': 'application/wasm' };
const server = createServer((request, response) => {
  const path = decodeURIComponent(new URL(request.url, 'http://x').pathname);
  if (served.has(path)) {
    const body = served.get(path);
    return response.writeHead(200, { 'content-type': 'model/gltf-binary', 'content-encoding': 'br', 'content-length': body.length, 'cache-control': 'no-store' }).end(body);
  }
  try {
    const file = join(app, normalize(path === '/' ? '/index.html' : path));
    const body = readFileSync(file);
    // The page's code cached, as a site serves it: only the files measured come over the throttled link.
    response.writeHead(200, { 'content-type': types[file.slice(file.lastIndexOf('.'))] ?? 'application/octet-stream', 'cache-control': 'max-age=3600' }).end(body);
  } catch {
    response.writeHead(404).end();
  }
});
await new Promise((done) => server.listen(0, '127.0.0.1', done));
const browser = await launch();
try {
  const page = await browser.newPage();
  page.on('pageerror', (error) => console.error(`page error: ${error.message}`));
  await page.goto(`http://127.0.0.1:${server.address().port}/`);
  await page.waitForFunction(() => window.ready === true);
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('Network.enable');
  await page.evaluate((url) => window.measure(url), '/files/1.glb');  // the decoder's worker and module loaded once, unthrottled
  for (const mbps of BANDWIDTHS) {
    await cdp.send('Network.emulateNetworkConditions', { offline: false, latency: 0, downloadThroughput: (mbps * 1e6) / 8, uploadThroughput: (mbps * 1e6) / 8 });
    for (const [i, file] of files.entries()) {
      process.stderr.write(`  ${mbps} Mbit/s: ${file.row.sequence} ${file.kind}\n`);
      file[mbps] = await page.evaluate((url) => window.measure(url), `/files/${i}.glb`);
    }
  }
} finally {
  await browser.close();
  server.close();
  rmSync(scratch, { recursive: true, force: true });
}

writeFileSync(join(work, 'results.json'), JSON.stringify(files.map(({ row, served: _, ...f }) => ({ sequence: row.sequence, target: row.target, ...f })), null, 1));
const kb = (bytes) => (bytes / 1000).toFixed(1);
const s = (ms) => (ms / 1000).toFixed(2);
console.log(`| sequence | KG ≤ | file | kB (brotli) | KG % | max error | ${BANDWIDTHS.map((b) => `${b} Mbit/s: loaded · first · last frame, s`).join(' | ')} | GPU MB (buffers + morph texture) |`);
console.log(`|---|---|---|---|---|---|${BANDWIDTHS.map(() => '---|').join('')}---|`);
for (const f of files) {
  const t = BANDWIDTHS.map((b) => `${s(f[b].loaded)} · ${s(f[b].first)} · ${s(f[b].last)}`);
  const gpu = f[BANDWIDTHS[0]];
  console.log(`| ${f.row.sequence} | ${f.row.target} | ${f.kind} | ${kb(f.bytes)} (${kb(f.served.length)}) | ${f.kg.toFixed(3)} | ${f.maxError.toPrecision(3)} | ${t.join(' | ')} | ${((gpu.buffers + gpu.texture) / 1e6).toFixed(1)} (${(gpu.buffers / 1e6).toFixed(2)} + ${(gpu.texture / 1e6).toFixed(1)}) |`);
}
console.log(`(${work}/results.json has every figure)`);
