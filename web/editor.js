// Drawing lines and zones on a source's picture, and saving them (docs/web.md, "Drawing lines and
// zones"). A line: click its two ends, choose its "in" side (an arrow shows it); a zone: click its
// corners, at least three. Saving sends the source's whole events section (what it has, plus the
// new shape, minus the ones removed) to POST /api/events?source=N; the server checks it with the
// configuration file's own reader, and its answer (or the field it refuses) is shown under the
// picture. Clicks are turned into the picture's own pixels, whatever size the page shows it at.
'use strict';

// "left" is as a person standing on the picture at `from`, looking at `to`, sees it (docs/events.md;
// y points down): the left normal of from -> to is (dy, -dx).
function inSideArrow(line, inSide, length) {
  const [x1, y1] = line.from, [x2, y2] = line.to;
  const dx = x2 - x1, dy = y2 - y1, norm = Math.hypot(dx, dy) || 1;
  const sign = inSide === 'left' ? 1 : -1;
  const mx = (x1 + x2) / 2, my = (y1 + y2) / 2;
  return {x1: mx, y1: my, x2: mx + sign * length * dy / norm, y2: my - sign * length * dx / norm};
}

function sectionOf(geometry) {
  return {
    lines: geometry.lines.map(l => ({name: l.name, from: l.from, to: l.to, in: l.in})),
    zones: geometry.zones.map(z => ({name: z.name, points: z.points})),
  };
}

async function postSection(index, section, token) {
  const response = await fetch('api/events?source=' + index, {
    method: 'POST', body: JSON.stringify(section),
    headers: {'Authorization': 'Bearer ' + token, 'Content-Type': 'application/json'},
  });
  let answer = {};
  try { answer = await response.json(); } catch (error) { answer = {error: 'HTTP ' + response.status}; }
  return {ok: response.ok, answer};
}

function explain(result) {
  const a = result.answer;
  if (result.ok) {
    return 'saved' + (a.saved_to ? ' to ' + a.saved_to : ' (the run has no configuration file)') +
           '; every count of this source restarts from zero';
  }
  return (a.field ? a.field + ': ' : '') + (a.problem || a.error || 'refused');
}

class Editor {
  constructor(index, picture) {
    this.index = index;
    this.picture = picture;  // {svg, geometry}: geometry is replaced by each status poll
    this.clicks = [];
    this.form = document.createElement('form');
    this.form.className = 'editor';
    this.form.innerHTML =
      '<b>Draw</b> <select name="shape"><option value="line">a line</option>' +
      '<option value="zone">a zone</option></select> ' +
      '<span class="hint"></span><br>' +
      '<input name="name" placeholder="name" required> ' +
      '<label class="in-side">in side <select name="in"><option>left</option><option>right</option></select></label> ' +
      '<input name="token" type="password" placeholder="token" autocomplete="off" required> ' +
      '<button type="submit" disabled>save</button> <button type="button" name="clear">clear</button> ' +
      '<span class="message"></span>';
    this.save = this.form.querySelector('button[type=submit]');
    this.message = this.form.querySelector('.message');
    this.form.shape.addEventListener('change', () => this.clear());
    this.form.in.addEventListener('change', () => this.changed());
    this.form.querySelector('button[name=clear]').addEventListener('click', () => this.clear());
    this.form.addEventListener('submit', event => { event.preventDefault(); this.submit(); });
    picture.svg.addEventListener('click', event => this.click(event));
    this.clear();
  }

  get shape() { return this.form.shape.value; }

  click(event) {
    const box = this.picture.svg.getBoundingClientRect();
    const g = this.picture.geometry;
    const x = Math.round(Math.min(Math.max((event.clientX - box.left) / box.width, 0), 1) * (g.width - 1));
    const y = Math.round(Math.min(Math.max((event.clientY - box.top) / box.height, 0), 1) * (g.height - 1));
    if (this.shape === 'line' && this.clicks.length === 2) this.clicks = [];
    this.clicks.push([x, y]);
    this.changed();
  }

  clear() {
    this.clicks = [];
    this.changed();
  }

  ready() { return this.shape === 'line' ? this.clicks.length === 2 : this.clicks.length >= 3; }

  changed() {
    const line = this.shape === 'line';
    this.form.querySelector('.in-side').hidden = !line;
    this.form.querySelector('.hint').textContent = line
      ? 'click its two ends on the picture; the arrow points to its "in" side'
      : 'click its corners on the picture (three or more), in order around it';
    this.save.disabled = !this.ready();
    this.picture.redraw();
  }

  // The shape being drawn, as SVG elements in the picture's pixels.
  draft(el) {
    const out = this.clicks.map(p => el('circle', {cx: p[0], cy: p[1], r: 6, class: 'click'}));
    if (this.shape === 'line' && this.clicks.length === 2) {
      const line = {from: this.clicks[0], to: this.clicks[1]};
      out.push(el('line', {x1: line.from[0], y1: line.from[1], x2: line.to[0], y2: line.to[1], class: 'new'}));
      out.push(el('line', {...inSideArrow(line, this.form.in.value, 40), class: 'new arrow'}));
    } else if (this.shape === 'zone' && this.clicks.length >= 2) {
      out.push(el('polygon', {points: this.clicks.map(p => p.join(',')).join(' '), class: 'new'}));
    }
    return out;
  }

  async submit() {
    const section = sectionOf(this.picture.geometry);
    const name = this.form.name.value;
    if (this.shape === 'line') {
      section.lines.push({name, from: this.clicks[0], to: this.clicks[1], in: this.form.in.value});
    } else {
      section.zones.push({name, points: this.clicks});
    }
    const result = await postSection(this.index, section, this.form.token.value);
    this.show(result);
    if (result.ok) this.clear();
  }

  // The counts table's "remove" buttons: the section without that line or zone.
  async remove(kind, name) {
    const section = sectionOf(this.picture.geometry);
    section[kind] = section[kind].filter(shape => shape.name !== name);
    if (!this.form.token.value) {
      this.show({ok: false, answer: {error: 'give the token first (removing is a write)'}});
      return;
    }
    this.show(await postSection(this.index, section, this.form.token.value));
  }

  show(result) {
    this.message.textContent = explain(result);
    this.message.className = 'message ' + (result.ok ? 'up' : 'down');
  }
}
