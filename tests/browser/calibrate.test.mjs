// The Calibrate tab (docs/calibration.md "Dashboard") on the embedded xArm with an arm file of
// the test's own: the wiggle highlights the joint in the 3D view, the user answers which
// joint moved and which way it went, puts it at its mark; limits from two ends the joint was
// moved to, a gripper whose open and closed cannot be told apart refused, a mark touched and
// verified; the pending changes are listed; Cancel writes nothing; Confirm writes the arm file
// with the previous one kept beside it, and after the page reloads (keeping control) the
// server calibrates again from the new file.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { waitFor, screenshot, dashboardForFile, clickAnswered, pageMove, waitForPosition, waitIdle, expectRefused } from './harness.mjs';

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armctl-calibrate-'));
for (const f of ['xarm.arm.json', 'xarm.urdf']) fs.copyFileSync(path.resolve('config', f), path.join(dir, f));
const armFile = path.join(dir, 'xarm.arm.json');
const original = fs.readFileSync(armFile, 'utf8');

let page;
let script;
let problems;
dashboardForFile(armFile, (s) => ({ page, script, problems } = s));

const state = (title) => page.getByRole('status', { name: `${title} state` });
const highlighted = () => page.evaluate(() => window.armctlView.highlighted());
const pendingText = () => page.getByLabel('Pending changes').textContent();
// A button of one step's row (the page has other buttons of the same name: the gripper's Open).
const stepButton = (step, name) => page.getByRole('listitem', { name: step }).getByRole('button', { name, exact: true });

async function startCalibration() {
  await page.getByRole('tab', { name: 'Calibrate' }).click();
  await clickAnswered(page, page.getByRole('button', { name: 'Start calibration' }), '/calibration/start');
  await waitFor(async () => (await page.getByRole('status', { name: 'Calibration file' }).textContent()).includes(armFile), 'the arm file named');
  await page.getByLabel('Calibration joint').selectOption('servo3');
}

async function direction(asShown) {
  await page.getByRole('button', { name: 'Run Direction' }).or(page.getByRole('button', { name: 'Redo Direction' })).first().click();
  const answer = page.getByRole('button', { name: asShown ? 'Yes, as shown' : 'No, the other way' });
  await answer.waitFor();
  assert.equal(await highlighted(), 'servo3', 'the nudged joint is highlighted');
  await clickAnswered(page, answer, '/calibration/direction');
  await waitFor(async () => (await state('Direction').textContent()).startsWith('servo3:'), 'the direction answered');
}

test('which joint, direction and zero on servo3: highlighted, answered, listed; cancel writes nothing', async () => {
  await startCalibration();
  await page.getByText('Pictures of the joints').click();  // folded by default: the 3D view is the guide
  const pictures = page.getByRole('img', { name: 'Each joint at its mark (grey) and moved positive (blue)' });
  await waitFor(() => pictures.evaluate((img) => img.complete && img.naturalWidth > 0), 'the joint pictures shown');

  await page.getByRole('button', { name: 'Run Which joint' }).click();
  const moved = page.getByLabel('Joint that moved');
  await moved.waitFor();
  assert.equal(await highlighted(), 'servo3', 'the wiggled joint is highlighted in the 3D view');
  await screenshot(page, 'calibrate-which');
  await moved.selectOption('servo3');
  await clickAnswered(page, page.getByRole('button', { name: 'Answer' }), '/calibration/which');
  await waitFor(async () => (await state('Which joint').textContent()) === 'servo3: right', 'the which answer');
  assert.equal(await highlighted(), null, 'the highlight goes with the answer');

  await direction(false);
  await waitFor(async () => /servo3: direction flipped/.test(await pendingText()), 'the flip pending');

  await page.getByRole('button', { name: 'Run Zero' }).click();
  await clickAnswered(page, page.getByRole('button', { name: 'At the mark' }), '/calibration/zero');
  // The xArm's zero goes to the servo's own offset (it fits -125..125 units).
  await waitFor(async () => (await state('Zero').textContent()).startsWith('servo3: servo offset'), 'the zero answered');
  await waitFor(async () => /servo3: servo 3 offset -?\d+ units/.test(await pendingText()), 'the zero pending');

  await page.getByRole('button', { name: 'Skip Limits' }).click();
  assert.equal(await state('Limits').textContent(), 'skipped');
  await screenshot(page, 'calibrate-pending');

  await clickAnswered(page, page.getByRole('button', { name: 'Cancel calibration' }), '/calibration/cancel');
  await waitFor(async () => (await page.getByRole('status', { name: 'Calibration result' }).textContent()).includes('nothing written'), 'cancelled');
  assert.equal(fs.readFileSync(armFile, 'utf8'), original, 'cancel writes nothing');
  assert.ok(!fs.existsSync(`${armFile}.prev`), 'and keeps no previous file');
});

test('limits from the two ends, a gripper too close to tell refused, a mark touched and verified', async () => {
  await startCalibration();
  // The joint "moved by hand" to each end: the page's own moves put it there (a move puts the
  // torque back on; the step reads where the joint stands).
  await page.getByRole('button', { name: 'Run Limits' }).click();
  await stepButton('Limits', 'At one end').waitFor();
  await pageMove(page, { servo3: -60 });
  await waitForPosition(script, 'servo3', -60);
  await waitIdle(script);
  await clickAnswered(page, stepButton('Limits', 'At one end'), '/calibration/read');
  await stepButton('Limits', 'At the other end').waitFor();
  await pageMove(page, { servo3: 60 }, 0.8);
  await waitForPosition(script, 'servo3', 60);
  await waitIdle(script);
  await clickAnswered(page, stepButton('Limits', 'At the other end'), '/calibration/limits');
  const limits = await waitFor(async () => {
    const t = await state('Limits').textContent();
    return t.startsWith('servo3:') && t;
  }, 'the limits answered');
  const [lower, upper] = [...limits.matchAll(/-?\d+(\.\d+)?/g)].slice(1).map((m) => Number(m[0]));
  assert.ok(lower > -60 && lower < -55 && upper < 60 && upper > 55, `the ends pulled in by the margin: ${limits}`);
  await waitFor(async () => /servo3: limits/.test(await pendingText()), 'the limits pending');

  // Open and closed read where the gripper stands both times: refused, saying why.
  await page.getByRole('button', { name: 'Run Gripper' }).click();
  await stepButton('Gripper', 'Open').click();
  await stepButton('Gripper', 'Closed').click();
  const refused = await waitFor(async () => {
    const t = await state('Gripper').textContent();
    return t.startsWith('failed:') && t;
  }, 'the gripper refused');
  assert.match(refused, /too close to tell apart/);
  expectRefused(problems, 400);

  // One mark touched where the tool stands (not on it): verify names it with its distance.
  await page.getByRole('button', { name: 'Run Touch and verify' }).click();
  await clickAnswered(page, stepButton('Touch and verify', 'On the mark'), '/calibration/touch');
  await clickAnswered(page, stepButton('Touch and verify', 'Done'), '/calibration/verify');
  const verified = await waitFor(async () => {
    const t = await state('Touch and verify').textContent();
    return t.startsWith('rms') && t;
  }, 'verified');
  assert.match(verified, /^rms \d+(\.\d+)? mm, worst \S+/);
  await screenshot(page, 'calibrate-limits-verify');

  await clickAnswered(page, page.getByRole('button', { name: 'Cancel calibration' }), '/calibration/cancel');
  assert.equal(fs.readFileSync(armFile, 'utf8'), original, 'cancel writes nothing');
  await pageMove(page, { servo3: 0 });
  await waitForPosition(script, 'servo3', 0);
  await waitIdle(script);
});

test('confirm writes the arm file, the previous one kept beside it', async () => {
  await startCalibration();
  await direction(false);
  await clickAnswered(page, page.getByRole('button', { name: 'Confirm and write' }), '/calibration/confirm');
  const result = await waitFor(async () => {
    const t = await page.getByRole('status', { name: 'Calibration result' }).textContent();
    return t.startsWith('Written to') && t;
  }, 'written');
  assert.ok(result.includes(armFile), result);
  const written = fs.readFileSync(armFile, 'utf8');
  assert.notEqual(written, original, 'the arm file changed');
  const previous = fs.readdirSync(dir).filter((f) => f !== 'xarm.arm.json' && f !== 'xarm.urdf');
  assert.equal(previous.length, 1, `one previous file beside it: ${previous}`);
  assert.equal(fs.readFileSync(path.join(dir, previous[0]), 'utf8'), original, 'the previous file is the old one');

  // The server drives with the new file at once: the page reloads, keeping control, and a
  // new calibration starts from the new file (no restart of armctl serve).
  const before = problems.length;
  await page.getByRole('button', { name: 'Reload the page' }).click();
  await page.waitForFunction(() => document.body.dataset.ready === 'true' && window.armctlView && window.armctlView.ready);
  // The reload cut the old page's requests under way (its event stream, a state poll): those
  // are the failures a reload makes; anything else stays on the list and fails the run.
  const cut = problems.splice(before).filter((p) => !/^request failed: .*\/api\/v1\/.* net::ERR_ABORTED$/.test(p));
  problems.push(...cut);
  await startCalibration();
  assert.equal(await pendingText().then((t) => /servo3/.test(t)), false, 'nothing pending in the new session');
  await clickAnswered(page, page.getByRole('button', { name: 'Cancel calibration' }), '/calibration/cancel');
});
