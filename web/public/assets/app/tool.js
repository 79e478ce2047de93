// The tool in millimetres and degrees: the live pose, jog buttons per axis with a step
// size (POST /api/v1/jog) or, with "hold to move", moving while held (POST /api/v1/servo every
// 50 ms, along or about the base frame's axes or the tool's; released, it stops: the server
// brings the arm to rest when the posts stop coming, also when the page is closed or the
// connection lost), the keys w/s a/d r/f doing the same for x, y, z; per-joint buttons that
// move one joint while held (the same POST, with a joint); speed sliders for both; and a
// "move tool to" form (POST /api/v1/tool), optionally around obstacles ("avoid").
import { api } from './api.js';
import { el, $, fmt, busy } from './dom.js';
import { onState } from './live.js';

const AXES = [
  { axis: 'x', unit: 'mm' }, { axis: 'y', unit: 'mm' }, { axis: 'z', unit: 'mm' },
  { axis: 'roll', unit: 'deg' }, { axis: 'pitch', unit: 'deg' }, { axis: 'yaw', unit: 'deg' },
];

// A speed slider with its value and unit beside it (a range input: arrow keys, Page Up/Down,
// Home/End move it from the keyboard). The server's limits are the sliders' ends.
function speedSlider(label, unit, min, max, value) {
  const input = el('input', { type: 'range', min, max, step: 1, value, 'aria-label': label });
  const shown = el('output', { 'aria-label': `${label} value` });
  const show = () => {
    shown.textContent = `${input.value} ${unit}`;
    input.setAttribute('aria-valuetext', shown.textContent);
  };
  input.addEventListener('input', show);
  show();
  return { input, label: el('label', { class: 'speed' }, input, ' ', shown) };
}

export function initTool(model) {
  const root = $('#tool');
  const stepMm = el('input', { type: 'number', min: 0.1, max: 100, step: 'any', value: 10, 'aria-label': 'Jog step (mm)' });
  const stepDeg = el('input', { type: 'number', min: 0.1, max: 90, step: 'any', value: 5, 'aria-label': 'Jog step (deg)' });
  const linear = el('input', { type: 'checkbox', checked: true, 'aria-label': 'Straight line' });
  const hold = el('input', { type: 'checkbox', 'aria-label': 'Hold to move' });
  // Held axes move in the base frame or the tool's own (x along the approach).
  const frame = el('select', { 'aria-label': 'Hold to move frame' },
    el('option', { value: 'base' }, 'base frame'), el('option', { value: 'tool' }, 'tool frame'));
  const avoid = el('input', { type: 'checkbox', 'aria-label': 'Avoid obstacles' });
  const speedMm = speedSlider('Hold speed (mm/s)', 'mm/s', 1, 100, 25);
  const speedDeg = speedSlider('Hold speed (deg/s)', 'deg/s', 1, 60, 20);
  const speedJoint = speedSlider('Joint hold speed (% of its limit)', '%', 5, 100, 20);
  let held = null;  // { body, timer } while a button or key is held
  const servo = (body) => api.post('/api/v1/servo', body).catch(() => release());
  // body: { axis } or { joint }; speed(): the signed speed, read when pressed.
  const press = (body, speed) => {
    if (held) release();
    const command = { ...body, speed: speed() };
    if (body.axis) command.frame = frame.value;
    servo(command);
    held = { body, timer: setInterval(() => servo(command), 50) };
  };
  const release = () => {
    if (!held) return;
    clearInterval(held.timer);
    const { body } = held;
    held = null;
    api.post('/api/v1/servo', { ...body, speed: 0 }).catch(() => {});
  };
  const holdHandlers = (body, speed) => ({
    onpointerdown: (e) => { if (hold.checked) { e.currentTarget.setPointerCapture?.(e.pointerId); press(body, speed); } },
    onpointerup: release, onpointercancel: release, onlostpointercapture: release,
  });
  const axisSpeed = (unit, sign) => () => sign * Number(unit === 'mm' ? speedMm.input.value : speedDeg.input.value);
  const KEYS = { w: ['x', 1], s: ['x', -1], a: ['y', 1], d: ['y', -1], r: ['z', 1], f: ['z', -1] };
  document.addEventListener('keydown', (e) => {
    const k = KEYS[e.key];
    if (!hold.checked || !k || e.repeat || e.target.closest('input, textarea, select')) return;
    press({ axis: k[0] }, axisSpeed('mm', k[1]));
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
    const minus = el('button', { type: 'button', 'aria-label': `jog ${axis} minus`, onclick: step(-1), ...holdHandlers({ axis }, axisSpeed(unit, -1)) }, `${axis} −`);
    const plus = el('button', { type: 'button', 'aria-label': `jog ${axis} plus`, onclick: step(1), ...holdHandlers({ axis }, axisSpeed(unit, 1)) }, `${axis} +`);
    body.append(el('tr', {}, el('th', {}, axis), el('td', {}, now, ' ', el('span', { class: 'muted' }, unit)),
      el('td', {}, minus, plus), el('td', {}, target)));
  }

  // Joint jog: each joint (not the gripper, which has its own control) moves while its
  // button is held, at the slider's share of its velocity limit; only with "hold to move".
  const jointButtons = [];
  const jointRows = el('tbody');
  for (const joint of model.joints.filter((j) => !j.gripper)) {
    const speed = (sign) => () => sign * Math.round(Number(speedJoint.input.value) / 100 * joint.max_velocity * 10) / 10;
    const button = (sign, text) => {
      const b = el('button', { type: 'button', disabled: true, 'aria-label': `joint ${joint.name} ${sign < 0 ? 'minus' : 'plus'}`,
        ...holdHandlers({ joint: joint.name }, speed(sign)) }, text);
      jointButtons.push(b);
      return b;
    };
    jointRows.append(el('tr', {}, el('th', {}, joint.name),
      el('td', {}, button(-1, `${joint.name} −`), button(1, `${joint.name} +`)),
      el('td', { class: 'muted' }, `up to ${fmt(joint.max_velocity, 0)} ${joint.unit}/s`)));
  }
  const jointTable = el('table', { class: 'tool', 'aria-label': 'Joint jog' },
    el('thead', {}, el('tr', {}, el('th', {}, 'joint'), el('th', {}, 'hold to move'), el('th', {}, 'limit'))), jointRows);
  hold.addEventListener('change', () => {
    for (const b of jointButtons) b.disabled = !hold.checked;
    if (!hold.checked) release();
  });

  const moveTo = el('button', { type: 'button', onclick: (e) => busy(e.currentTarget, () => {
    const body = { linear: linear.checked };
    // Around obstacles: a PTP only (a straight line has no detour).
    if (avoid.checked && !linear.checked) body.avoid = true;
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
      el('label', {}, hold, ' hold to move'), ' in the ', frame, ' at ', speedMm.label, speedDeg.label),
    table,
    el('div', { class: 'row' }, 'Joints, held: ', speedJoint.label),
    jointTable,
    el('div', { class: 'row' }, copy, moveTo,
      el('label', { title: 'When the direct move would collide, go around the scene\'s objects (not with straight line)' },
        avoid, ' avoid obstacles')));
  const avoidUsable = () => { avoid.disabled = linear.checked; };
  linear.addEventListener('change', avoidUsable);
  avoidUsable();

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
