// The decoder's speed through its interfaces against the native decoder,
// in one run (docs/web.md, docs/api.md): the horse and the cow of
// ../shared/data encoded by every 3D codec, each stream decoded to every
// frame, hashes verified, natively (m4mesh_decode_bench, Google Benchmark,
// with the MD5), in Python (m4mesh.decode), in Node (the npm package's
// module) and in headless Chromium (the page's #bench, with the MD5); the
// MD5s must agree. Also the size of the site, gzip-compressed.
// Usage: node scripts/web_bench.mjs [BUILD (default build)] [DATA (default ../shared/data)]
import { execFileSync } from 'node:child_process';
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
const native = JSON.parse(execFileSync(join(build, 'bench', 'm4mesh_decode_bench'), ['--benchmark_format=json', '--benchmark_repetitions=5',
  '--benchmark_report_aggregates_only=true'], { env: { ...process.env, M4MESH_DECODE_STREAMS: Object.values(streams).join(',') }, maxBuffer: 1 << 26 }));
const nativeMs = {};
for (const b of native.benchmarks) if (b.aggregate_name === 'median') nativeMs[b.run_name.replace('Decode/', '')] = b.real_time;
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
console.log('| stream | bytes | native ms | Python ms (speed) | Node ms (speed) | Chromium ms (speed) | same MD5 |');
console.log('|---|---:|---:|---:|---:|---:|---|');
let slow = 0, differ = 0;
const cell = (name, ms) => `${ms.toFixed(1)} (${(nativeMs[name] / ms).toFixed(2)})`;
for (const r of web.results) {
  slow += nativeMs[r.url] / r.ms < 0.5;
  differ += r.md5 !== nativeMd5[r.url];
  console.log(`| ${r.url} | ${r.bytes.toLocaleString('en')} | ${nativeMs[r.url].toFixed(1)} | ${cell(r.url, pythonMs[r.url])} | ${cell(r.url, nodeMs[r.url])} | ` +
    `${cell(r.url, r.ms)} | ${r.md5 === nativeMd5[r.url] ? 'yes' : 'NO'} |`);
}

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
