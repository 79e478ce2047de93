// Live state: the server's event stream (one "state" event per published snapshot, >= 20/s
// while moving). Subscribers get every snapshot; the latest is kept for late readers.
import { api, eventsUrl, clientId } from './api.js';

const subscribers = new Set();
let latest = null;
let connected = false;
// Counts for the browser tests (the live rate while moving): events received so far.
const counters = { events: 0 };
window.armctlLive = counters;
const connectionListeners = new Set();

export function onState(fn) {
  subscribers.add(fn);
  if (latest) fn(latest);
}
// Control as seen by this client: only from /state, which carries this page's client id
// (the event stream cannot send the header, so its "you" may speak for nobody).
const controlListeners = new Set();
export function onControl(fn) { controlListeners.add(fn); if (latest) fn(latest.control); }
function publishControl(state) { for (const fn of controlListeners) fn(state.control); }

export function onConnection(fn) { connectionListeners.add(fn); fn(connected); }
export function latestState() { return latest; }

export function publish(state) {
  latest = state;
  for (const fn of subscribers) fn(state);
}

function setConnected(value) {
  if (value === connected) return;
  connected = value;
  for (const fn of connectionListeners) fn(value);
}

export async function startLive() {
  // A first snapshot at once (the stream may take up to a second when idle).
  const first = await api.get('/api/v1/state');
  publish(first);
  publishControl(first);
  const separator = eventsUrl().includes('?') ? '&' : '?';
  const source = new EventSource(`${eventsUrl()}${separator}client=${clientId}`);
  source.addEventListener('open', () => setConnected(true));
  source.addEventListener('error', () => setConnected(false)); // EventSource reconnects itself
  source.addEventListener('state', (event) => {
    setConnected(true);
    counters.events += 1;
    try { publish(JSON.parse(event.data)); } catch { /* a torn event: the next one follows */ }
  });
}

// A fresh snapshot now (after an action whose effect the page shows at once: control).
export async function refreshState() {
  try {
    const state = await api.get('/api/v1/state', { quiet: true });
    publish(state);
    publishControl(state);
  } catch { /* shown by the link state */ }
}
