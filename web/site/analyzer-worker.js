// The analyzer's work, off the page's thread (docs/web.md). Given a
// stream, it lists the parts (the 3D object header and units, the 2D mesh
// object and planes) from a trace of the fixed fields, sums their bits per
// element for the chart and runs `m4mesh check`; the elements of one part,
// bins and raw bits included, are traced only when that part is chosen,
// and handed out a page at a time.
import createM4mesh from './m4mesh.mjs';

const CHART_KINDS = 9;  // the costliest kinds; the rest are summed as "other"

const modulePromise = createM4mesh();
let stream = null;  // { bytes, mesh3d }
let chosen = null;  // { part, lines }

// Bits a trace line costs: a fixed field its size, a byte section its bytes.
function lineBits([, , position, , size, value]) {
  if (size === 'B') return 8 * parseInt(value, 10);
  if (position.includes(':') || size === 'b') return 0;
  return Number(size) || 0;
}

// 3D: the object header, every unit as the C++ names it (unit_labels3d), with its bytes.
function units(module, bytes, lines) {
  const layout = JSON.parse(module.units3d(bytes));
  const byUnit = new Map();
  for (const line of lines) byUnit.get(line[0])?.push(line) ?? byUnit.set(line[0], [line]);
  const parts = [{ label: 'object header', part: -1, lines: (byUnit.get(-1) ?? []).filter((l) => l[3] !== 'mesh_object_end_code') }];
  (layout.units ?? []).forEach((unit, index) =>
    parts.push({ label: `unit ${index}: ${unit.label}`, part: index, size: `${unit.bytes} B`, lines: byUnit.get(index) ?? [] }));
  return parts;
}

// 2D: the mesh object, then one part per plane start code, with its bits.
function planes(lines) {
  const parts = [{ label: 'mesh object', part: -1, offset: 0, lines: [] }];
  for (const line of lines) {
    if (line[3] === 'mesh_object_plane_start_code')
      parts.push({ label: `plane ${parts.length - 1}`, part: parts.length - 1, offset: Number(line[2]), lines: [] });
    parts[parts.length - 1].lines.push(line);
  }
  parts.forEach((part, k) => {
    const last = part.lines[part.lines.length - 1];
    const end = parts[k + 1]?.offset ?? (last ? Number(last[2]) + lineBits(last) : 0);
    part.size = `${end - part.offset} bits`;
    const intra = part.lines.find((l) => l[3] === 'new_mesh_flag');
    if (intra) part.label += intra[5] === '1' ? ' (I)' : ' (P)';
  });
  return parts;
}

// Bits per element kind in every part: the costliest kinds, then "other".
function chart(parts) {
  const perPart = parts.map((part) => {
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
  const sum = (values) => values.reduce((a, b) => a + b, 0);
  const stacks = perPart.map((bits) => {
    const stack = kinds.map((kind) => bits.get(kind) ?? 0);
    stack.push(sum([...bits.values()]) - sum(stack));
    return stack;
  });
  const kindTotals = kinds.map((kind) => totals.get(kind));
  kindTotals.push(sum([...totals.values()]) - sum(kindTotals));
  return { kinds, totals: kindTotals, stacks };
}

function open(module, bytes) {
  const mesh3d = JSON.parse(module.streamKind(bytes)).kind === '3d';
  stream = { bytes, mesh3d };
  chosen = null;
  postMessage({ progress: 'tracing the fields' });
  const trace = JSON.parse(module.traceFields(bytes));
  const parts = mesh3d ? units(module, bytes, trace.lines) : planes(trace.lines);
  postMessage({ progress: 'checking' });
  const check = JSON.parse(module.check(bytes));
  const findings = check.error ? [{ error: true, ...check.error }] : check.findings;
  for (const finding of findings) {
    const index = parts.findIndex((p) => p.part === (mesh3d ? finding.unit : finding.plane));
    finding.part = index >= 0 ? index : null;
    if (index >= 0 && finding.error) parts[index].bad = true;
  }
  return {
    kind: mesh3d ? '3d' : '2d',
    parts: parts.map(({ label, part, size, bad }) => ({ label, part, size, bad: Boolean(bad) })),
    findings: findings.map(({ error, text, part }) => ({ error: Boolean(error), text, part })),
    traceError: trace.error?.text ?? null,
    chart: chart(parts),
  };
}

// Traces one part whole and keeps its elements for rows().
function choose(module, part) {
  const trace = JSON.parse(module.tracePart(stream.bytes, part));
  const lines = stream.mesh3d && part === -1 ? trace.lines.filter((l) => l[3] !== 'mesh_object_end_code') : trace.lines;
  chosen = { part, lines };
  return { part, count: lines.length, error: trace.error?.text ?? null };
}

// Elements [from, from + count) of the chosen part: position, element, size, value.
function rows(part, from, count) {
  if (chosen?.part !== part) throw new Error(`part ${part} is not the one traced`);
  return chosen.lines.slice(from, from + count).map(([, , position, name, size, value, context]) =>
    [position, name, size, context >= 0 ? `${value}  ctx ${context}` : value]);
}

onmessage = async ({ data }) => {
  const { id, request } = data;
  try {
    const module = await modulePromise;
    let result;
    if (request.type === 'open') result = open(module, new Uint8Array(request.bytes));
    else if (request.type === 'choose') result = choose(module, request.part);
    else if (request.type === 'rows') result = rows(request.part, request.from, request.count);
    else throw new Error(`unknown request ${request.type}`);
    postMessage({ id, result });
  } catch (error) {
    postMessage({ id, error: String(error.message || error) });
  }
};
