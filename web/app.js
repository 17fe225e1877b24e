// The operator's page (docs/web.md): one picture per source with its lines and zones drawn over
// it, the counts and the health, polled once a second from /api/status. No framework, no build.
// Times shown are the board's own durations; the page never compares the board's clock with its
// own, so a board whose clock is wrong shows the same.
'use strict';

const sourcesEl = document.getElementById('sources');
const cards = new Map();  // stream index -> elements and its Editor (editor.js)

function el(tag, attrs, text) {
  const e = ['svg', 'line', 'polygon', 'text', 'circle'].includes(tag)
    ? document.createElementNS('http://www.w3.org/2000/svg', tag) : document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

function card(index, geometry) {
  if (cards.has(index)) return cards.get(index);
  const box = el('section', {class: 'source', id: 'source-' + index});
  box.append(el('h2', {}, 'stream ' + geometry.stream + ': ' + geometry.uri));
  const picture = el('div', {class: 'picture'});
  const img = el('img', {src: 'video/' + index + '.mjpg', alt: 'live picture of ' + geometry.uri,
                         width: geometry.width, height: geometry.height});
  const svg = el('svg', {viewBox: '0 0 ' + geometry.width + ' ' + geometry.height,
                         preserveAspectRatio: 'none'});
  picture.append(img, svg);
  const health = el('table', {class: 'health'});
  const counts = el('table', {class: 'counts'});
  const c = {svg, health, counts, drawn: '', geometry};
  c.redraw = () => { c.drawn = ''; drawGeometry(c, c.geometry); };
  c.editor = new Editor(index, c);
  box.append(picture, c.editor.form, health, counts);
  sourcesEl.append(box);
  cards.set(index, c);
  return c;
}

function drawGeometry(c, geometry) {
  c.geometry = geometry;
  const key = JSON.stringify([geometry.lines, geometry.zones, c.editor ? c.editor.clicks : []]);
  if (key === c.drawn) return;
  c.drawn = key;
  c.svg.replaceChildren();
  for (const z of geometry.zones) {
    c.svg.append(el('polygon', {points: z.points.map(p => p.join(',')).join(' ')}));
    c.svg.append(el('text', {x: z.points[0][0] + 4, y: z.points[0][1] + 20}, z.name));
  }
  for (const l of geometry.lines) {
    c.svg.append(el('line', {x1: l.from[0], y1: l.from[1], x2: l.to[0], y2: l.to[1]}));
    c.svg.append(el('line', {...inSideArrow(l, l.in, 24), class: 'arrow'}));
    c.svg.append(el('text', {x: (l.from[0] + l.to[0]) / 2 + 6, y: (l.from[1] + l.to[1]) / 2 - 6}, l.name));
  }
  if (c.editor) c.svg.append(...c.editor.draft(el));
}

function rows(table, head, list) {
  table.replaceChildren();
  const tr = el('tr');
  for (const h of head) tr.append(el('th', {}, h));
  table.append(tr);
  for (const r of list) {
    const row = el('tr');
    for (const [i, v] of r.entries()) {
      const td = v instanceof Element ? el('td') : el('td', {}, String(v));
      if (v instanceof Element) td.append(v);
      if (i === 1 && (v === 'up' || v === 'down')) td.className = v;
      row.append(td);
    }
    table.append(row);
  }
}

function removeButton(c, kind, name) {
  const button = el('button', {type: 'button', class: 'remove', title: 'remove ' + name + ' (needs the token)'}, 'remove');
  button.addEventListener('click', () => c.editor.remove(kind, name));
  return button;
}

// A line's or zone's row, then one row per class it counted when there are several; a single
// class is named in the row itself.
function withClasses(row, classes, first, second) {
  const names = Object.keys(classes || {});
  if (names.length === 1) return [[row[0] + ' (' + names[0] + ')', ...row.slice(1)]];
  return [row, ...names.map(name => ['\u2003' + name, classes[name][first], classes[name][second], ''])];
}

function show(status) {
  // The detector's first words in the header, its whole description (engine choice, why) on hover.
  const detector = document.getElementById('detector');
  detector.textContent = 'rtmot ' + status.version + ' · ' + status.detector.split(' (')[0];
  detector.title = status.detector;
  status.geometry.forEach((geometry, index) => {
    const c = card(index, geometry);
    drawGeometry(c, geometry);
    const s = status.sources.find(x => x.stream === geometry.stream) || {};
    rows(c.health, ['health', ''], [
      ['source', s.up ? 'up' : 'down'],
      ['output rate (fps)', (s.fps || 0).toFixed(1)],
      ['frames captured', s.frames_captured], ['frames processed', s.frames_processed],
      ['frames skipped (detector busy)', s.frames_skipped], ['outages', s.outages],
      ['tracks now', s.tracks],
      ['capture \u2192 sent p50 / p99 (ms)', s.end_to_end
        ? s.end_to_end.p50_ms.toFixed(0) + ' / ' + s.end_to_end.p99_ms.toFixed(0) : ''],
      ['detector capacity (fps, every source)', (status.detector_capacity_fps || 0).toFixed(1)]]);
    const e = status.events.find(x => x.stream === geometry.stream) || {lines: [], zones: []};
    rows(c.counts, [e.generation > 0 ? 'counted since the last save' : 'counted', 'in', 'out', ''], [
      ...e.lines.flatMap(l => withClasses(['line ' + l.name, l.in, l.out, removeButton(c, 'lines', l.name)],
                                          l.classes, 'in', 'out')),
      ...e.zones.flatMap(z => withClasses(['zone ' + z.name + ' (inside ' + z.occupancy + ')', z.enter, z.exit,
                                           removeButton(c, 'zones', z.name)], z.classes, 'enter', 'exit'))]);
  });
  const tbody = document.querySelector('#latency tbody');
  tbody.replaceChildren();
  for (const [stage, q] of Object.entries(status.latency)) {
    const tr = el('tr');
    tr.append(el('td', {}, stage), el('td', {}, q.p50_ms.toFixed(1)), el('td', {}, q.p99_ms.toFixed(1)));
    tbody.append(tr);
  }
}

async function poll() {
  const connection = document.getElementById('connection');
  try {
    const response = await fetch('api/status', {cache: 'no-store'});
    if (!response.ok) throw new Error(response.status);
    show(await response.json());
    connection.textContent = 'live';
    connection.className = 'up';
  } catch (error) {
    connection.textContent = 'no answer from the board';
    connection.className = 'down';
  }
  setTimeout(poll, 1000);
}

poll();
