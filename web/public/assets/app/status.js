// Always on screen: link, battery, job, faults, control (watch mode), STOP and the errors.
import { api, onApiError } from './api.js';
import { el, $, fmt } from './dom.js';
import { onState, onControl, onConnection, refreshState } from './live.js';

const MAX_ERRORS = 4;

export function showError(message) {
  const list = $('#errors');
  // One banner per error: the same message again (a request's answer and the state's
  // last_error say the same thing) moves its banner to the top instead of adding another.
  for (const item of list.children) {
    if (item.firstElementChild && item.firstElementChild.textContent === message) {
      list.prepend(item);
      return;
    }
  }
  const item = el('div', { class: 'error', role: 'alert' },
    el('span', {}, message),
    el('button', { type: 'button', class: 'dismiss', 'aria-label': 'Dismiss error', onclick: () => item.remove() }, '×'));
  list.prepend(item);
  while (list.children.length > MAX_ERRORS) list.lastElementChild.remove();
}

export function clearErrors() { $('#errors').replaceChildren(); }

async function stop() {
  // Accepted from anyone, always: no control check, no confirmation.
  try {
    const answer = await api.post('/api/v1/stop', {});
    // Taken, but with the link lost it may not have reached the arm: say so.
    if (answer && answer.warning) showError(`STOP: ${answer.warning}`);
  } catch { /* shown */ }
}

// The faults the joints hold (a runaway, a following error): cleared once the cause is
// fixed; each joint then holds where it is and drives again. Needs control, as a move.
async function clearFaults() {
  try { await api.post('/api/v1/clear-faults', {}); } catch { /* shown */ }
  await refreshState();
}

async function takeControl() {
  try { await api.post('/api/v1/control', { take: true }); } catch { /* shown */ }
  await refreshState();
}

let watching = false;
function setWatching(value) {
  if (value === watching) return;
  watching = value;
  document.body.classList.toggle('watching', value);
  // Another client drives the arm: this page watches until it takes over.
  for (const panel of document.querySelectorAll('[role=tabpanel]')) panel.disabled = value;
}

function renderControl(control) {
  const box = $('#control');
  if (!control) { box.replaceChildren(); return; }
  if (control.you) {
    box.replaceChildren(el('span', { class: 'ok' }, 'You have control'));
    setWatching(false);
    return;
  }
  const since = control.since && !Number.isNaN(Date.parse(control.since))
    ? new Date(control.since).toLocaleTimeString() : control.since;
  const text = control.holder
    ? `Watching: another client has control${since ? ` since ${since}` : ''}`
    : 'Nobody has control';
  box.replaceChildren(el('span', { class: 'warn' }, text),
    el('button', { type: 'button', onclick: takeControl }, 'Take control'));
  setWatching(Boolean(control.holder));
}

export function initStatus(model) {
  $('#arm-name').textContent = model.arm;
  $('#arm-description').textContent = [model.description, model.device].filter(Boolean).join(' · ');
  document.title = `armctl · ${model.arm}`;
  $('#stop').addEventListener('click', stop);
  $('#clear-faults').addEventListener('click', clearFaults);
  document.addEventListener('keydown', (event) => {
    if (event.key === 'Escape') { event.preventDefault(); stop(); }
  });
  onApiError((error) => showError(`${error.method} ${error.path}: ${error.message}${error.status ? ` (${error.status})` : ''}`));

  let streamUp = false;
  let everUp = false;
  let lastLink = null;
  const renderLink = () => {
    const link = $('#link-state');
    // Before the event stream first opens the page is connecting, not broken.
    if (!streamUp && !everUp) { link.textContent = 'connecting…'; link.className = 'muted'; return; }
    if (!streamUp) { link.textContent = 'no connection to armctl serve'; link.className = 'bad'; return; }
    if (!lastLink) return;
    // A device armctl serve does not open again (a Robot Commands board) needs a restart.
    const restart = lastLink.reconnects ? '' : ' (restart armctl serve once the arm is back)';
    link.textContent = lastLink.ok ? 'ok' : `down: ${lastLink.error || 'no answer'}${restart}`;
    link.className = lastLink.ok ? 'ok' : 'bad';
  };
  onConnection((up) => { streamUp = up; everUp = everUp || up; renderLink(); });
  let lastErrorShown = '';
  onState((state) => {
    lastLink = state.link;
    renderLink();
    $('#battery').textContent = state.battery_volts == null ? 'n/a' : `${fmt(state.battery_volts, 2)} V`;
    $('#job').textContent = state.job || 'idle';
    const faults = state.faults || [];
    $('#faults').textContent = faults.length ? faults.join('; ') : 'none';
    $('#faults').className = faults.length ? 'bad' : 'ok';
    $('#clear-faults').hidden = faults.length === 0;
    // The scene's fence and reduced mode: null where the scene sets none.
    const limits = state.limits || {};
    const words = [['fence', limits.fence], ['reduced mode', limits.reduced]]
      .filter(([, on]) => on != null).map(([name, on]) => `${name} ${on ? 'on' : 'off'}`);
    $('#limits').textContent = words.length ? words.join(', ') : 'none';
    // A job that failed in the background (a run, a group) reports here, not to a request.
    if (state.last_error && state.last_error !== lastErrorShown) showError(state.last_error);
    lastErrorShown = state.last_error || '';
  });
  onControl(renderControl);
  // Control changes when another client takes over: read it for this client every second.
  setInterval(refreshState, 1000);
}

export async function takeControlIfFree(state) {
  if (state.control && !state.control.holder) await takeControl();
}
