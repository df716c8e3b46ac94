// Both conformance suites through the WebAssembly decoder, judged by the
// C++ that judges `m4mesh conform` (conformance/judge.h): a stream to
// decode by the MD5 of its decoded output, a stream to reject by its
// error's kind, element, plane and bit.
const SUITES = ['conformance', 'conformance/mesh3d'];

export async function runConformance(module, state) {
  const table = document.getElementById('conformance-results');
  const summary = document.getElementById('conformance-summary');
  table.replaceChildren();
  const run = { done: false, passed: 0, failed: 0, decoded: 0, rejected: 0, results: [] };
  state.conformance = run;
  for (const suite of SUITES) {
    const manifest = new module.Suite(await (await fetch(`${suite}/manifest.json`)).text(), `${suite}/manifest.json`);
    try {
      const { entries, error } = JSON.parse(manifest.entries());
      if (error) throw new Error(error.text);
      for (const [index, entry] of entries.entries()) {
        const bytes = new Uint8Array(await (await fetch(`${suite}/${entry.file}`)).arrayBuffer());
        const verdict = JSON.parse(manifest.judge(index, bytes));
        const [pass, detail] = verdict.error ? [false, verdict.error.text] : [verdict.pass, verdict.detail];
        run.results.push({ suite, id: entry.id, expect: entry.expect, pass, detail });
        pass ? run.passed++ : run.failed++;
        entry.expect === 'decode' ? run.decoded++ : run.rejected++;
        const row = table.insertRow();
        for (const text of [suite, entry.id, entry.expect]) row.insertCell().textContent = text;
        Object.assign(row.insertCell(), { textContent: pass ? 'pass' : 'FAIL', className: pass ? 'pass' : 'fail' });
        row.insertCell().textContent = detail;
        summary.textContent = `${run.passed} passed, ${run.failed} failed`;
      }
    } finally {
      manifest.delete();
    }
  }
  run.done = true;
}
