// The ground station's page (docs/web.md, "At the ground station"): one card per stream heard,
// with a canvas of the stream's frame size and its current tracks drawn as boxes, its counts and
// its losses, polled from /api/listen four times a second. Read-only; no framework, no build.
// Ages and rates come from the listener's own clock: the page never reads a board's clock.
'use strict';

const streamsEl = document.getElementById('streams');
const cards = new Map();  // stream id -> elements
const TRACK_COLOUR = '#00ff66';  // one colour for every box (the system test looks for it)
const CANVAS_BACKGROUND = '#1c2833';

function el(tag, attrs, text) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

function card(stream) {
  if (cards.has(stream.stream)) return cards.get(stream.stream);
  const none = document.getElementById('none');
  if (none) none.remove();
  const box = el('section', {class: 'source', id: 'stream-' + stream.stream});
  const title = el('h2');
  const canvas = el('canvas', {class: 'tracks'});
  const health = el('table', {class: 'health'});
  const counts = el('table', {class: 'counts'});
  box.append(title, canvas, health, counts);
  // Streams in id order, whenever they are first heard.
  const after = [...cards.keys()].filter(id => id > stream.stream).sort((a, b) => a - b)[0];
  streamsEl.insertBefore(box, after === undefined ? null : cards.get(after).box);
  const c = {box, title, canvas, health, counts};
  cards.set(stream.stream, c);
  return c;
}

// The stream's frame size; before a message has carried one, the tracks' extent.
function frameSize(stream) {
  if (stream.width > 0 && stream.height > 0) return [stream.width, stream.height, true];
  let w = 320, h = 240;
  for (const t of stream.tracks) { w = Math.max(w, t.x + t.w); h = Math.max(h, t.y + t.h); }
  return [Math.ceil(w), Math.ceil(h), false];
}

function draw(c, stream) {
  const [width, height] = frameSize(stream);
  if (c.canvas.width !== width) c.canvas.width = width;
  if (c.canvas.height !== height) c.canvas.height = height;
  const g = c.canvas.getContext('2d');
  g.fillStyle = CANVAS_BACKGROUND;
  g.fillRect(0, 0, width, height);
  const line = Math.max(2, Math.round(width / 256));
  g.lineWidth = line;
  g.strokeStyle = TRACK_COLOUR;
  g.fillStyle = TRACK_COLOUR;
  g.font = Math.max(12, Math.round(width / 40)) + 'px sans-serif';
  g.textBaseline = 'bottom';
  for (const t of stream.tracks) {
    g.strokeRect(t.x, t.y, t.w, t.h);
    g.fillText(t.id + ' ' + (t.label || 'class ' + t.class), t.x, t.y - line);
  }
}

function rows(table, entries) {
  table.replaceChildren(...entries.map(([name, value, cls]) => {
    const tr = el('tr');
    tr.append(el('td', {}, name), el('td', cls ? {class: cls} : {}, String(value)));
    return tr;
  }));
}

function age(seconds) {
  return seconds < 1 ? 'just now' : seconds < 120 ? seconds.toFixed(1) + ' s ago'
                                                   : (seconds / 60).toFixed(1) + ' min ago';
}

function show(c, stream) {
  const [width, height, known] = frameSize(stream);
  const state = stream.ended ? 'ended' : stream.up ? 'up' : 'down';
  c.title.textContent = 'stream ' + stream.stream + (stream.run ? ' (run ' + stream.run + ')' : '') +
    ': ' + width + '×' + height + (known ? '' : ' (size not sent)');
  draw(c, stream);
  rows(c.health, [
    ['state', state + (stream.source_outage ? ' (source outage)' : ''),
     stream.up ? 'up' : 'down'],
    ['last heard', age(stream.age_s)],
    ['messages/s', stream.rate.toFixed(1)],
    ['tracks now', stream.tracks.length],
    ['received', stream.received],
    ['lost', stream.lost],
    ['reordered', stream.reordered],
    ['duplicated', stream.duplicated],
    ['restarts', stream.restarts],
    ['clashes (two senders, one id)', stream.clashes],
    ['truncated', stream.truncated],
    ['sender skipped frames', stream.sender_skipped],
    ['latency mean (sender) ms', stream.latency_mean_ms.toFixed(1)],
  ]);
  const counted = stream.events.map(e => [e.kind.replace('_', ' ') + ' #' + e.index, e.count]);
  if (stream.events_unlisted > 0) counted.push(['other kinds and indexes', stream.events_unlisted]);
  if (counted.length === 0) counted.push(['events', 'none received']);
  rows(c.counts, counted);
}

async function poll() {
  const connection = document.getElementById('connection');
  try {
    const response = await fetch('api/listen', {cache: 'no-store'});
    if (!response.ok) throw new Error('HTTP ' + response.status);
    const listen = await response.json();
    for (const stream of listen.streams) show(card(stream), stream);
    const heard = new Set(listen.streams.map(s => s.stream));
    for (const [id, c] of cards) {  // evicted by the listener (more streams than it shows)
      if (!heard.has(id)) { c.box.remove(); cards.delete(id); }
    }
    document.getElementById('totals').textContent =
      listen.streams.length + ' stream(s), ' + listen.received + ' messages, ' + listen.corrupt +
      ' corrupt' + (listen.streams_evicted > 0 ? ', ' + listen.streams_evicted + ' evicted' : '');
    connection.textContent = 'live';
    connection.className = 'up';
  } catch (error) {
    connection.textContent = 'listener unreachable (' + error.message + ')';
    connection.className = 'down';
  }
}

poll();
setInterval(poll, 250);
