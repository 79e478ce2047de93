// The action-group editor, as the board maker's PC software has it: the page holds the frame
// table (a Robot Commands board cannot send a group back), each frame a time and a position
// per joint. Frames come from the live positions (GET /api/v1/frame), from a file (import),
// or are typed in; the whole table is sent when it is downloaded (PUT /api/v1/groups/<n>).
import { api } from './api.js';
import { el, $, fmt, busy } from './dom.js';

function base64FromBytes(bytes) {
  let text = '';
  for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(text);
}
function bytesFromBase64(text) { return Uint8Array.from(atob(text), (c) => c.charCodeAt(0)); }

function download(name, data, type) {
  const url = URL.createObjectURL(new Blob([data], { type }));
  const a = el('a', { href: url, download: name });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

export function initGroups(model) {
  const root = $('#groups');
  if (!model.groups_supported) {
    root.append(el('h2', {}, 'Action groups'),
      el('p', { class: 'muted' }, 'Action groups need a Robot Commands board (an xArm, or the SCARA arm through its arm controller); this device speaks the joint bus.'));
    return;
  }
  const names = model.joints.map((j) => j.name);
  const units = new Map(model.joints.map((j) => [j.name, j.unit]));
  let frames = [];
  let selected = -1;

  const status = el('p', { class: 'muted', role: 'status', 'aria-label': 'Group editor status' }, 'No frames yet.');
  const tbody = el('tbody');
  const table = el('table', { class: 'frames', 'aria-label': 'Frames' },
    el('thead', {}, el('tr', {}, el('th', {}, '#'), el('th', {}, 'time ms'),
      ...names.map((n) => el('th', {}, n, el('span', { class: 'muted' }, ` ${units.get(n)}`))))),
    tbody);

  function render() {
    tbody.replaceChildren(...frames.map((frame, i) => {
      const cell = (value, label, onchange) => el('td', {}, el('input', {
        type: 'number', step: 'any', value: value ?? '', 'aria-label': `frame ${i + 1} ${label}`,
        onchange: (e) => onchange(e.currentTarget.value === '' ? undefined : Number(e.currentTarget.value)),
        onfocus: () => select(i),
      }));
      return el('tr', { class: i === selected ? 'selected' : '', 'aria-selected': String(i === selected), onclick: () => select(i) },
        el('td', {}, el('input', { type: 'radio', name: 'frame', checked: i === selected, 'aria-label': `select frame ${i + 1}`, onchange: () => select(i) }), ` ${i + 1}`),
        cell(frame.time_ms, 'time ms', (v) => { frame.time_ms = v; renderStatus(); }),
        ...names.map((n) => cell(frame.positions[n] === undefined ? undefined : fmt(frame.positions[n], 2), `${n} (${units.get(n)})`,
          (v) => { if (v === undefined) delete frame.positions[n]; else frame.positions[n] = v; })));
    }));
    renderStatus();
  }
  function renderStatus() {
    const total = frames.reduce((sum, f) => sum + (Number(f.time_ms) || 0), 0);
    status.textContent = frames.length
      ? `${frames.length} frame${frames.length === 1 ? '' : 's'}, ${fmt(total / 1000, 2)} s${selected >= 0 ? `; frame ${selected + 1} selected` : ''}`
      : 'No frames yet.';
  }
  function select(i) {
    if (selected === i) return;
    selected = i;
    for (const [k, row] of [...tbody.children].entries()) {
      row.classList.toggle('selected', k === i);
      row.setAttribute('aria-selected', String(k === i));
      row.querySelector('input[type=radio]').checked = k === i;
    }
    renderStatus();
  }

  const timeMs = el('input', { type: 'number', min: 0, max: 30000, step: 1, value: 1000, 'aria-label': 'Frame time (ms)' });
  async function currentFrame() {
    const frame = await api.get('/api/v1/frame');
    return { time_ms: Number(timeMs.value), positions: frame.positions };
  }
  const needSelection = () => {
    if (selected >= 0 && selected < frames.length) return true;
    status.textContent = 'Select a frame first.';
    return false;
  };
  const actions = {
    add: async () => { frames.push(await currentFrame()); selected = frames.length - 1; },
    insert: async () => {
      const at = selected >= 0 ? selected : 0;
      frames.splice(at, 0, await currentFrame());
      selected = at;
    },
    update: async () => {
      if (!needSelection()) return;
      frames[selected].positions = (await currentFrame()).positions;
    },
    remove: async () => {
      if (!needSelection()) return;
      frames.splice(selected, 1);
      selected = Math.min(selected, frames.length - 1);
    },
    up: async () => {
      if (!needSelection() || selected === 0) return;
      [frames[selected - 1], frames[selected]] = [frames[selected], frames[selected - 1]];
      selected -= 1;
    },
    down: async () => {
      if (!needSelection() || selected === frames.length - 1) return;
      [frames[selected + 1], frames[selected]] = [frames[selected], frames[selected + 1]];
      selected += 1;
    },
    clear: async () => { frames = []; selected = -1; },
  };
  const action = (label, fn, title) => el('button', { type: 'button', title, onclick: (e) => busy(e.currentTarget, async () => {
    try { await fn(); } finally { render(); }
  }) }, label);

  const group = el('input', { type: 'number', min: 0, max: 254, step: 1, value: 1, 'aria-label': 'Group number' });
  const count = el('input', { type: 'number', min: 1, step: 1, value: 1, 'aria-label': 'Run count' });
  const continuous = el('input', { type: 'checkbox', 'aria-label': 'Run continuously' });
  const speed = el('input', { type: 'number', min: 1, max: 1000, step: 1, value: 100, 'aria-label': 'Group speed (%)' });
  const groupPath = () => `/api/v1/groups/${encodeURIComponent(group.value)}`;
  const say = (text) => { status.textContent = text; };
  const board = {
    download: async () => {
      await api.put(groupPath(), { frames });
      say(`Downloaded ${frames.length} frame${frames.length === 1 ? '' : 's'} as group ${group.value}.`);
    },
    run: async () => {
      await api.post(`${groupPath()}/run`, continuous.checked ? { continuous: true } : { count: Number(count.value) });
      say(`Group ${group.value} running${continuous.checked ? ' continuously' : ` ${count.value} time${count.value === '1' ? '' : 's'}`}.`);
    },
    stop: async () => { await api.post('/api/v1/groups/stop', {}); say('Group stopped.'); },
    erase: async () => { await api.del(groupPath()); say(`Group ${group.value} erased.`); },
    speed: async () => { await api.post('/api/v1/groups/speed', { percent: Number(speed.value) }); say(`Group speed ${speed.value}%.`); },
  };
  const boardButton = (label, fn) => el('button', { type: 'button', onclick: (e) => busy(e.currentTarget, fn) }, label);

  const exportFormat = el('select', { 'aria-label': 'Export format' },
    el('option', { value: 'group' }, 'group file (.group)'), el('option', { value: 'rob' }, 'PC software file (.rob)'));
  const importFile = el('input', { type: 'file', accept: '.group,.rob,.txt', 'aria-label': 'Import group file' });
  importFile.addEventListener('change', () => busy(importFile, async () => {
    const file = importFile.files[0];
    if (!file) return;
    const rob = file.name.toLowerCase().endsWith('.rob');
    const content = rob ? base64FromBytes(new Uint8Array(await file.arrayBuffer())) : await file.text();
    try {
      const answer = await api.post('/api/v1/groups/import', { format: rob ? 'rob' : 'group', content });
      frames = answer.frames;
      selected = frames.length ? 0 : -1;
      render();
      say(`Imported ${frames.length} frames from ${file.name}.`);
    } finally { importFile.value = ''; }
  }));
  const exportButton = boardButton('Export', async () => {
    const format = exportFormat.value;
    const answer = await api.post('/api/v1/groups/export', { format, frames });
    const name = `group-${group.value}.${format}`;
    if (format === 'rob') download(name, bytesFromBase64(answer.content), 'application/octet-stream');
    else download(name, answer.content, 'text/plain');
    say(`Exported ${frames.length} frames as ${name}.`);
  });

  root.append(
    el('h2', {}, 'Action groups'),
    el('div', { class: 'row' },
      el('label', {}, 'Time ', timeMs, ' ms'),
      action('Read current positions', actions.add, 'Append a frame with the arm\'s current positions'),
      action('Insert frame', actions.insert, 'Insert a frame with the current positions before the selected one'),
      action('Update frame', actions.update, 'Set the selected frame to the current positions'),
      action('Delete frame', actions.remove),
      action('Move up', actions.up), action('Move down', actions.down),
      action('Clear table', actions.clear)),
    el('div', { class: 'table-scroll' }, table),
    status,
    el('div', { class: 'row' },
      el('label', {}, 'Group ', group), boardButton('Download', board.download),
      el('label', {}, 'Count ', count), el('label', {}, continuous, ' continuous'), boardButton('Run', board.run),
      boardButton('Stop group', board.stop), boardButton('Erase', board.erase),
      el('label', {}, 'Speed ', speed, ' %'), boardButton('Set speed', board.speed)),
    el('div', { class: 'row' },
      el('label', {}, 'Import ', importFile), exportFormat, exportButton));
  render();
}
