// The tool in millimetres and degrees: the live pose, jog buttons per axis with a step
// size (POST /api/v1/jog) or, with "hold to move", moving while held (POST /api/v1/servo every
// 50 ms; released, it stops: the server brings the arm to rest when the posts stop coming,
// also when the page is closed or the connection lost), the keys w/s a/d r/f doing the same
// for x, y, z; and a "move tool to" form (POST /api/v1/tool).
import { api } from './api.js';
import { el, $, fmt, busy } from './dom.js';
import { onState } from './live.js';

const AXES = [
  { axis: 'x', unit: 'mm' }, { axis: 'y', unit: 'mm' }, { axis: 'z', unit: 'mm' },
  { axis: 'roll', unit: 'deg' }, { axis: 'pitch', unit: 'deg' }, { axis: 'yaw', unit: 'deg' },
];

export function initTool(model) {
  const root = $('#tool');
  const stepMm = el('input', { type: 'number', min: 0.1, max: 100, step: 'any', value: 10, 'aria-label': 'Jog step (mm)' });
  const stepDeg = el('input', { type: 'number', min: 0.1, max: 90, step: 'any', value: 5, 'aria-label': 'Jog step (deg)' });
  const linear = el('input', { type: 'checkbox', checked: true, 'aria-label': 'Straight line' });
  const hold = el('input', { type: 'checkbox', 'aria-label': 'Hold to move' });
  const speedMm = el('input', { type: 'number', min: 1, max: 100, step: 'any', value: 25, 'aria-label': 'Hold speed (mm/s)' });
  const speedDeg = el('input', { type: 'number', min: 1, max: 60, step: 'any', value: 20, 'aria-label': 'Hold speed (deg/s)' });
  let held = null;  // { axis, timer } while a button or key is held
  const servo = (axis, speed) => api.post('/api/v1/servo', { axis, speed }).catch(() => release());
  const press = (axis, unit, sign) => {
    if (held) release();
    const speed = sign * Number(unit === 'mm' ? speedMm.value : speedDeg.value);
    servo(axis, speed);
    held = { axis, timer: setInterval(() => servo(axis, speed), 50) };
  };
  const release = () => {
    if (!held) return;
    clearInterval(held.timer);
    const { axis } = held;
    held = null;
    api.post('/api/v1/servo', { axis, speed: 0 }).catch(() => {});
  };
  const holdHandlers = (axis, unit, sign) => ({
    onpointerdown: (e) => { if (hold.checked) { e.currentTarget.setPointerCapture?.(e.pointerId); press(axis, unit, sign); } },
    onpointerup: release, onpointercancel: release, onlostpointercapture: release,
  });
  const KEYS = { w: ['x', 1], s: ['x', -1], a: ['y', 1], d: ['y', -1], r: ['z', 1], f: ['z', -1] };
  document.addEventListener('keydown', (e) => {
    const k = KEYS[e.key];
    if (!hold.checked || !k || e.repeat || e.target.closest('input, textarea, select')) return;
    press(k[0], 'mm', k[1]);
  });
  document.addEventListener('keyup', (e) => { if (KEYS[e.key] && held) release(); });
  window.addEventListener('blur', release);
  const pose = new Map();
  const targets = new Map();

  const jog = (axis, unit, sign, button) => busy(button, () => api.post('/api/v1/jog', {
    axis, step: sign * Number(unit === 'mm' ? stepMm.value : stepDeg.value), linear: linear.checked,
  }));

  const table = el('table', { class: 'tool' },
    el('thead', {}, el('tr', {}, el('th', {}, 'axis'), el('th', {}, 'now'), el('th', {}, 'jog'), el('th', {}, 'move to'))));
  const body = el('tbody');
  table.append(body);
  for (const { axis, unit } of AXES) {
    const now = el('output', { 'aria-label': `tool ${axis} (${unit})` }, '–');
    pose.set(axis, now);
    const target = el('input', { type: 'number', step: 'any', class: 'target', 'aria-label': `tool ${axis} target (${unit})` });
    targets.set(axis, target);
    const step = (sign) => (e) => { if (!hold.checked) jog(axis, unit, sign, e.currentTarget); };
    const minus = el('button', { type: 'button', 'aria-label': `jog ${axis} minus`, onclick: step(-1), ...holdHandlers(axis, unit, -1) }, `${axis} −`);
    const plus = el('button', { type: 'button', 'aria-label': `jog ${axis} plus`, onclick: step(1), ...holdHandlers(axis, unit, 1) }, `${axis} +`);
    body.append(el('tr', {}, el('th', {}, axis), el('td', {}, now, ' ', el('span', { class: 'muted' }, unit)),
      el('td', {}, minus, plus), el('td', {}, target)));
  }

  const moveTo = el('button', { type: 'button', onclick: (e) => busy(e.currentTarget, () => {
    const body = { linear: linear.checked };
    for (const [axis, input] of targets) {
      if (input.value !== '') body[axis] = Number(input.value);
    }
    return api.post('/api/v1/tool', body);
  }) }, 'Move tool');
  const copy = el('button', { type: 'button', onclick: () => {
    for (const [axis, out] of pose) targets.get(axis).value = out.dataset.value ?? '';
  } }, 'Use current pose');

  root.append(
    el('div', { class: 'row' },
      el('label', {}, 'Step ', stepMm, ' mm'), el('label', {}, ' ', stepDeg, ' deg'),
      el('label', {}, linear, ' straight line')),
    el('div', { class: 'row' },
      el('label', {}, hold, ' hold to move'), el('label', {}, ' at ', speedMm, ' mm/s'), el('label', {}, ' ', speedDeg, ' deg/s')),
    table,
    el('div', { class: 'row' }, copy, moveTo));

  onState((state) => {
    for (const { axis } of AXES) {
      const out = pose.get(axis);
      const value = state.tool ? state.tool[axis] : null;
      out.textContent = fmt(value, 1);
      if (value == null) delete out.dataset.value; else out.dataset.value = fmt(value, 2);
    }
  });
  if (!model.tool_frame) root.prepend(el('p', { class: 'muted' }, 'This arm has no tool frame.'));
}
