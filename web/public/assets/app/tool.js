// The tool in millimetres and degrees: the live pose, jog buttons per axis with a step
// size (POST /api/v1/jog) and a "move tool to" form (POST /api/v1/tool).
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
    const minus = el('button', { type: 'button', 'aria-label': `jog ${axis} minus`, onclick: (e) => jog(axis, unit, -1, e.currentTarget) }, `${axis} −`);
    const plus = el('button', { type: 'button', 'aria-label': `jog ${axis} plus`, onclick: (e) => jog(axis, unit, 1, e.currentTarget) }, `${axis} +`);
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
