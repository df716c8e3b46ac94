// The analyzer: a stream's units (3D) or planes (2D) with their sizes, the
// syntax elements of the one chosen (what `m4mesh trace` prints), a page
// at a time, every violation `m4mesh check` finds, located in the list,
// and a chart of the bits each kind of element costs in every unit or
// plane. Fixed-length fields count their bits; an arithmetic-coded section
// counts its bytes under the section's name (its symbols have no bit
// length of their own). The tracing and checking run in a worker
// (analyzer-worker.js): the page answers while a large stream is analysed.
const COLOURS = ['#4e79a7', '#f28e2b', '#e15759', '#76b7b2', '#59a14f', '#edc948', '#b07aa1', '#ff9da7', '#9c755f', '#bab0ac'];
const PAGE_ROWS = 500;

function cell(row, text, className) {
  const td = row.insertCell();
  td.textContent = text;
  if (className) td.className = className;
  return td;
}

export class Analyzer {
  constructor(state) {
    this.state = state;
    this.list = document.getElementById('unit-list');
    this.elements = document.getElementById('elements');
    this.findingsBox = document.getElementById('findings');
    this.pager = document.getElementById('pager');
    this.worker = new Worker(new URL('./analyzer-worker.js', import.meta.url), { type: 'module' });
    this.pending = new Map();
    this.nextId = 0;
    this.worker.onmessage = ({ data }) => {
      if (data.progress) return this.progress(data.progress);
      const { resolve, reject } = this.pending.get(data.id);
      this.pending.delete(data.id);
      if (data.error) reject(new Error(data.error));
      else resolve(data.result);
    };
    this.worker.onerror = (event) => {
      for (const { reject } of this.pending.values()) reject(new Error(`the analyzer's worker failed: ${event.message}`));
      this.pending.clear();
    };
    document.getElementById('page-previous').addEventListener('click', () => this.showPage(this.page - 1));
    document.getElementById('page-next').addEventListener('click', () => this.showPage(this.page + 1));
  }

  call(request, transfer = []) {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage({ id, request }, transfer);
    });
  }

  progress(text) {
    document.getElementById('detail-title').textContent = `Analysing ${this.name}: ${text}…`;
  }

  async load(bytesPromise, name) {
    this.name = name;
    this.progress('receiving');
    const bytes = await bytesPromise;
    const summary = await this.call({ type: 'open', bytes }, [bytes]);
    this.parts = summary.parts;
    this.findings = summary.findings;
    this.state.analyzer = {
      name, kind: summary.kind, parts: this.parts.map(({ label, size }) => ({ label, size })),
      findings: this.findings.map((f) => f.text), errors: this.findings.filter((f) => f.error).length,
      traceError: summary.traceError, selected: null, elementsShown: 0, rowsShown: 0, page: 0, pages: 0, chartKinds: summary.chart.kinds,
    };
    document.getElementById('list-title').textContent = summary.kind === '3d' ? `Units of ${name}` : `Planes of ${name}`;
    this.drawList();
    this.drawFindings();
    this.drawChart(summary.chart, summary.kind);
    await this.select(this.findings.find((f) => f.part !== null && f.error)?.part ?? Math.min(1, this.parts.length - 1));
  }

  drawList() {
    this.list.replaceChildren();
    this.parts.forEach((part, index) => {
      const row = this.list.insertRow();
      row.dataset.index = index;
      if (part.bad) row.classList.add('bad');
      cell(row, part.label);
      cell(row, part.size ?? '', 'number');
      row.addEventListener('click', () => this.select(index).catch((error) => this.fail(error)));
    });
  }

  drawFindings() {
    this.findingsBox.replaceChildren();
    if (this.findings.length === 0) {
      this.findingsBox.textContent = 'check: no violation';
      return;
    }
    for (const finding of this.findings) {
      const div = document.createElement('div');
      div.className = `finding ${finding.error ? 'error' : 'warning'}`;
      div.textContent = finding.text;
      if (finding.part !== null) div.addEventListener('click', () => this.select(finding.part).catch((error) => this.fail(error)));
      this.findingsBox.append(div);
    }
  }

  fail(error) {
    document.getElementById('detail-title').textContent = String(error.message || error);
  }

  // Traces the part (in the worker) and shows its first page of elements.
  async select(index) {
    const part = this.parts[index];
    if (!part) return;
    this.selected = index;
    for (const row of this.list.rows) row.classList.toggle('selected', Number(row.dataset.index) === index);
    this.progress(`tracing ${part.label}`);
    const traced = await this.call({ type: 'choose', part: part.part });
    if (this.selected !== index) return;  // another part was chosen meanwhile
    this.count = traced.count;
    this.traceError = traced.error;
    Object.assign(this.state.analyzer, { selected: part.label, elementsShown: traced.count });
    await this.showPage(0);
  }

  async showPage(page) {
    const pages = Math.max(1, Math.ceil(this.count / PAGE_ROWS));
    if (page < 0 || page >= pages) return;
    const index = this.selected;
    const part = this.parts[index];
    const rows = await this.call({ type: 'rows', part: part.part, from: page * PAGE_ROWS, count: PAGE_ROWS });
    if (this.selected !== index) return;
    this.page = page;
    document.getElementById('detail-title').textContent =
      `Syntax elements of ${part.label}` + (this.traceError ? ` (the trace stops: ${this.traceError})` : '');
    this.elements.replaceChildren();
    const head = this.elements.createTHead().insertRow();
    for (const title of ['position', 'element', 'size', 'value']) head.append(Object.assign(document.createElement('th'), { textContent: title }));
    const body = this.elements.createTBody();
    for (const [position, name, size, value] of rows) {
      const row = body.insertRow();
      cell(row, position, 'number');
      cell(row, name);
      cell(row, size, 'number');
      cell(row, value);
    }
    const first = page * PAGE_ROWS;
    document.getElementById('page-label').textContent = this.count === 0 ? 'no elements'
      : `elements ${(first + 1).toLocaleString()}–${(first + rows.length).toLocaleString()} of ${this.count.toLocaleString()}`;
    document.getElementById('page-previous').disabled = page === 0;
    document.getElementById('page-next').disabled = page + 1 >= pages;
    this.elements.parentElement.scrollTop = 0;
    Object.assign(this.state.analyzer, { rowsShown: rows.length, page, pages });
  }

  drawChart({ kinds, totals, stacks }, kind) {
    const canvas = document.getElementById('chart');
    const context = canvas.getContext('2d');
    context.clearRect(0, 0, canvas.width, canvas.height);
    const sum = (values) => values.reduce((a, b) => a + b, 0);
    const highest = Math.max(1, ...stacks.map(sum));
    const left = 60, bottom = canvas.height - 24, height = bottom - 10;
    const width = (canvas.width - left - 10) / Math.max(1, stacks.length);
    context.font = '11px sans-serif';
    context.fillStyle = '#333';
    context.fillText(`${highest} bits`, 4, 16);
    context.fillText('0', 4, bottom);
    stacks.forEach((stack, k) => {
      let y = bottom;
      stack.forEach((bits, layer) => {
        const h = (bits / highest) * height;
        context.fillStyle = COLOURS[layer % COLOURS.length];
        context.fillRect(left + k * width, y - h, Math.max(1, width - 1), h);
        y -= h;
      });
    });
    context.fillStyle = '#333';
    context.fillText(kind === '3d' ? 'unit →' : 'plane →', left, canvas.height - 6);
    const legend = document.getElementById('legend');
    legend.replaceChildren();
    [...kinds, 'other'].forEach((name, k) => {
      const span = document.createElement('span');
      span.innerHTML = `<i style="background:${COLOURS[k % COLOURS.length]}"></i>`;
      span.append(`${name} (${totals[k].toLocaleString()} bits)`);
      legend.append(span);
    });
  }
}
