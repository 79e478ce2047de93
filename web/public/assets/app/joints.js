// One slider per joint in the user's units (deg or mm) with the raw value beside it. The
// slider follows the live position except while the user holds or has just moved it; on
// release the move is sent (POST /api/v1/joints). The number box sends on Enter / change.
import { api } from './api.js';
import { el, $, fmt } from './dom.js';
import { onState } from './live.js';

// After a release the arm needs a moment to start: the slider keeps the user's value
// until the server's position has had time to follow, so it does not jump back.
const HOLD_AFTER_RELEASE_MS = 1500;

// Fine enough to reach any value a user types; the server checks the limits.

export function initJoints(model) {
  const root = $('#joints');
  const speed = $('#joint-speed');
  speed.addEventListener('input', () => { $('#joint-speed-value').textContent = `${Math.round(speed.value * 100)}%`; });
  const rows = new Map();

  async function move(name, value) {
    try {
      await api.post('/api/v1/joints', { positions: { [name]: Number(value) }, speed: Number(speed.value) });
    } catch { /* shown by the error display */ }
  }

  for (const joint of model.joints) {
    const id = `joint-${joint.name}`;
    const slider = el('input', {
      id, type: 'range', min: joint.min, max: joint.max, step: 0.1, value: 0,
      'aria-label': `${joint.name} (${joint.unit})`,
    });
    const target = el('input', {
      type: 'number', min: joint.min, max: joint.max, step: 'any', class: 'target',
      'aria-label': `${joint.name} target (${joint.unit})`,
    });
    const readout = el('output', { for: id, class: 'readout', 'aria-label': `${joint.name} position` }, '–');
    const raw = el('span', { class: 'raw muted', 'aria-label': `${joint.name} raw` }, '');
    const row = { joint, slider, target, readout, raw, holding: false, holdUntil: 0 };
    rows.set(joint.name, row);

    slider.addEventListener('pointerdown', () => { row.holding = true; });
    slider.addEventListener('pointerup', () => { row.holding = false; row.holdUntil = performance.now() + HOLD_AFTER_RELEASE_MS; });
    slider.addEventListener('input', () => {
      row.holdUntil = performance.now() + HOLD_AFTER_RELEASE_MS;
      target.value = slider.value;
    });
    slider.addEventListener('change', () => {
      row.holdUntil = performance.now() + HOLD_AFTER_RELEASE_MS;
      move(joint.name, slider.value);
    });
    const send = () => {
      if (target.value === '') return;
      row.holdUntil = performance.now() + HOLD_AFTER_RELEASE_MS;
      slider.value = target.value;
      move(joint.name, target.value);
    };
    // 'change' fires only when the value changed: Enter sends again what was refused (busy).
    let sentByEnter = false;
    target.addEventListener('keydown', (event) => {
      if (event.key !== 'Enter') return;
      sentByEnter = true;
      send();
    });
    target.addEventListener('change', () => {
      if (sentByEnter) { sentByEnter = false; return; }  // already sent by its Enter
      send();
    });

    root.append(el('div', { class: 'joint' },
      el('label', { for: id, class: 'name' }, joint.name, el('span', { class: 'muted' }, ` ${joint.gripper ? 'gripper' : joint.kind}`)),
      slider, target,
      el('div', { class: 'values' }, readout, ' ', el('span', { class: 'muted' }, joint.unit), ' ', raw),
      el('div', { class: 'limits muted' },
        `${fmt(joint.min)}…${fmt(joint.max)} ${joint.unit} · raw ${fmt(joint.raw_min, 0)}…${fmt(joint.raw_max, 0)} ${joint.raw_unit}`)));
  }

  onState((state) => {
    const now = performance.now();
    for (const j of state.joints || []) {
      const row = rows.get(j.name);
      if (!row) continue;
      row.readout.textContent = fmt(j.position, 1);
      row.raw.textContent = `raw ${fmt(j.raw, 0)} ${row.joint.raw_unit}`;
      row.slider.dataset.position = j.position;
      if (!row.holding && now > row.holdUntil) {
        row.slider.value = j.position;
        if (document.activeElement !== row.target) row.target.value = fmt(j.position, 1);
      }
    }
  });
}
