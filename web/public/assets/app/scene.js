// The planning scene (docs/scene.md, docs/http-api.md "Scene"): the objects listed, a box,
// cylinder, capsule or sphere added with its size and place, an object moved (its position edited)
// or removed, and the scene saved to the file armctl serve was started with. Changes need
// control (the panel is disabled while another client has it).
// The scene itself is shared with the 3D view (onScene): read at start, after each change
// made here, and every 2 s (another client may change it).
import { api } from './api.js';
import { el, $, fmt, busy } from './dom.js';

const POLL_MS = 2000;
// The scene file's limits (docs/scene.md "Scene files"): checked here too, so that each
// field says what is wrong before anything is sent; the server checks them again.
const NAME = /^[A-Za-z0-9_.-]{1,40}$/;
const SIZE = { min: 0.1, max: 10000, unit: 'mm' };
const COORDINATE = { min: -10000, max: 10000, unit: 'mm' };
const ANGLE = { min: -360, max: 360, unit: 'deg' };

const listeners = new Set();
let current = null;
let currentText = '';

// fn(scene) now (when read) and whenever the scene changes: {"objects": [...], "file"}.
export function onScene(fn) {
  listeners.add(fn);
  if (current) fn(current);
}

function setScene(scene) {
  const text = JSON.stringify(scene);
  if (text === currentText) return;
  currentText = text;
  current = scene;
  for (const fn of listeners) fn(scene);
}

export async function refreshScene() {
  try { setScene(await api.get('/api/v1/scene', { quiet: true })); } catch { /* the link state shows it */ }
}

const SHAPES = {
  box: [['x', 'size x'], ['y', 'size y'], ['z', 'size z']],
  cylinder: [['radius', 'radius'], ['length', 'length']],
  capsule: [['radius', 'radius'], ['length', 'length']],
  sphere: [['radius', 'radius']],
};

// The object's words: its shape and size.
function describe(o) {
  if (o.table) return `table, top at ${fmt(o.table.top ?? 0)} mm`;
  const role = o.keep_out ? 'keep-out ' : o.attached ? 'held ' : '';
  if (o.box) return `${role}box ${o.box.map((v) => fmt(v)).join(' × ')} mm`;
  if (o.cylinder) return `${role}cylinder r ${fmt(o.cylinder.radius)} × ${fmt(o.cylinder.length)} mm`;
  if (o.capsule) return `${role}capsule r ${fmt(o.capsule.radius)} × ${fmt(o.capsule.length)} mm`;
  if (o.sphere) return `${role}sphere r ${fmt(o.sphere.radius)} mm`;
  return 'unknown shape';
}

// A number field with its own error line (aria-describedby), checked against `range`.
function numberField(label, range, value = '') {
  const input = el('input', { type: 'number', step: 'any', value, 'aria-label': label, class: 'target' });
  const error = el('span', { class: 'field-error', role: 'alert' });
  const id = `field-${Math.random().toString(36).slice(2)}`;
  error.id = id;
  input.setAttribute('aria-describedby', id);
  const check = () => {
    const text = input.value.trim();
    const v = Number(text);
    let problem = '';
    if (text === '') problem = 'required';
    else if (!Number.isFinite(v) || v < range.min || v > range.max) problem = `${text} is outside ${range.min}..${range.max} ${range.unit}`;
    error.textContent = problem ? `${label}: ${problem}` : '';
    input.setAttribute('aria-invalid', String(Boolean(problem)));
    return problem ? null : v;
  };
  input.addEventListener('input', () => { if (error.textContent) check(); });
  return { input, error, check, wrap: el('span', { class: 'field' }, input, error) };
}

export function initScene() {
  const root = $('#scene');
  const list = el('tbody');
  const file = el('p', { class: 'muted', 'aria-label': 'Scene file' });
  const status = el('p', { role: 'status', 'aria-label': 'Scene status', class: 'muted' });
  // Empty, it is not shown (nor an alert to assistive technology): see style.css.
  const formError = el('p', { role: 'alert', class: 'bad scene-error', 'aria-label': 'Scene error' });
  const sayError = (e) => { formError.textContent = e.message; status.textContent = ''; };
  const said = (text) => { formError.textContent = ''; status.textContent = text; };

  // An object's change, answered with the scene as it is now.
  const put = async (name, object) => {
    const answer = await api.put(`/api/v1/scene/objects/${encodeURIComponent(name)}`, object);
    setScene(answer.scene);
    return answer;
  };

  function row(o) {
    const placed = !o.table;
    const at = (o.at || [0, 0, 0]).map((v, i) => numberField(`${o.name} ${'xyz'[i]} (mm)`, COORDINATE, fmt(v, 3)));
    const move = el('button', { type: 'button', 'aria-label': `Move ${o.name}`, onclick: (e) => busy(e.currentTarget, async () => {
      const values = at.map((f) => f.check());
      if (values.some((v) => v === null)) return;
      try {
        await put(o.name, { ...o, at: values });
        said(`${o.name} moved to (${values.map((v) => fmt(v)).join(', ')}) mm`);
      } catch (err) { sayError(err); }
    }) }, 'Move');
    const remove = el('button', { type: 'button', 'aria-label': `Remove ${o.name}`, onclick: (e) => busy(e.currentTarget, async () => {
      try {
        const answer = await api.del(`/api/v1/scene/objects/${encodeURIComponent(o.name)}`);
        setScene(answer.scene);
        said(`${o.name} removed`);
      } catch (err) { sayError(err); }
    }) }, 'Remove');
    return el('tr', { 'data-object': o.name },
      el('th', {}, o.name),
      el('td', {}, describe(o), o.attached ? el('span', { class: 'muted' }, ' (in the tool frame)') : ''),
      el('td', {}, placed ? at.map((f) => f.wrap) : el('span', { class: 'muted' }, '–')),
      el('td', {}, placed ? move : '', remove));
  }

  onScene((scene) => {
    list.replaceChildren(...(scene.objects || []).map(row));
    if (!scene.objects || !scene.objects.length) list.append(el('tr', {}, el('td', { colspan: 4, class: 'muted' }, 'The scene is empty.')));
    file.textContent = scene.file ? `Scene file: ${scene.file}` : 'No scene file: start armctl serve with --scene FILE to save one.';
  });

  // Adding: a name, a shape and its size, where it stands.
  const name = el('input', { type: 'text', 'aria-label': 'New object name', placeholder: 'crate', maxlength: 40 });
  const nameError = el('span', { class: 'field-error', role: 'alert' });
  const shape = el('select', { 'aria-label': 'New object shape' },
    ...Object.keys(SHAPES).map((s) => el('option', { value: s }, s)));
  const defaults = { x: 50, y: 50, z: 50, radius: 25, length: 80 };
  let sizeFields = [];
  const sizes = el('span', { class: 'row' });
  const showSizes = () => {
    sizeFields = SHAPES[shape.value].map(([key, label]) => ({ key, field: numberField(`New object ${label} (mm)`, SIZE, defaults[key]) }));
    sizes.replaceChildren(...sizeFields.map(({ field }) => field.wrap));
  };
  shape.addEventListener('change', showSizes);
  showSizes();
  const position = ['x', 'y', 'z'].map((a, i) => numberField(`New object ${a} (mm)`, COORDINATE, [150, 0, 25][i]));
  // Turned (Z-Y-X, as the scene file's rpy): a cylinder or capsule lying down, a box at an angle.
  const turn = ['roll', 'pitch', 'yaw'].map((a) => numberField(`New object ${a} (deg)`, ANGLE, 0));
  const keepOut = el('input', { type: 'checkbox', 'aria-label': 'Keep-out zone' });
  const add = el('button', { type: 'button', onclick: (e) => busy(e.currentTarget, async () => {
    const n = name.value.trim();
    nameError.textContent = NAME.test(n) ? '' : 'New object name: 1..40 of a-z A-Z 0-9 _ - .';
    name.setAttribute('aria-invalid', String(!NAME.test(n)));
    const size = sizeFields.map(({ key, field }) => [key, field.check()]);
    const at = position.map((f) => f.check());
    const rpy = turn.map((f) => f.check());
    if (!NAME.test(n) || size.some(([, v]) => v === null) || at.some((v) => v === null) || rpy.some((v) => v === null)) return;
    const object = { at };
    if (rpy.some((v) => v !== 0)) object.rpy = rpy;
    if (shape.value === 'box') object.box = size.map(([, v]) => v);
    else object[shape.value] = Object.fromEntries(size);
    if (keepOut.checked) object.keep_out = true;
    try {
      const answer = await put(n, object);
      said(`${n} ${answer.replaced ? 'replaced' : 'added'}`);
    } catch (err) { sayError(err); }
  }) }, 'Add object');

  const save = el('button', { type: 'button', onclick: (e) => busy(e.currentTarget, async () => {
    try {
      const answer = await api.post('/api/v1/scene/save', {});
      said(`Saved ${answer.objects} objects to ${answer.saved}`);
    } catch (err) { sayError(err); }
  }) }, 'Save to scene file');

  root.append(
    el('table', { class: 'tool', 'aria-label': 'Scene objects' },
      el('thead', {}, el('tr', {}, el('th', {}, 'name'), el('th', {}, 'shape'), el('th', {}, 'position (mm)'), el('th', {}, ''))),
      list),
    el('div', { class: 'row', role: 'group', 'aria-label': 'Add an object' },
      el('span', { class: 'field' }, name, nameError), shape, sizes,
      el('span', { class: 'muted' }, 'at'), position.map((f) => f.wrap),
      el('span', { class: 'muted' }, 'turned'), turn.map((f) => f.wrap),
      el('label', {}, keepOut, ' keep-out'), add),
    el('div', { class: 'row' }, save, file),
    formError, status);

  refreshScene();
  setInterval(refreshScene, POLL_MS);
}
