// What the dashboard's server refuses (docs/http-api.md "Security"), seen from a script and
// from the page: a request without the token (non-loopback listen), from another origin, a
// body that a form from another site could send, a move from a client without control.
// And the page itself works with the token it was opened with.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import http from 'node:http';
import { startServer, launchBrowser, openDashboard, apiClient, waitFor, screenshot } from './harness.mjs';

let local; // 127.0.0.1, no token
let remote; // 127.0.0.2 with --token: a second origin, and a server that asks for a token
let browser;

before(async () => {
  local = await startServer({ arm: 'xarm' });
  remote = await startServer({ arm: 'xarm', host: '127.0.0.2', token: 'browser-test-token-5f2c' });
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  for (const server of [local, remote]) {
    const exit = await server?.stop();
    assert.ok(!exit || exit.code === 0 || exit.signal === 'SIGTERM', `armctl serve ended with ${JSON.stringify(exit)}: ${server?.output}`);
  }
});

// A raw request (node's fetch would not let a test set Host).
function raw(server, { method = 'GET', path = '/api/v1/state', headers = {}, body } = {}) {
  return new Promise((resolve, reject) => {
    const request = http.request({ host: server.host, port: server.port, method, path, headers }, (response) => {
      let text = '';
      response.on('data', (d) => { text += d; });
      response.on('end', () => {
        let json = null;
        try { json = JSON.parse(text); } catch { /* not JSON */ }
        resolve({ status: response.statusCode, json, text });
      });
    });
    request.on('error', reject);
    if (body !== undefined) request.write(body);
    request.end();
  });
}

test('without the token (or with a wrong one) every request is refused: 401', async () => {
  for (const path of ['/api/v1/state', '/', '/assets/app/main.js', '/api/v1/events']) {
    const r = await raw(remote, { path });
    assert.equal(r.status, 401, `${path} without a token`);
  }
  const wrong = await raw(remote, { headers: { Authorization: 'Bearer not-the-token' } });
  assert.equal(wrong.status, 401);
  assert.ok(wrong.json && wrong.json.error, 'a JSON error says why');
  const moved = await raw(remote, { method: 'POST', path: '/api/v1/stop', headers: { 'Content-Type': 'application/json' }, body: '{}' });
  assert.equal(moved.status, 401);
  assert.equal((await raw(remote, { headers: { Authorization: `Bearer ${remote.token}` } })).status, 200);
  assert.equal((await raw(remote, { path: `/api/v1/state?token=${remote.token}` })).status, 200);
});

test('the page opened with ?token= loads every asset with it and works, no console errors', async () => {
  const { page, problems, context } = await openDashboard(browser, remote);
  await waitFor(async () => (await page.getByRole('status', { name: 'Link state' }).textContent()) === 'ok', 'the live state with the token');
  await waitFor(async () => (await page.getByRole('status', { name: 'Control' }).textContent()).includes('You have control'), 'control');
  await screenshot(page, 'token-page');
  await context.close();
  assert.deepEqual(problems, []);
});

test('a request from another origin is refused: 403, nothing moves', async () => {
  const script = apiClient(local);
  await script.post('/api/v1/control', { take: true });
  const was = await script.position('servo6');
  const r = await raw(local, {
    method: 'POST', path: '/api/v1/joints', body: JSON.stringify({ positions: { servo6: 40 } }),
    headers: { 'Content-Type': 'application/json', Origin: 'http://attacker.example', 'X-Armctl-Client': script.id },
  });
  assert.equal(r.status, 403);
  assert.ok(r.json && r.json.error);
  const s = await script.state();
  assert.equal(s.motion, null);
  assert.ok(Math.abs(s.joints.find((j) => j.name === 'servo6').position - was) < 0.5);
});

test('a page of another origin cannot move the arm (a cross-site "simple" POST)', async () => {
  // The attack a browser allows without a preflight: a text/plain POST from another site's
  // page (here the second server's page, another host:port). The server sees its Origin.
  const script = apiClient(local);
  await script.post('/api/v1/control', { take: true });
  const was = await script.position('servo6');
  const context = await browser.newContext();
  const page = await context.newPage();
  await page.goto(remote.url);
  await page.evaluate(async ({ target, value }) => {
    // Resolves when the (opaque) answer has arrived: the server has decided by then.
    await fetch(`${target}/api/v1/joints`, { method: 'POST', mode: 'no-cors', headers: { 'Content-Type': 'text/plain' },
      body: JSON.stringify({ positions: { servo6: value } }) }).catch(() => {});
  }, { target: local.base, value: was + 30 });
  await context.close();
  const s = await script.state();
  assert.equal(s.motion, null, 'no motion started');
  assert.ok(Math.abs(s.joints.find((j) => j.name === 'servo6').position - was) < 0.5, 'servo6 did not move');
});

test('a page of another origin cannot frame the dashboard (clickjacking)', async () => {
  // The other server's page adds an iframe of this dashboard: the browser refuses to show it
  // (X-Frame-Options DENY, CSP frame-ancestors 'none'), so none of its buttons can be clicked.
  const context = await browser.newContext();
  const page = await context.newPage();
  await page.goto(remote.url);
  const framed = await page.evaluate(async (target) => {
    const frame = document.createElement('iframe');
    frame.src = `${target}/`;
    const loaded = new Promise((resolve) => { frame.onload = resolve; });
    document.body.append(frame);
    await Promise.race([loaded, new Promise((resolve) => setTimeout(resolve, 5000))]);
    return true;
  }, local.base.replace(/\/api\/v1$/, ''));
  assert.ok(framed);
  const child = page.frames().find((f) => f !== page.mainFrame());
  assert.ok(child, 'the iframe exists');
  // A refused frame holds the browser's error page, not the dashboard's STOP button.
  const stopButtons = await child.locator('#stop').count().catch(() => 0);
  assert.equal(stopButtons, 0, 'the dashboard rendered inside another site\'s frame');
  await context.close();
});

test('a DNS-rebinding Host is refused: 403', async () => {
  const r = await raw(local, { headers: { Host: `attacker.example:${local.port}` } });
  assert.equal(r.status, 403);
  assert.equal((await raw(local, { headers: { Host: `localhost:${local.port}` } })).status, 200);
});

test('a body without Content-Type: application/json is refused: 415', async () => {
  const script = apiClient(local);
  await script.post('/api/v1/control', { take: true });
  const r = await raw(local, { method: 'POST', path: '/api/v1/joints', body: JSON.stringify({ positions: { servo6: 10 } }),
    headers: { 'Content-Type': 'text/plain', 'X-Armctl-Client': script.id } });
  assert.equal(r.status, 415);
});

test('a client without control is refused (409) but STOP is accepted from anyone', async () => {
  const holder = apiClient(local);
  const other = apiClient(local);
  await holder.post('/api/v1/control', { take: true });
  const refused = await other.call('POST', '/api/v1/joints', { positions: { servo6: 10 } });
  assert.equal(refused.status, 409);
  assert.match(refused.json.error, /control/);
  const stop = await other.call('POST', '/api/v1/stop', {});
  assert.ok(stop.status < 300, `stop from a client without control: ${stop.status} ${stop.text}`);
});
