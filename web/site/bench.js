// Decode speed: each stream decoded to its conformance output (every frame,
// hash units verified, the MD5) by the WebAssembly decoder; the best of
// `repeat` runs. scripts/web_bench.mjs runs it in headless Chromium beside
// the native decoder.
export async function runBench(module, state, params) {
  const streams = (params.get('streams') || 'conformance/mesh3d/streams/cpca-01-wpt.m4m').split(',');
  const repeat = Number(params.get('repeat') || 5);
  const table = document.getElementById('bench-results');
  table.replaceChildren();
  const header = table.insertRow();
  for (const title of ['stream', 'bytes', 'best ms', 'MD5']) header.insertCell().textContent = title;
  const run = { done: false, results: [] };
  state.bench = run;
  for (const url of streams) {
    const bytes = new Uint8Array(await (await fetch(url)).arrayBuffer());
    let best = Infinity, result = null;
    for (let k = 0; k < repeat; ++k) {
      const start = performance.now();
      result = JSON.parse(module.decodedMd5(bytes, 2));
      best = Math.min(best, performance.now() - start);
      await new Promise((resolve) => setTimeout(resolve, 0));  // let the page draw between runs
    }
    run.results.push({ url, bytes: bytes.length, ms: best, md5: result.md5 ?? null, error: result.error?.text ?? null });
    const row = table.insertRow();
    for (const text of [url, bytes.length, best.toFixed(2), result.md5 ?? result.error.text]) row.insertCell().textContent = String(text);
  }
  run.done = true;
}
