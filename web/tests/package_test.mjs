// The npm package as an application uses it: `npm pack` of the assembled
// package (build/web/package), installed offline into an empty
// application beside three.js, then streams of the 3D suite loaded by
// M4MeshLoader over HTTP in Node (in its own thread) and in Chromium (in
// the package's worker): every frame's MD5 is the manifest's, a
// progressive stream's refinements arrive one after another, and a bad
// stream's error names its element.
// Usage: node package_test.mjs PACKAGE_DIR SOURCE_DIR
import { createHash } from 'node:crypto';
import { mkdtempSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { basename, extname, join, normalize, relative } from 'node:path';
import { pathToFileURL } from 'node:url';
import { installPackage, launch, unitOffsets } from './harness.mjs';

const [packageDir, source] = process.argv.slice(2);
const suite = join(source, 'conformance', 'mesh3d');
const manifest = JSON.parse(readFileSync(join(suite, 'manifest.json'), 'utf8')).streams;
const streams = ['bfs3d-01-average', 'lcc-01-stream', 'cpca-01-wpt', 'cpca-38-segments-written'];
const work = mkdtempSync(join(tmpdir(), 'm4mesh-npm-'));
let failures = 0;
const check = (ok, what) => {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
};

try {
  const app = installPackage(packageDir, source, work);
  writeFileSync(join(app, 'index.html'), `<!doctype html><script type="importmap">
{"imports": {"three": "/node_modules/three/build/three.module.js", "m4mesh": "/node_modules/m4mesh/index.js"}}
</script><script type="module">
import { M4MeshLoader } from 'm4mesh';
window.load = (url) => new Promise((resolve) => {
  let refinements = 0;
  const animation = new M4MeshLoader().load(url, () => {
    const bytes = new Uint8Array(animation.frames.reduce((n, f) => n + f.byteLength, 0));
    let at = 0;
    for (const f of animation.frames) bytes.set(new Uint8Array(f.buffer, f.byteOffset, f.byteLength), at), (at += f.byteLength);
    let text = '';
    for (const b of bytes) text += String.fromCharCode(b);
    resolve({ frames: btoa(text), refinements, faces: animation.faces.length / 3, morphs: animation.geometry.morphAttributes.position.length });
  }, undefined, (error) => resolve({ error: String(error.message) }));
  animation.addEventListener('frames', () => (refinements++, fetch('/refined')));
});
</script>`);

  // The application's files, and the suite's streams under /streams/: a
  // progressive one in three steps that end where a unit is whole, each
  // step after the loader has shown a refinement (the page calls
  // /refined, Node's test refined()), so that it refines while it arrives
  // however busy the machine is; the others 256 bytes at a time.
  const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.wasm': 'application/wasm', '.json': 'application/json' };
  let onRefined = () => {};
  const refined = () => onRefined();
  const nextRefinement = () => new Promise((resolve) => (onRefined = resolve));
  const server = createServer(async (request, response) => {
    const path = decodeURIComponent(new URL(request.url, 'http://x').pathname);
    if (path === '/refined') {
      refined();
      response.writeHead(204).end();
      return;
    }
    const stream = path.startsWith('/streams/');
    const file = stream ? join(suite, normalize(path)) : join(app, normalize(path === '/' ? '/index.html' : path));
    let body;
    try {
      body = readFileSync(file);
    } catch {
      response.writeHead(404).end();
      return;
    }
    response.writeHead(200, { 'content-type': types[extname(file)] ?? 'application/octet-stream', 'content-length': statSync(file).size });
    const units = unitOffsets(body).map((offset) => offset + 4);
    if (stream && entry(basename(file, '.m4m'))?.clauses.includes('cpca') && units.length > 6) {
      let at = 0;
      for (const end of [units[Math.floor(units.length / 3)], units[Math.floor((2 * units.length) / 3)]]) {
        const shown = nextRefinement();
        response.write(body.subarray(at, end));
        at = end;
        await shown;
      }
      response.end(body.subarray(at));
      return;
    }
    for (let at = 0; stream && at + 256 < body.length; at += 256) response.write(body.subarray(at, at + 256));
    response.end(stream ? body.subarray(Math.max(0, Math.floor((body.length - 1) / 256) * 256)) : body);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const origin = `http://127.0.0.1:${server.address().port}`;

  const md5 = (bytes) => createHash('md5').update(bytes).digest('hex');
  const entry = (id) => manifest.find((e) => e.id === id);

  // Node: the package as installed, three.js beside it, no Worker: decoded in this thread.
  const { M4MeshLoader } = await import(pathToFileURL(join(app, 'node_modules', 'm4mesh', 'index.js')));
  for (const id of streams) {
    const result = await new Promise((resolve) => {
      let refinements = 0;
      const animation = new M4MeshLoader().load(`${origin}/streams/${id}.m4m`, () => resolve({ animation, refinements }), undefined,
        (error) => resolve({ error }));
      animation.addEventListener('frames', () => (refinements++, refined()));
    });
    if (result.error) {
      check(false, `Node: ${id}: ${result.error.message}`);
      continue;
    }
    const frames = Buffer.concat(result.animation.frames.map((f) => Buffer.from(f.buffer, f.byteOffset, f.byteLength)));
    check(md5(frames) === entry(id).decoded_md5, `Node: ${id}: ${result.animation.frames.length} frames, the manifest's MD5`);
    if (result.animation.progressive) check(result.refinements > 1, `Node: ${id}: refined ${result.refinements} times as it arrived`);
  }
  const bad = await new Promise((resolve) => new M4MeshLoader().load(`${origin}/streams/x-01-codec-unknown.m4m`, () => resolve(null), undefined, resolve));
  check(bad && /codec_id/.test(bad.message), `Node: x-01-codec-unknown rejected: ${bad?.message}`);
  // Node: a file by its path (relative to the working folder, or absolute) and by a file: URL.
  const onDisk = join(suite, 'streams', `${streams[0]}.m4m`);
  for (const name of [relative(process.cwd(), onDisk), onDisk, pathToFileURL(onDisk).href]) {
    const loaded = await new Promise((resolve) => {
      const animation = new M4MeshLoader().load(name, () => resolve({ animation }), undefined, (error) => resolve({ error }));
    });
    const frames = loaded.animation && Buffer.concat(loaded.animation.frames.map((f) => Buffer.from(f.buffer, f.byteOffset, f.byteLength)));
    check(frames && md5(frames) === entry(streams[0]).decoded_md5, `Node: load('${name}'): ${loaded.error?.message ?? "the manifest's MD5"}`);
  }
  // Bytes that are no stream say so.
  for (const [bytes, says] of [[new Uint8Array(0), /an empty stream/], [new Uint8Array([0xff, 0xd8, 0xff, 0xe0, 1]), /not an m4mesh stream: it starts with ff d8 ff e0/]]) {
    const error = await new M4MeshLoader().parse(bytes).then(() => null, (e) => e);
    check(error && says.test(error.message), `Node: parse of ${bytes.length} bytes that are no stream: ${error?.message}`);
  }

  // Chromium: the same through an import map, decoded in the package's worker.
  const browser = await launch();
  try {
    const page = await browser.newPage();
    page.on('pageerror', (error) => check(false, `Chromium page error: ${error.message}`));
    await page.goto(`${origin}/`);
    await page.waitForFunction(() => typeof window.load === 'function');
    for (const id of streams) {
      const result = await page.evaluate((url) => window.load(url), `/streams/${id}.m4m`);
      if (result.error) {
        check(false, `Chromium: ${id}: ${result.error}`);
        continue;
      }
      check(md5(Buffer.from(result.frames, 'base64')) === entry(id).decoded_md5,
        `Chromium: ${id}: the manifest's MD5, ${result.faces} faces, ${result.morphs} morph targets, ${result.refinements} updates`);
      if (id.startsWith('cpca')) check(result.refinements > 1, `Chromium: ${id}: refined ${result.refinements} times as it arrived`);
    }
    const rejected = await page.evaluate((url) => window.load(url), '/streams/x-01-codec-unknown.m4m');
    check(/codec_id/.test(rejected.error ?? ''), `Chromium: x-01-codec-unknown rejected: ${rejected.error}`);
  } finally {
    await browser.close();
    server.close();
  }
} finally {
  rmSync(work, { recursive: true, force: true });
}
console.log(failures ? `${failures} failed` : 'the npm package: all passed');
process.exit(failures ? 1 : 0);
