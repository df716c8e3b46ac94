// The decoder's speed and memory through its interfaces against the
// native decoder, in one run (docs/web.md, docs/api.md): the horse and the
// cow of ../shared/data encoded by every 3D codec, each stream decoded to
// every frame, hashes verified, natively (m4mesh_decode_bench, Google
// Benchmark, with the MD5; also on one core), in Python (m4mesh.decode), in
// Node (the npm package's module) and in headless Chromium (the page's
// #bench, with the MD5); the MD5s must agree. Then each interface's peak
// memory decoding each stream in a process of its own (the CLI, the C
// interface, Python, Node), beside that process's floor. Also the size of
// the site, gzip-compressed.
// Usage: node scripts/web_bench.mjs [BUILD (default build)] [DATA (default ../shared/data)]
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, readdirSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { gzipSync } from 'node:zlib';
import { launch, serve, siteCopy, until } from '../web/tests/harness.mjs';

const root = resolve(new URL('..', import.meta.url).pathname);
const build = resolve(process.argv[2] || join(root, 'build'));
const data = resolve(process.argv[3] || join(root, '..', 'shared', 'data'));
const m4mesh = join(build, 'cli', 'm4mesh');
const SEQUENCES = { horse: 'horse-gallop/*.obj', cow: 'pcow/*.obj' };
const CODECS = ['bfs3d', 'affine-octree', 'lcc', 'cpca-wpt'];

if (!existsSync(join(data, 'horse-gallop')) || !existsSync(join(data, 'pcow'))) {
  console.log(`skipped: no horse-gallop and pcow in ${data}`);
  process.exit(0);
}

const work = mkdtempSync(join(tmpdir(), 'm4mesh-web-bench-'));
const streams = {};
for (const [sequence, pattern] of Object.entries(SEQUENCES))
  for (const codec of CODECS) {
    const name = `${sequence}-${codec}.m4m`;
    process.stderr.write(`encoding ${name}\n`);
    execFileSync(m4mesh, ['encode3d', join(data, pattern), '--codec', codec, '-o', join(work, name), '-q']);
    streams[name] = join(work, name);
  }

process.stderr.write('native decoding (m4mesh_decode_bench)\n');
const native = JSON.parse(execFileSync(join(build, 'bench', 'm4mesh_decode_bench'), ['--benchmark_format=json', '--benchmark_filter=^Decode/', '--benchmark_repetitions=5',
  '--benchmark_report_aggregates_only=true'], { env: { ...process.env, M4MESH_DECODE_STREAMS: Object.values(streams).join(',') }, maxBuffer: 1 << 26 }));
const nativeMs = {};
for (const b of native.benchmarks) if (b.aggregate_name === 'median') nativeMs[b.run_name.replace('Decode/', '')] = b.real_time;
// The same on one core: the native decoder decodes bfs3d's axes and lcc's symbols and vertices side by side.
const oneCore = JSON.parse(execFileSync('taskset', ['-c', '0', join(build, 'bench', 'm4mesh_decode_bench'), '--benchmark_format=json', '--benchmark_filter=^Decode/',
  '--benchmark_repetitions=5', '--benchmark_report_aggregates_only=true'], { env: { ...process.env, M4MESH_DECODE_STREAMS: Object.values(streams).join(',') },
  maxBuffer: 1 << 26 }));
const oneCoreMs = {};
for (const b of oneCore.benchmarks) if (b.aggregate_name === 'median') oneCoreMs[b.run_name.replace('Decode/', '')] = b.real_time;
const nativeMd5 = Object.fromEntries(Object.entries(streams).map(([name, path]) =>
  [name, execFileSync(m4mesh, ['decode3d', '--md5', path, '-q'], { encoding: 'utf8' }).trim().split('\n')[0]]));

// Python (build/python) and the npm package's module in Node: each stream decoded whole, the best of 5.
process.stderr.write('Python decoding (m4mesh.decode)\n');
const pythonMs = JSON.parse(execFileSync('/usr/bin/python3', ['-c', `
import json, sys, time, m4mesh
out = {}
for path in sys.argv[1:]:
    data = open(path, "rb").read()
    best = float("inf")
    for _ in range(5):
        start = time.perf_counter()
        m4mesh.decode(data)
        best = min(best, time.perf_counter() - start)
    out[path.rsplit("/", 1)[-1]] = best * 1000
print(json.dumps(out))`, ...Object.values(streams)], { env: { ...process.env, PYTHONPATH: join(build, 'python') }, encoding: 'utf8' }));
process.stderr.write('Node decoding (the npm package\'s module)\n');
const { createM4meshDecoder } = await import(join(build, 'web', 'package', 'decoder.js'));
const decoderModule = await createM4meshDecoder();
const nodeMs = {};
for (const [name, path] of Object.entries(streams)) {
  const bytes = readFileSync(path);
  let best = Infinity;
  for (let run = 0; run < 5; ++run) {
    const start = performance.now();
    const stream = new decoderModule.Stream3d();
    stream.push(bytes);
    const status = JSON.parse(stream.end());
    if (status.error) throw new Error(`${name}: ${status.error.text}`);
    for (let f = 0; f < status.header.frames; ++f) stream.frame(f);
    stream.delete();
    best = Math.min(best, performance.now() - start);
  }
  nodeMs[name] = best;
}

// Peak resident memory (/usr/bin/time's %M) of a process decoding one stream through one interface, and of the same
// process decoding none (its floor): the CLI to a .f32 file; tests/install/decode.c on the build's C library, 64 KiB
// pieces, each frame written as it comes; Python's m4mesh.frames, one frame at a time, and m4mesh.decode, every frame
// at once; Node with the npm package's module, 64 KiB pieces, each final frame taken and dropped (also with Liftoff alone).
process.stderr.write('peak memory of each interface\n');
const peakMiB = (command, args, { env = process.env, floor = false } = {}) => {
  const run = spawnSync('/usr/bin/time', ['-f', 'peak %M', command, ...args], { env, encoding: 'utf8', maxBuffer: 1 << 26 });
  const kib = run.stderr.match(/peak (\d+)\s*$/);
  if (!kib || (run.status !== 0 && !floor)) throw new Error(`${command} ${args.join(' ')}: ${run.stderr}`);
  return Number(kib[1]) / 1024;
};
const decodeC = join(work, 'decode');
execFileSync('cc', ['-std=c99', '-O2', '-I', join(root, 'api'), '-o', decodeC, join(root, 'tests', 'install', 'decode.c'), '-L', join(build, 'api'),
  '-lm4mesh', `-Wl,-rpath,${join(build, 'api')}`]);
const nodeDecode = `
const { readFileSync } = await import('node:fs');
const { createM4meshDecoder } = await import(${JSON.stringify(join(build, 'web', 'package', 'decoder.js'))});
const decoder = await createM4meshDecoder();
if (process.argv[1]) {
  const bytes = readFileSync(process.argv[1]), stream = new decoder.Stream3d();
  let next = 0;
  const take = (text) => {
    const status = JSON.parse(text);
    if (status.error) throw new Error(status.error.text);
    if (status.done || !status.header?.progressive) for (; next < status.framesDecoded; ++next) stream.frame(next), stream.drop(next);
  };
  for (let at = 0; at < bytes.length; at += 65536) take(stream.push(bytes.subarray(at, at + 65536)));
  take(stream.end());
  stream.delete();
}`;
const python = (statement) => ['-c', `import sys, numpy, m4mesh\nm4mesh.codecs()\nif len(sys.argv) > 1:\n    stream = open(sys.argv[1], "rb").read()\n    ${statement}`];
const pythonEnv = { ...process.env, PYTHONPATH: join(build, 'python') };
const interfaces = {
  CLI: (path) => path ? peakMiB(m4mesh, ['decode3d', path, '-o', join(work, 'out.f32'), '-y', '-q']) : peakMiB(m4mesh, ['--version']),
  C: (path) => path ? peakMiB(decodeC, ['--chunk', '65536', path, join(work, 'out.f32')]) : peakMiB(decodeC, [], { floor: true }),
  Python: (path) => peakMiB('/usr/bin/python3', [...python('for frame in m4mesh.frames(stream): pass'), ...(path ? [path] : [])], { env: pythonEnv }),
  'Python decode': (path) => peakMiB('/usr/bin/python3', [...python('m4mesh.decode(stream)'), ...(path ? [path] : [])], { env: pythonEnv }),
  Node: (path) => peakMiB(process.execPath, ['--input-type=module', '-e', nodeDecode, ...(path ? [path] : [])]),
  // Without V8's optimizing compiler: what its work on the module's hot functions costs.
  'Node --liftoff-only': (path) => peakMiB(process.execPath, ['--liftoff-only', '--input-type=module', '-e', nodeDecode, ...(path ? [path] : [])]),
};
const floorMiB = Object.fromEntries(Object.entries(interfaces).map(([name, peak]) => [name, peak(null)]));
const memoryMiB = Object.fromEntries(Object.entries(streams).map(([name, path]) =>
  [name, Object.fromEntries(Object.entries(interfaces).map(([interfaceName, peak]) => [interfaceName, peak(path)]))]));

process.stderr.write('WebAssembly decoding in Chromium\n');
const site = siteCopy(join(build, 'web', 'site'), streams);
const server = await serve(m4mesh, site.folder);
const browser = await launch();
let web;
try {
  const page = await browser.newPage();
  await page.goto(`${server.url}#bench?run&repeat=5&streams=${Object.keys(streams).join(',')}`);
  await until(page, () => window.m4mesh?.bench?.done, 900000);
  web = await page.evaluate(() => ({ results: window.m4mesh.bench.results, agent: navigator.userAgent }));
} finally {
  await browser.close();
  server.stop();
  site.remove();
  rmSync(work, { recursive: true, force: true });
}

console.log(`Chromium: ${web.agent.match(/Chrome\/[\d.]+/)?.[0]}; native: ${native.context.host_name}, ${native.context.num_cpus} CPUs\n`);
console.log('| stream | bytes | native ms | one core ms | Python ms (speed) | Node ms (speed) | Chromium ms (speed) | same MD5 |');
console.log('|---|---:|---:|---:|---:|---:|---:|---|');
let slow = 0, differ = 0;
const cell = (name, ms) => `${ms.toFixed(1)} (${(nativeMs[name] / ms).toFixed(2)})`;
for (const r of web.results) {
  slow += nativeMs[r.url] / r.ms < 0.5;
  differ += r.md5 !== nativeMd5[r.url];
  console.log(`| ${r.url} | ${r.bytes.toLocaleString('en')} | ${nativeMs[r.url].toFixed(1)} | ${oneCoreMs[r.url].toFixed(1)} | ${cell(r.url, pythonMs[r.url])} | ` +
    `${cell(r.url, nodeMs[r.url])} | ` +
    `${cell(r.url, r.ms)} | ${r.md5 === nativeMd5[r.url] ? 'yes' : 'NO'} |`);
}

console.log('\nPeak memory, MiB (above the floor: the same process decoding nothing):\n');
console.log(`| stream | ${Object.keys(interfaces).join(' | ')} |`);
console.log(`|---|${Object.keys(interfaces).map(() => '---:').join('|')}|`);
console.log(`| floor | ${Object.values(floorMiB).map((m) => m.toFixed(1)).join(' | ')} |`);
for (const [name, peaks] of Object.entries(memoryMiB))
  console.log(`| ${name} | ${Object.entries(peaks).map(([i, m]) => `${m.toFixed(1)} (+${(m - floorMiB[i]).toFixed(1)})`).join(' | ')} |`);

const files = (folder) => readdirSync(folder, { recursive: true }).map((f) => join(folder, f)).filter((f) => statSync(f).isFile());
const gz = (list) => list.reduce((n, f) => n + gzipSync(readFileSync(f), { level: 9 }).length, 0);
const siteDir = join(build, 'web', 'site');
const code = files(siteDir).filter((f) => !f.includes(`${join(siteDir, 'conformance')}`));
const part = (test) => code.filter(test);
console.log(`\nsite without the suites, gzip -9: ${(gz(code) / 1024).toFixed(0)} KiB — WebAssembly ${(gz(part((f) => f.endsWith('.wasm'))) / 1024).toFixed(0)} KiB, ` +
  `its JavaScript ${(gz(part((f) => f.endsWith('m4mesh.mjs'))) / 1024).toFixed(0)} KiB, three.js ${(gz(part((f) => f.includes('vendor'))) / 1024).toFixed(0)} KiB, ` +
  `pages ${(gz(part((f) => !f.endsWith('.wasm') && !f.endsWith('m4mesh.mjs') && !f.includes('vendor'))) / 1024).toFixed(0)} KiB`);
console.log(slow === 0 && differ === 0 ? 'every stream at least half the native speed, with the native MD5'
  : `${slow} streams below half the native speed, ${differ} with another MD5`);
process.exit(slow === 0 && differ === 0 ? 0 : 1);
