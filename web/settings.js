// The settings a running rtmot takes without a restart (docs/web.md, POST /api/settings): the
// detector's score cut. Kept apart from app.js (the pictures, lines and counts); it uses the token
// typed into a source's box (app.js' form.editor), so a person types the token once per save.
'use strict';
(() => {
  const box = document.getElementById('settings');
  if (!box) return;
  box.innerHTML =
    '<h2>Settings</h2><form class="settings">' +
    '<label>detector score cut <input name="score" type="number" min="0.01" max="1" step="0.05" ' +
    'required></label> <span class="current"></span> ' +
    '<button type="submit">save</button> <span class="message"></span>' +
    '<br><small>Applied from the next frame on; the token is the one typed under a picture. ' +
    'Every other setting needs a restart.</small></form>';
  const form = box.querySelector('form');
  const current = box.querySelector('.current');
  const message = box.querySelector('.message');
  let edited = false;
  form.score.addEventListener('input', () => { edited = true; });

  async function poll() {
    try {
      const response = await fetch('api/status', {cache: 'no-store'});
      const status = await response.json();
      if (!status.settings) { box.hidden = true; return; }
      const cut = status.settings.score_threshold;
      current.textContent = 'now ' + cut.toFixed(2);
      if (!edited) form.score.value = cut.toFixed(2);
    } catch (error) {
      current.textContent = 'status unavailable';
    }
  }

  form.addEventListener('submit', async event => {
    event.preventDefault();
    const tokenBox = document.querySelector('form.editor input[name=token]');
    const token = tokenBox ? tokenBox.value : '';
    if (!token) {
      message.textContent = 'type the token in the box under a picture first';
      message.className = 'message down';
      return;
    }
    const response = await fetch('api/settings', {
      method: 'POST', body: JSON.stringify({score_threshold: Number(form.score.value)}),
      headers: {'Authorization': 'Bearer ' + token, 'Content-Type': 'application/json'},
    });
    const answer = await response.json();
    message.textContent = response.ok
      ? 'saved' + (answer.saved_to ? ' to ' + answer.saved_to : ' (not to a file)')
      : (answer.field ? answer.field + ': ' : '') + (answer.problem || answer.error);
    message.className = 'message ' + (response.ok ? 'up' : 'down');
    if (response.ok) edited = false;
    poll();
  });

  poll();
  setInterval(poll, 2000);
})();
