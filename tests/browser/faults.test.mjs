// A joint fault on the dashboard: the embedded SCARA with UAE's motor leads swapped
// (`--device 'sim?swapped=3'`). Driven, UAE runs away and stops itself with a runaway
// fault; the status bar names it and offers "Clear faults", which clears it (the joint
// holds where it is) and goes away again.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { dashboardForFile, waitFor, waitIdle, pageMove, clickAnswered, screenshot } from './harness.mjs';

let page;
let problems;
let script;

dashboardForFile('scara', (s) => ({ page, problems, script } = s), { extra: ['--device', 'sim?swapped=3'] });

test('a runaway joint is named in the status bar, and Clear faults clears it', async () => {
  const faults = page.getByRole('status', { name: 'Faults' });
  const clear = page.getByRole('button', { name: 'Clear faults' });
  await waitFor(async () => (await page.getByRole('status', { name: 'Control' }).textContent()).includes('You have control'), 'control');
  assert.equal(await faults.textContent(), 'none');
  assert.equal(await clear.isVisible(), false, 'nothing to clear: no button');
  const model = await script.get('/api/v1/model');
  const uae = model.joints.find((j) => j.name === 'UAE');  // joint 3 on the bus
  assert.ok(uae, 'the SCARA has UAE');
  await waitIdle(script);
  // The move fails (the joint runs the wrong way); the page shows that as an error.
  await pageMove(page, { [uae.name]: uae.max * 0.5 }, 1.0).catch(() => {});
  await waitFor(async () => (await faults.textContent()).includes('runaway'), 'the runaway fault in the status bar');
  assert.match(await faults.textContent(), /joint 3: runaway/);
  await clear.waitFor({ state: 'visible' });
  await screenshot(page, 'faults');
  await clickAnswered(page, clear, '/api/v1/clear-faults');
  await waitFor(async () => (await faults.textContent()) === 'none', 'no fault after Clear faults');
  assert.equal(await clear.isVisible(), false);
  const state = await script.state();
  assert.deepEqual(state.faults, []);
  // The failed move is an error banner, not a console error (the harness checks at the end).
  assert.deepEqual(problems, []);
});
