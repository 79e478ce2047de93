// The same page on the embedded simulated SCARA arm (joint bus, seven joints, a prismatic
// Z in mm): built from its model, its sliders move it, its 3D view follows, the tool is
// jogged and moved in millimetres, a program runs with its progress, STOP halts a move, and
// the action group editor says why it is not offered (no Robot Commands board).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  waitFor, waitForPosition, waitIdle, screenshot, expectRefused,
  dashboardForFile, pageMove, clickAnswered,
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

// The SCARA's own pose to start from: every chain joint at 40 % of its range (the tool well
// inside the workspace, away from the stretched-out arm), in the API's units.
async function insidePose() {
  const model = await script.get('/api/v1/model');
  const pose = {};
  for (const j of model.joints.filter((j) => !j.gripper)) pose[j.name] = Math.round((j.min + 0.4 * (j.max - j.min)) * 10) / 10;
  return pose;
}

async function toInsidePose() {
  await page.getByRole('tab', { name: 'Move' }).click();
  await waitIdle(script);
  const pose = await insidePose();
  await pageMove(page, pose, 1.5);
  for (const [name, value] of Object.entries(pose)) await waitForPosition(script, name, value, 0.6);
  return waitIdle(script);
}

test('jog and the move-to form move the SCARA tool in millimetres', async () => {
  const start = (await toInsidePose()).tool;
  await page.getByRole('spinbutton', { name: 'Jog step (mm)' }).fill('10');
  await clickAnswered(page, page.getByRole('button', { name: 'jog z minus' }), '/api/v1/jog');
  await waitFor(async () => {
    const s = await script.state();
    return s.motion === null && s.job === '' && Math.abs(s.tool.z - (start.z - 10)) < 1 &&
      Math.abs(s.tool.x - start.x) < 1 && Math.abs(s.tool.y - start.y) < 1;
  }, `the tool 10 mm lower, at z = ${start.z - 10} mm`);
  await waitFor(async () => Math.abs(Number(await page.getByRole('status', { name: 'tool z (mm)' }).textContent()) - (start.z - 10)) < 1,
    'the page showing the new z');

  const before = (await waitIdle(script)).tool;
  await page.getByRole('button', { name: 'Use current pose' }).click();
  const x = page.getByRole('spinbutton', { name: 'tool x target (mm)' });
  assert.ok(Math.abs(Number(await x.inputValue()) - before.x) < 0.5, `x target ${await x.inputValue()}, the tool at ${before.x}`);
  await x.fill(String(Math.round(before.x - 20)));
  await clickAnswered(page, page.getByRole('button', { name: 'Move tool' }), '/api/v1/tool');
  await waitFor(async () => {
    const s = await script.state();
    return s.motion === null && s.job === '' && Math.abs(s.tool.x - Math.round(before.x - 20)) < 1 &&
      Math.abs(s.tool.y - before.y) < 1 && Math.abs(s.tool.z - before.z) < 1;
  }, `the tool at x = ${Math.round(before.x - 20)} mm`);
  await screenshot(page, 'scara-jog');
});

test('a program runs on the SCARA: its line, the time left, its output, the end', async () => {
  const pose = await insidePose();
  const model = await script.get('/api/v1/model');
  const unit = (name) => model.joints.find((j) => j.name === name).unit;
  const joints = (shift) => Object.entries(pose).map(([n, v], k) => `${k === 0 ? v + shift : v}${unit(n)}`).join(', ');
  const source = [
    `ptp joints(${joints(0)}) speed=30%`,
    `ptp joints(${joints(20)}) speed=30%`,
    'print "halfway"',
    `ptp joints(${joints(-20)}) speed=30%`,
  ].join('\n');
  await page.getByRole('tab', { name: 'Program' }).click();
  await page.getByRole('textbox', { name: 'Program source' }).fill(source);
  await waitIdle(script);
  await page.getByRole('button', { name: 'Run', exact: true }).click();
  const progress = page.getByRole('status', { name: 'Program progress' });
  await waitFor(async () => /^running: line \d+.*; [\d.]+ s left/.test(await progress.textContent()), 'the run to show its line and time left');
  await screenshot(page, 'scara-program-run');
  await waitFor(async () => (await page.getByLabel('Program output').textContent()).includes('halfway'), 'the print');
  await waitFor(async () => (await progress.textContent()) === 'idle', 'the end of the run', 60000);
  const first = Object.keys(pose)[0];
  await waitForPosition(script, first, pose[first] - 20, 0.6);
  assert.deepEqual(problems, []);
});

test('STOP halts a SCARA move, short of its target, and it stays there', async () => {
  await toInsidePose();
  const model = await script.get('/api/v1/model');
  const shoulder = model.joints.find((j) => j.kind === 'revolute');
  const start = await script.position(shoulder.name);
  const target = Math.round(shoulder.max - 1 > start + 30 ? start + 30 : start - 30);
  await page.getByRole('slider', { name: 'Joint speed' }).fill('0.05');
  await page.getByRole('slider', { name: `${shoulder.name} (deg)`, exact: true }).fill(String(target));
  await waitFor(async () => Math.abs((await script.position(shoulder.name)) - start) > 1, 'the move to start');
  await page.getByRole('button', { name: 'STOP (Esc)' }).click();
  const stopped = await waitIdle(script);
  const at = stopped.joints.find((j) => j.name === shoulder.name).position;
  assert.ok(Math.abs(at - target) > 5, `${shoulder.name} stopped at ${at}, short of ${target}`);
  const events = await page.evaluate(() => window.armctlLive.events);
  await page.waitForFunction((n) => window.armctlLive.events >= n + 3, events);
  assert.ok(Math.abs((await script.position(shoulder.name)) - at) < 0.2, 'the arm stays where it stopped');
  await page.getByRole('slider', { name: 'Joint speed' }).fill('0.25');
});

test('the action-group view says groups need a Robot Commands board', async () => {
  await page.getByRole('tab', { name: 'Action groups' }).click();
  await page.getByText('Action groups need a Robot Commands board').waitFor();
  await screenshot(page, 'scara-groups');
  await page.getByRole('tab', { name: 'Program' }).click();
  await screenshot(page, 'scara-program');
});
