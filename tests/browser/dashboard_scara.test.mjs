// The same page on the embedded simulated SCARA arm (joint bus, seven joints, a prismatic
// Z in mm): built from its model, its sliders move it, its 3D view follows, and the action
// group editor says why it is not offered (no Robot Commands board).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  waitFor, waitForPosition, waitIdle, screenshot, expectRefused,
  dashboardForFile,
} from './harness.mjs';

let page;
let problems;
let script;

const viewValue = (name) => page.evaluate((n) => window.armctlView.jointValues()[n], name);

dashboardForFile('scara', (s) => ({ page, problems, script } = s));

test('the SCARA page loads with no console errors, a slider per joint in its units', async () => {
  const model = await script.get('/api/v1/model');
  assert.equal(model.protocol, 'joint_bus');
  for (const joint of model.joints) {
    const slider = page.getByRole('slider', { name: `${joint.name} (${joint.unit})`, exact: true });
    await slider.waitFor();
    assert.equal(Number(await slider.getAttribute('min')), joint.min);
    assert.equal(Number(await slider.getAttribute('max')), joint.max);
  }
  assert.ok(model.joints.some((j) => j.unit === 'mm'), 'the SCARA has a joint in mm');
  await waitFor(async () => (await page.getByRole('status', { name: 'Control' }).textContent()).includes('You have control'), 'control');
  assert.deepEqual(problems, []);
});

test('the Z slider (mm) and the shoulder slider (deg) move the arm; the 3D view follows', async () => {
  const model = await script.get('/api/v1/model');
  const z = model.joints.find((j) => j.kind === 'prismatic');
  const shoulder = model.joints.find((j) => j.kind === 'revolute');
  const zTarget = Math.round((z.min + (z.max - z.min) * 0.3) * 10) / 10;
  const shoulderTarget = Math.round(shoulder.max * 0.25);
  // The server refuses a move while another runs: each starts from rest.
  await waitIdle(script);
  await page.getByRole('slider', { name: `${z.name} (mm)`, exact: true }).fill(String(zTarget));
  await waitForPosition(script, z.name, zTarget, 0.6);
  await waitIdle(script);
  await page.getByRole('slider', { name: `${shoulder.name} (deg)`, exact: true }).fill(String(shoulderTarget));
  await waitForPosition(script, shoulder.name, shoulderTarget, 0.6);
  await waitFor(async () => Math.abs((await viewValue(z.name)) - zTarget) < 0.6
    && Math.abs((await viewValue(shoulder.name)) - shoulderTarget) < 0.6, 'the 3D view at the new Z and shoulder');
  await screenshot(page, 'scara-move');
});

test('a value outside a joint\'s limits is refused with the server\'s message, nothing moves', async () => {
  const model = await script.get('/api/v1/model');
  const joint = model.joints[1];
  await waitIdle(script);
  const was = await script.position(joint.name);
  const answered = page.waitForResponse((r) => r.url().endsWith('/api/v1/joints'));
  const target = page.getByRole('spinbutton', { name: `${joint.name} target (${joint.unit})` });
  await target.fill(String(joint.max + 50));
  await target.press('Enter');
  const response = await answered;
  assert.equal(response.status(), 400);
  const { error } = await response.json();
  await waitFor(async () => (await page.getByRole('alert').first().textContent()).includes(error), 'the message shown');
  expectRefused(problems, 400);
  const s = await script.state();
  assert.equal(s.motion, null);
  assert.ok(Math.abs(s.joints.find((j) => j.name === joint.name).position - was) < 0.5, 'nothing moved');
});

test('the action-group view says groups need a Robot Commands board', async () => {
  await page.getByRole('tab', { name: 'Action groups' }).click();
  await page.getByText('Action groups need a Robot Commands board').waitFor();
  await screenshot(page, 'scara-groups');
  await page.getByRole('tab', { name: 'Program' }).click();
  await screenshot(page, 'scara-program');
});
