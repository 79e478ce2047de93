// Gripper, torque (off to move the arm by hand) and named points: record the current pose
// (POST /api/v1/points), list them, go to one, delete one.
import { api } from './api.js';
import { el, $, fmt, busy } from './dom.js';
import { refreshState } from './live.js';

export function initPoints(model) {
  const root = $('#points');

  if (model.has_gripper) {
    const closed = el('input', { type: 'range', min: 0, max: 1, step: 0.05, value: 0, 'aria-label': 'Gripper closed (0 open … 1 closed)' });
    const send = (value, button) => busy(button, () => api.post('/api/v1/gripper', { closed: Number(value) }));
    closed.addEventListener('change', () => send(closed.value));
    root.append(el('div', { class: 'row' }, el('strong', {}, 'Gripper '),
      el('button', { type: 'button', onclick: (e) => { closed.value = 0; send(0, e.currentTarget); } }, 'Open gripper'),
      closed,
      el('button', { type: 'button', onclick: (e) => { closed.value = 1; send(1, e.currentTarget); } }, 'Close gripper')));
  }

  const torqueState = el('span', { class: 'muted', role: 'status', 'aria-label': 'Torque' }, '');
  const torque = (on, button) => busy(button, async () => {
    await api.post('/api/v1/torque', { on });
    torqueState.textContent = on ? 'torque on' : 'torque off: move the arm by hand, then record';
  });
  root.append(el('div', { class: 'row' }, el('strong', {}, 'Torque '),
    el('button', { type: 'button', onclick: (e) => torque(false, e.currentTarget) }, 'Torque off'),
    el('button', { type: 'button', onclick: (e) => torque(true, e.currentTarget) }, 'Torque on'),
    ' ', torqueState));

  const name = el('input', { type: 'text', placeholder: 'pick', 'aria-label': 'Point name', maxlength: 64 });
  const list = el('tbody');
  const file = el('span', { class: 'muted' });
  const positionsText = (joints) => Object.entries(joints || {}).map(([n, v]) => `${n} ${fmt(v)}`).join(', ');

  async function reload() {
    let answer;
    try { answer = await api.get('/api/v1/points'); } catch { return; }
    file.textContent = answer.file ? `saved to ${answer.file}` : 'not saved to a file (serve --points FILE)';
    list.replaceChildren(...answer.points.map((p) => el('tr', {},
      el('th', { scope: 'row' }, p.name),
      el('td', {}, positionsText(p.joints)),
      el('td', {},
        el('button', { type: 'button', 'aria-label': `Go to point ${p.name}`, onclick: (e) => busy(e.currentTarget,
          () => api.post('/api/v1/joints', { positions: p.joints })) }, 'Go'),
        el('button', { type: 'button', 'aria-label': `Delete point ${p.name}`, onclick: (e) => busy(e.currentTarget, async () => {
          await api.del(`/api/v1/points/${encodeURIComponent(p.name)}`);
          await reload();
        }) }, 'Delete')))));
  }

  const record = el('button', { type: 'button', onclick: (e) => busy(e.currentTarget, async () => {
    await api.post('/api/v1/points', { name: name.value.trim() });
    await reload();
    await refreshState();
  }) }, 'Record point');
  name.addEventListener('keydown', (e) => { if (e.key === 'Enter') record.click(); });

  root.append(el('div', { class: 'row' }, el('strong', {}, 'Points '), name, record, ' ', file),
    el('table', { class: 'points', 'aria-label': 'Recorded points' }, list));
  reload();
}
