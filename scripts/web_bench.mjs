// The WebAssembly decoder's speed in headless Chromium against the native
// decoder, in one run (docs/web.md): the horse and the cow of ../shared/data
// encoded by every 3D codec, each stream decoded to its conformance output
// (every frame, hashes verified, MD5) natively (m4mesh_decode_bench, Google
// Benchmark) and in the page (#bench); the MD5s must agree. Also the size
// of the site, gzip-compressed.
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
console.log('| stream | bytes | native ms | WebAssembly ms | speed, WebAssembly / native | same MD5 |');
console.log('|---|---:|---:|---:|---:|---|');
let slow = 0, differ = 0;
for (const r of web.results) {
  const ratio = nativeMs[r.url] / r.ms;
  slow += ratio < 0.5;
  differ += r.md5 !== nativeMd5[r.url];
  console.log(`| ${r.url} | ${r.bytes.toLocaleString('en')} | ${nativeMs[r.url].toFixed(1)} | ${r.ms.toFixed(1)} | ${ratio.toFixed(2)} | ${r.md5 === nativeMd5[r.url] ? 'yes' : 'NO'} |`);
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
