// The browser tests' harness: starts `armctl serve` on a free loopback port with the
// embedded simulators, drives Debian's chromium (headless) through playwright-core, and
// gives the tests an HTTP client of their own (another client, as a script would be).
// Waits are for conditions (a poll with a deadline), never for a fixed time.
import { before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { createRequire } from 'node:module';
import fs from 'node:fs';
import net from 'node:net';
import path from 'node:path';
import { randomBytes } from 'node:crypto';

const require = createRequire(new URL('../../web/package.json', import.meta.url));
const { chromium } = require('playwright-core');

export const cli = process.env.ARMCTL_CLI || path.resolve('build/armctl');
export const artifacts = process.env.ARMCTL_ARTIFACTS_DIR || path.resolve('build/test-artifacts/browser');
const chromiumPath = process.env.ARMCTL_CHROMIUM || '/usr/bin/chromium';
const WAIT_MS = Number(process.env.ARMCTL_BROWSER_WAIT_MS || 20000);

// Polls `probe` until it returns a truthy value (which is returned) or the deadline passes.
export async function waitFor(probe, what, timeoutMs = WAIT_MS) {
  const deadline = Date.now() + timeoutMs;
  let last;
  for (;;) {
    try {
      last = await probe();
      if (last) return last;
    } catch (e) { last = e; }
    if (Date.now() > deadline) throw new Error(`timed out waiting for ${what} (last: ${last instanceof Error ? last.message : JSON.stringify(last)})`);
    await new Promise((resolve) => setImmediate(resolve));
    await new Promise((resolve) => setTimeout(resolve, 20)); // a poll interval, not a settle time
  }
}

async function freePort(host) {
  return new Promise((resolve, reject) => {
    const server = net.createServer();
    server.once('error', reject);
    server.listen(0, host, () => {
      const { port } = server.address();
      server.close(() => resolve(port));
    });
  });
}

// A running `armctl serve`: its base URL, token (when it prints one), output, and stop().
export async function startServer({ arm = 'xarm', host = '127.0.0.1', token, extra = [] } = {}) {
  const port = await freePort(host);
  const args = ['serve', '--arm', arm, '--listen', `${host}:${port}`, ...extra];
  if (token) args.push('--token', token);
  const child = spawn(cli, args, { stdio: ['ignore', 'pipe', 'pipe'] });
  let output = '';
  let exited = null;
  child.stdout.on('data', (d) => { output += d; });
  child.stderr.on('data', (d) => { output += d; });
  child.on('exit', (code, signal) => { exited = { code, signal }; });
  const base = `http://${host}:${port}`;
  const server = {
    base, host, port, arm, child,
    get output() { return output; },
    token,
    async stop() {
      if (exited) return exited;
      const done = new Promise((resolve) => child.once('exit', (code, signal) => resolve({ code, signal })));
      child.kill('SIGTERM');
      return done;
    },
  };
  // Ready when the API answers; a generated token is read from the printed URL.
  await waitFor(async () => {
    if (exited) throw new Error(`armctl serve exited (${JSON.stringify(exited)}): ${output}`);
    const printed = output.match(new RegExp(`http://${host.replace(/\\./g, '\\\\.')}:${port}/\\S*`));
    const t = printed && new URL(printed[0]).searchParams.get('token');
    if (t) server.token = t;
    const r = await fetch(`${base}/api/v1/model`, { headers: server.token ? { Authorization: `Bearer ${server.token}` } : {} });
    return r.ok;
  }, `armctl serve on ${base}`);
  server.url = server.token ? `${base}/?token=${encodeURIComponent(server.token)}` : `${base}/`;
  return server;
}

// An HTTP client of the API with its own client id: "a move started elsewhere".
export function apiClient(server, id = `test-${randomBytes(6).toString('hex')}`) {
  const call = async (method, p, body) => {
    const headers = { 'X-Armctl-Client': id };
    if (server.token) headers.Authorization = `Bearer ${server.token}`;
    if (body !== undefined) headers['Content-Type'] = 'application/json';
    const r = await fetch(server.base + p, { method, headers, body: body === undefined ? undefined : JSON.stringify(body) });
    const text = await r.text();
    let json = null;
    try { json = JSON.parse(text); } catch { /* not JSON (the URDF) */ }
    return { status: r.status, json, text };
  };
  const ok = async (method, p, body) => {
    const r = await call(method, p, body);
    if (r.status >= 300) throw new Error(`${method} ${p} -> ${r.status} ${r.text}`);
    return r.json;
  };
  return {
    id, call,
    get: (p) => ok('GET', p),
    post: (p, body = {}) => ok('POST', p, body),
    state: () => ok('GET', '/api/v1/state'),
    position: async (name) => (await ok('GET', '/api/v1/state')).joints.find((j) => j.name === name).position,
  };
}

export async function launchBrowser() {
  const args = ['--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--ignore-gpu-blocklist'];
  if (process.getuid && process.getuid() === 0) args.push('--no-sandbox');
  return chromium.launch({ executablePath: chromiumPath, headless: true, args });
}

// One dashboard for a whole test file, through node:test's before/after: `armctl serve` for
// `arm` (with `extra` arguments), a browser, the page, and a second API client (another
// client, as a script would be), handed to `use` once they are up. At the end the file fails if the server crashed (a
// sanitizer report) or the page logged an error.
export function dashboardForFile(arm, use, { extra = [] } = {}) {
  const s = {};
  before(async () => {
    s.server = await startServer({ arm, extra });
    s.browser = await launchBrowser();
    ({ page: s.page, problems: s.problems } = await openDashboard(s.browser, s.server));
    s.script = apiClient(s.server);
    use(s);
  });
  after(async () => {
    await s.browser?.close();
    const exit = await s.server?.stop();
    assert.ok(!exit || exit.code === 0 || exit.signal === 'SIGTERM',
      `armctl serve ended with ${JSON.stringify(exit)}: ${s.server?.output}`);
    assert.deepEqual(s.problems ?? [], [], 'no console errors during the whole run');
  });
}

// A page on the dashboard that records every console error and page error.
export async function openDashboard(browser, server, { viewport = { width: 1400, height: 900 } } = {}) {
  const context = await browser.newContext({ viewport, acceptDownloads: true });
  const page = await context.newPage();
  const problems = [];
  page.on('console', (m) => { if (m.type() === 'error') problems.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('requestfailed', (r) => problems.push(`request failed: ${r.url()} ${r.failure()?.errorText}`));
  await page.goto(server.url);
  await page.waitForFunction(() => document.body.dataset.ready === 'true' && window.armctlView && window.armctlView.ready,
    null, { timeout: WAIT_MS });
  return { page, context, problems };
}

export async function screenshot(page, name) {
  fs.mkdirSync(artifacts, { recursive: true });
  const file = path.join(artifacts, `${name}.png`);
  await page.screenshot({ path: file });
  return file;
}

// Waits until the joint's live position is within `tolerance` of `target` (via the API).
// On a timeout the error carries the server's state (where the joints stand, the job, the
// motion, the last error), so that a failure says why the joint did not arrive.
export async function waitForPosition(client, name, target, tolerance = 1) {
  try {
    return await waitFor(async () => Math.abs((await client.position(name)) - target) <= tolerance,
      `${name} at ${target}`);
  } catch (e) {
    const s = await client.state().catch((err) => ({ unreadable: err.message }));
    e.message += `; the server's state: ${JSON.stringify(s)}`;
    throw e;
  }
}

// A refused request is logged by chromium as a console error ("Failed to load resource: the
// server responded with a status of 400"): a test that provokes one takes exactly that one
// off the list, so that every other console error still fails the run.
export function expectRefused(problems, status) {
  const i = problems.findIndex((p) => p.includes(`the server responded with a status of ${status}`));
  if (i < 0) throw new Error(`no refused request (${status}) in the console: ${JSON.stringify(problems)}`);
  problems.splice(i, 1);
}

// Waits until the arm is idle: no job, no motion, every joint at rest. The server refuses a
// move while another runs (409 busy), so a test that starts one waits for this first.
export async function waitIdle(client) {
  return waitFor(async () => {
    const s = await client.state();
    return s.job === '' && s.motion === null && s.joints.every((j) => Math.abs(j.velocity) < 1e-6) && s;
  }, 'the arm at rest with no job');
}

// A move sent by the page itself (as its sliders send one), so that control stays with it.
export function pageMove(page, positions, duration = 0.4) {
  return page.evaluate(async ({ p, d }) => {
    const { api } = await import('/assets/app/api.js');
    await api.post('/api/v1/joints', { positions: p, duration: d });
  }, { p: positions, d: duration });
}

// Clicks and waits for the server's answer to the request the click sends (it must be 2xx).
export async function clickAnswered(page, locator, pathEnd) {
  const answered = page.waitForResponse((r) => new URL(r.url()).pathname.endsWith(pathEnd) && r.request().method() !== 'GET');
  await locator.click();
  const response = await answered;
  assert.ok(response.ok(), `${pathEnd}: ${response.status()} ${await response.text()}`);
  return response;
}
