// Both conformance suites through the WebAssembly decoder, judged as
// `m4mesh conform` judges: a stream to decode by the MD5 of its decoded
// output, a stream to reject by its error's kind, element, plane and bit.
const SUITES = ['conformance', 'conformance/mesh3d'];

function judge(entry, result) {
  if (entry.expect === 'decode') {
    if (result.error) return [false, result.error.text];
    return [result.md5 === entry.decoded_md5, result.md5 === entry.decoded_md5 ? result.md5 : `MD5 ${result.md5}, expected ${entry.decoded_md5}`];
  }
  if (!result.error) return [false, `decoded, expected ${entry.error_kind} at ${entry.error_element}`];
  const e = result.error;
  const same = e.kind === entry.error_kind && e.element === entry.error_element && e.plane === entry.error_plane && e.offset === entry.error_offset;
  return [same, same ? `${e.kind}: ${e.text}` : `${e.kind}: ${e.text}; expected ${entry.error_kind} at ${entry.error_element}, bit ${entry.error_offset}`];
}

export async function runConformance(module, state) {
  const table = document.getElementById('conformance-results');
  const summary = document.getElementById('conformance-summary');
  table.replaceChildren();
  const run = { done: false, passed: 0, failed: 0, decoded: 0, rejected: 0, results: [] };
  state.conformance = run;
  for (const suite of SUITES) {
    const manifest = await (await fetch(`${suite}/manifest.json`)).json();
    for (const entry of manifest.streams) {
      const bytes = new Uint8Array(await (await fetch(`${suite}/${entry.file}`)).arrayBuffer());
      const [pass, detail] = judge(entry, JSON.parse(module.decodedMd5(bytes, entry.method ?? 2)));
      run.results.push({ suite, id: entry.id, expect: entry.expect, pass, detail });
      pass ? run.passed++ : run.failed++;
      entry.expect === 'decode' ? run.decoded++ : run.rejected++;
      const row = table.insertRow();
      for (const text of [suite, entry.id, entry.expect]) row.insertCell().textContent = text;
      Object.assign(row.insertCell(), { textContent: pass ? 'pass' : 'FAIL', className: pass ? 'pass' : 'fail' });
      row.insertCell().textContent = detail;
      summary.textContent = `${run.passed} passed, ${run.failed} failed`;
    }
  }
  run.done = true;
}
