// The operator's page (docs/web.md): one picture per source with its lines and zones drawn over
// it, the counts and the health, polled once a second from /api/status. No framework, no build.
// Times shown are the board's own durations; the page never compares the board's clock with its
// own, so a board whose clock is wrong shows the same.
'use strict';

const sourcesEl = document.getElementById('sources');
const cards = new Map();  // stream index -> elements

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
  const editor = el('form', {class: 'editor'});
  editor.innerHTML =
    '<b>Draw a line:</b> click its two ends on the picture (its "in" side is the left of ' +
    'first → second), name it, save. <br>' +
    '<input name="name" placeholder="name" required> ' +
    '<input name="token" type="password" placeholder="token" required> ' +
    '<button type="submit" disabled>save</button> <button type="button" name="clear">clear</button> ' +
    '<span class="message"></span>';
  const health = el('table', {class: 'health'});
  const counts = el('table', {class: 'counts'});
  box.append(picture, editor, health, counts);
  sourcesEl.append(box);
  const c = {svg, health, counts, drawn: '', clicks: [], geometry};
  setupEditor(index, c, svg, editor);
  cards.set(index, c);
  return c;
}

// Clicks on the picture become the new line's ends, in the picture's pixels. The saved section
// holds the lines the source has plus the new one, with the zones unchanged (docs/web.md).
function setupEditor(index, c, svg, form) {
  const save = form.querySelector('button[type=submit]');
  const message = form.querySelector('.message');
  svg.addEventListener('click', event => {
    const box = svg.getBoundingClientRect();
    const x = Math.round((event.clientX - box.left) / box.width * c.geometry.width);
    const y = Math.round((event.clientY - box.top) / box.height * c.geometry.height);
    if (c.clicks.length === 2) c.clicks = [];
    c.clicks.push([x, y]);
    save.disabled = c.clicks.length !== 2;
    c.drawn = '';
    drawGeometry(c, c.geometry);
  });
  form.querySelector('button[name=clear]').addEventListener('click', () => {
    c.clicks = []; save.disabled = true; c.drawn = ''; drawGeometry(c, c.geometry);
  });
  form.addEventListener('submit', async event => {
    event.preventDefault();
    const line = {name: form.name.value, from: c.clicks[0], to: c.clicks[1], in: 'left'};
    const section = {
      lines: [...c.geometry.lines.map(l => ({name: l.name, from: l.from, to: l.to, in: l.in})), line],
      zones: c.geometry.zones.map(z => ({name: z.name, points: z.points})),
    };
    const response = await fetch('api/events?source=' + index, {
      method: 'POST', body: JSON.stringify(section),
      headers: {'Authorization': 'Bearer ' + form.token.value, 'Content-Type': 'application/json'},
    });
    const answer = await response.json();
    message.textContent = response.ok
      ? 'saved' + (answer.saved_to ? ' to ' + answer.saved_to : ' (not to a file)') + '; counts restart from zero'
      : (answer.field ? answer.field + ': ' : '') + (answer.problem || answer.error);
    message.className = 'message ' + (response.ok ? 'up' : 'down');
    if (response.ok) { c.clicks = []; save.disabled = true; }
  });
}

function drawGeometry(c, geometry) {
  c.geometry = geometry;
  const key = JSON.stringify([geometry.lines, geometry.zones, c.clicks]);
  if (key === c.drawn) return;
  c.drawn = key;
  c.svg.replaceChildren();
  for (const p of c.clicks) c.svg.append(el('circle', {cx: p[0], cy: p[1], r: 6, class: 'click'}));
  if (c.clicks.length === 2) {
    c.svg.append(el('line', {x1: c.clicks[0][0], y1: c.clicks[0][1], x2: c.clicks[1][0], y2: c.clicks[1][1], class: 'new'}));
  }
  for (const z of geometry.zones) {
    c.svg.append(el('polygon', {points: z.points.map(p => p.join(',')).join(' ')}));
    c.svg.append(el('text', {x: z.points[0][0] + 4, y: z.points[0][1] + 20}, z.name));
  }
  for (const l of geometry.lines) {
    c.svg.append(el('line', {x1: l.from[0], y1: l.from[1], x2: l.to[0], y2: l.to[1]}));
    c.svg.append(el('text', {x: (l.from[0] + l.to[0]) / 2 + 6, y: (l.from[1] + l.to[1]) / 2 - 6}, l.name));
  }
}

function rows(table, head, list) {
  table.replaceChildren();
  const tr = el('tr');
  for (const h of head) tr.append(el('th', {}, h));
  table.append(tr);
  for (const r of list) {
    const row = el('tr');
    for (const [i, v] of r.entries()) {
      const td = el('td', {}, String(v));
      if (i === 1 && (v === 'up' || v === 'down')) td.className = v;
      row.append(td);
    }
    table.append(row);
  }
}

function show(status) {
  document.getElementById('detector').textContent = 'rtmot ' + status.version + ' · ' + status.detector;
  status.geometry.forEach((geometry, index) => {
    const c = card(index, geometry);
    drawGeometry(c, geometry);
    const s = status.sources.find(x => x.stream === geometry.stream) || {};
    rows(c.health, ['health', ''], [
      ['source', s.up ? 'up' : 'down'],
      ['output rate (fps)', (s.fps || 0).toFixed(1)],
      ['frames captured', s.frames_captured], ['frames processed', s.frames_processed],
      ['frames skipped (detector busy)', s.frames_skipped], ['outages', s.outages],
      ['tracks now', s.tracks]]);
    const e = status.events.find(x => x.stream === geometry.stream) || {lines: [], zones: []};
    rows(c.counts, [e.generation > 0 ? 'counted since the last save' : 'counted', 'in', 'out'], [
      ...e.lines.map(l => ['line ' + l.name, l.in, l.out]),
      ...e.zones.map(z => ['zone ' + z.name + ' (inside ' + z.occupancy + ')', z.enter, z.exit])]);
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
