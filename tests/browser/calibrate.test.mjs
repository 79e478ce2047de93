// The Calibrate tab (docs/calibration.md "Dashboard") on the embedded xArm with an arm file of
// the test's own: the wiggle highlights the joint in the 3D view, the user answers which
// joint moved and which way it went, puts it at its mark; the pending changes are listed;
// Cancel writes nothing; Confirm writes the arm file with the previous one kept beside it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { waitFor, screenshot, dashboardForFile, clickAnswered } from './harness.mjs';

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armctl-calibrate-'));
for (const f of ['xarm.arm.json', 'xarm.urdf']) fs.copyFileSync(path.resolve('config', f), path.join(dir, f));
const armFile = path.join(dir, 'xarm.arm.json');
const original = fs.readFileSync(armFile, 'utf8');

let page;
dashboardForFile(armFile, (s) => ({ page } = s));

const state = (title) => page.getByRole('status', { name: `${title} state` });
const highlighted = () => page.evaluate(() => window.armctlView.highlighted());
const pendingText = () => page.getByLabel('Pending changes').textContent();

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
  await waitFor(async () => (await state('Zero').textContent()).startsWith('servo3: zero moves by'), 'the zero answered');
  await waitFor(async () => /zero moved by/.test(await pendingText()), 'the zero pending');

  await page.getByRole('button', { name: 'Skip Limits' }).click();
  assert.equal(await state('Limits').textContent(), 'skipped');
  await screenshot(page, 'calibrate-pending');

  await clickAnswered(page, page.getByRole('button', { name: 'Cancel calibration' }), '/calibration/cancel');
  await waitFor(async () => (await page.getByRole('status', { name: 'Calibration result' }).textContent()).includes('nothing written'), 'cancelled');
  assert.equal(fs.readFileSync(armFile, 'utf8'), original, 'cancel writes nothing');
  assert.ok(!fs.existsSync(`${armFile}.prev`), 'and keeps no previous file');
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
});
