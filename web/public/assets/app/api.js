// The one way the page talks to armctl serve: the JSON HTTP API of docs/http-api.md.
// Every request carries this page's client id (control is per client) and, when the page
// was opened with ?token=T (a non-loopback listen), the token as a bearer header.

const params = new URLSearchParams(location.search);
export const token = params.get('token') || '';

// crypto.randomUUID needs a secure context; a dashboard on a LAN address is not one.
function randomClientId() {
  const bytes = new Uint8Array(16);
  crypto.getRandomValues(bytes);
  return Array.from(bytes, (b) => b.toString(16).padStart(2, '0')).join('');
}
// A reload the page asks for itself (reloadKeepingControl) keeps its client id, and so the
// control it holds: handed over once through this tab's session storage.
const HANDOVER = 'armctl.client';
function pageClientId() {
  try {
    const kept = sessionStorage.getItem(HANDOVER);
    sessionStorage.removeItem(HANDOVER);
    if (kept && /^[0-9a-f]{32}$/.test(kept)) return kept;
  } catch (e) {
    // no session storage (a locked-down browser): a new id, control taken again
  }
  return randomClientId();
}
export const clientId = pageClientId();
export function reloadKeepingControl() {
  try { sessionStorage.setItem(HANDOVER, clientId); } catch (e) { /* the reloaded page asks for control */ }
  window.location.reload();
}

// A refused request: the server's message, its status, what was asked, and the answer's
// whole body (its typed detail: "collision" for a move that would collide).
export class ApiError extends Error {
  constructor(status, message, method, path, body = null) {
    super(message);
    this.status = status;
    this.method = method;
    this.path = path;
    this.body = body;
  }
}

const listeners = new Set();
// fn(error) for every refused or failed request (the page shows them all in one place).
export function onApiError(fn) { listeners.add(fn); }
const answerListeners = new Set();
// fn(method, path, answer) for every accepted request (the 3D view clears a refusal's red
// bodies when a move is taken).
export function onApiAnswer(fn) { answerListeners.add(fn); }

function headers(hasBody) {
  const h = { 'X-Armctl-Client': clientId };
  if (hasBody) h['Content-Type'] = 'application/json';
  if (token) h.Authorization = `Bearer ${token}`;
  return h;
}

async function request(method, path, body, { quiet = false } = {}) {
  let response;
  try {
    response = await fetch(path, {
      method,
      headers: headers(body !== undefined),
      body: body === undefined ? undefined : JSON.stringify(body),
      cache: 'no-store',
    });
  } catch (e) {
    const error = new ApiError(0, `armctl serve cannot be reached (${e.message})`, method, path);
    if (!quiet) listeners.forEach((fn) => fn(error));
    throw error;
  }
  const type = response.headers.get('Content-Type') || '';
  const payload = type.includes('json') ? await response.json().catch(() => null) : await response.text();
  if (!response.ok) {
    const message = payload && typeof payload === 'object' && payload.error
      ? payload.error : `${response.status} ${response.statusText}`;
    const error = new ApiError(response.status, message, method, path, payload && typeof payload === 'object' ? payload : null);
    if (!quiet) listeners.forEach((fn) => fn(error));
    throw error;
  }
  answerListeners.forEach((fn) => fn(method, path, payload));
  return payload;
}

export const api = {
  get: (path, options) => request('GET', path, undefined, options),
  post: (path, body = {}, options) => request('POST', path, body, options),
  put: (path, body, options) => request('PUT', path, body, options),
  del: (path, options) => request('DELETE', path, undefined, options),
};

// The event stream's URL: EventSource cannot send headers, so the token rides in the query.
export function eventsUrl() {
  return token ? `/api/v1/events?token=${encodeURIComponent(token)}` : '/api/v1/events';
}
