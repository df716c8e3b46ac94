// The analyzer: a stream's units (3D) or planes (2D) with their sizes, the
// syntax elements of the one chosen (what `m4mesh trace` prints), every
// violation `m4mesh check` finds, located in the list, and a chart of the
// bits each kind of element costs in every unit or plane. Fixed-length
// fields count their bits; an arithmetic-coded section counts its bytes
// under the section's name (its symbols have no bit length of their own).
const COLOURS = ['#4e79a7', '#f28e2b', '#e15759', '#76b7b2', '#59a14f', '#edc948', '#b07aa1', '#ff9da7', '#9c755f', '#bab0ac'];
const CHART_KINDS = 9;  // the costliest kinds; the rest are drawn as "other"

function cell(row, text, className) {
  const td = row.insertCell();
  td.textContent = text;
  if (className) td.className = className;
  return td;
}

// Bits a trace line costs: a fixed field its size, a byte section its bytes.
function lineBits([, , position, , size, value]) {
  if (size === 'B') return 8 * parseInt(value, 10);
  if (position.includes(':') || size === 'b') return 0;
  return Number(size) || 0;
}

export class Analyzer {
  constructor(module, state) {
    this.module = module;
    this.state = state;
    this.list = document.getElementById('unit-list');
    this.elements = document.getElementById('elements');
    this.findingsBox = document.getElementById('findings');
  }

  async load(bytesPromise, name) {
    const bytes = new Uint8Array(await bytesPromise);
    const mesh3d = JSON.parse(this.module.streamKind(bytes)).kind === '3d';
    const trace = JSON.parse(this.module.trace(bytes, 2));
    const check = JSON.parse(this.module.check(bytes));
    this.parts = mesh3d ? this.units(bytes, trace.lines) : this.planes(trace.lines);
    this.findings = check.error ? [{ error: true, ...check.error }] : check.findings;
    for (const finding of this.findings) {
      const index = this.parts.findIndex((p) => (mesh3d ? p.unit === finding.unit : p.plane === finding.plane));
      finding.part = index >= 0 ? index : null;
      if (index >= 0 && finding.error) this.parts[index].bad = true;
    }
    this.state.analyzer = {
      name, kind: mesh3d ? '3d' : '2d', parts: this.parts.map(({ label, size }) => ({ label, size })),
      findings: this.findings.map((f) => f.text), errors: this.findings.filter((f) => f.error).length,
      traceError: trace.error?.text ?? null, selected: null, elementsShown: 0, chartKinds: [],
    };
    document.getElementById('list-title').textContent = mesh3d ? `Units of ${name}` : `Planes of ${name}`;
    this.drawList();
    this.drawFindings();
    this.drawChart();
    this.select(this.findings.find((f) => f.part !== null && f.error)?.part ?? Math.min(1, this.parts.length - 1));
  }

  // 3D: the object header, every unit with its type, frame and bytes, the end code.
  units(bytes, lines) {
    const layout = JSON.parse(this.module.units3d(bytes));
    const byUnit = new Map();
    for (const line of lines) byUnit.get(line[0])?.push(line) ?? byUnit.set(line[0], [line]);
    const header = (byUnit.get(-1) ?? []).filter((l) => l[3] !== 'mesh_object_end_code');
    const parts = [{ label: 'object header', unit: -1, lines: header }];
    (layout.units ?? []).forEach((unit, index) => {
      const own = byUnit.get(index) ?? [];
      const field = (name) => own.find((l) => l[3] === name)?.[5];
      const type = { 0: 'base mesh', 1: 'frame', 2: 'refinement', 3: 'hash', 4: 'group hash' }[field('unit_type')] ?? `type ${field('unit_type') ?? '?'}`;
      const frame = field('frame_index');
      // A refinement unit refines every frame (its frame_index is 0): named by its cluster and kind.
      const kind = { 0: 'start', 1: 'component', 2: 'mesh component', 3: 'trajectory component' }[field('unit_kind')];
      const what = String(field('unit_type')) === '2' ? (field('cluster') !== undefined ? `, cluster ${field('cluster')} ${kind ?? ''}` : '')
        : frame !== undefined ? ', frame ' + frame : '';
      parts.push({
        label: `unit ${index}: ${type}${what.trimEnd()}`, unit: index, offset: unit.offset,
        size: `${unit.bytes} B`, lines: own,
      });
    });
    return parts;
  }

  // 2D: the object, then one part per plane start code, with its bits.
  planes(lines) {
    const parts = [];
    let current = { label: 'mesh object', plane: -1, lines: [] };
    parts.push(current);
    for (const line of lines) {
      if (line[3] === 'mesh_object_plane_start_code') {
        current = { label: `plane ${parts.length - 1}`, plane: parts.length - 1, offset: Number(line[2]), lines: [] };
        parts.push(current);
      }
      current.lines.push(line);
    }
    parts.forEach((part, k) => {
      const next = parts[k + 1]?.offset ?? Number(part.lines[part.lines.length - 1]?.[2] ?? 0) + lineBits(part.lines[part.lines.length - 1] ?? [0, 0, '0', '', '0']);
      part.size = `${next - (part.offset ?? 0)} bits`;
      const intra = part.lines.find((l) => l[3] === 'new_mesh_flag');
      if (intra) part.label += intra[5] === '1' ? ' (I)' : ' (P)';
    });
    return parts;
  }

  drawList() {
    this.list.replaceChildren();
    this.parts.forEach((part, index) => {
      const row = this.list.insertRow();
      row.dataset.index = index;
      if (part.bad) row.classList.add('bad');
      cell(row, part.label);
      cell(row, part.size ?? '', 'number');
      row.addEventListener('click', () => this.select(index));
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
      if (finding.part !== null) div.addEventListener('click', () => this.select(finding.part));
      this.findingsBox.append(div);
    }
  }

  select(index) {
    if (index < 0 || !this.parts[index]) return;
    for (const row of this.list.rows) row.classList.toggle('selected', Number(row.dataset.index) === index);
    const part = this.parts[index];
    document.getElementById('detail-title').textContent = `Syntax elements of ${part.label}`;
    this.elements.replaceChildren();
    const head = this.elements.createTHead().insertRow();
    for (const title of ['position', 'element', 'size', 'value']) head.append(Object.assign(document.createElement('th'), { textContent: title }));
    const body = this.elements.createTBody();
    for (const [, , position, name, size, value, context] of part.lines) {
      const row = body.insertRow();
      cell(row, position, 'number');
      cell(row, name);
      cell(row, size, 'number');
      cell(row, context >= 0 ? `${value}  ctx ${context}` : value);
    }
    this.state.analyzer.selected = part.label;
    this.state.analyzer.elementsShown = part.lines.length;
  }

  drawChart() {
    const canvas = document.getElementById('chart');
    const context = canvas.getContext('2d');
    context.clearRect(0, 0, canvas.width, canvas.height);
    const perPart = this.parts.map((part) => {
      const bits = new Map();
      for (const line of part.lines) {
        const cost = lineBits(line);
        if (cost > 0) bits.set(line[3], (bits.get(line[3]) ?? 0) + cost);
      }
      return bits;
    });
    const totals = new Map();
    for (const bits of perPart) for (const [name, cost] of bits) totals.set(name, (totals.get(name) ?? 0) + cost);
    const kinds = [...totals.keys()].sort((a, b) => totals.get(b) - totals.get(a)).slice(0, CHART_KINDS);
    const stacks = perPart.map((bits) => {
      const stack = kinds.map((kind) => bits.get(kind) ?? 0);
      stack.push([...bits.values()].reduce((a, b) => a + b, 0) - stack.reduce((a, b) => a + b, 0));
      return stack;
    });
    const highest = Math.max(1, ...stacks.map((s) => s.reduce((a, b) => a + b, 0)));
    const left = 60, bottom = canvas.height - 24, height = bottom - 10;
    const width = (canvas.width - left - 10) / Math.max(1, stacks.length);
    context.font = '11px sans-serif';
    context.fillStyle = '#333';
    context.fillText(`${highest} bits`, 4, 16);
    context.fillText('0', 4, bottom);
    stacks.forEach((stack, k) => {
      let y = bottom;
      stack.forEach((bits, kind) => {
        const h = (bits / highest) * height;
        context.fillStyle = COLOURS[kind % COLOURS.length];
        context.fillRect(left + k * width, y - h, Math.max(1, width - 1), h);
        y -= h;
      });
    });
    context.fillStyle = '#333';
    context.fillText(this.state.analyzer.kind === '3d' ? 'unit →' : 'plane →', left, canvas.height - 6);
    const legend = document.getElementById('legend');
    legend.replaceChildren();
    [...kinds, 'other'].forEach((kind, k) => {
      const span = document.createElement('span');
      span.innerHTML = `<i style="background:${COLOURS[k % COLOURS.length]}"></i>`;
      span.append(`${kind} (${(k < kinds.length ? totals.get(kind) : [...totals.values()].reduce((a, b) => a + b, 0) - kinds.reduce((a, n) => a + totals.get(n), 0)).toLocaleString()} bits)`);
      legend.append(span);
    });
    this.state.analyzer.chartKinds = kinds;
  }
}
