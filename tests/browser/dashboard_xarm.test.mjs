// The dashboard on the embedded emulated xArm, in headless chromium: every scenario of the
// issue that needs an xArm (action groups) or applies to both arms.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import {
  waitFor, waitForPosition, waitIdle, screenshot, artifacts, expectRefused,
  dashboardForFile, pageMove as pageMoveOn, clickAnswered as clickAnsweredOn,
} from './harness.mjs';

let server;
let page;
let problems;
let script; // another client, as a script or a second page would be

const slider = (name) => page.getByRole('slider', { name: `${name} (deg)`, exact: true });
const sliderValue = async (name) => Number(await slider(name).inputValue());
const viewValue = (name) => page.evaluate((n) => window.armctlView.jointValues()[n], name);
const tab = (name) => page.getByRole('tab', { name });
const pageMove = (positions, duration = 0.4) => pageMoveOn(page, positions, duration);
const clickAnswered = (locator, pathEnd) => clickAnsweredOn(page, locator, pathEnd);

dashboardForFile('xarm', (s) => ({ server, page, problems, script } = s));

test('the page loads with no console errors and shows the model, the state and control', async () => {
  const model = await script.get('/api/v1/model');
  for (const joint of model.joints) await slider(joint.name).waitFor();
  await waitFor(async () => (await page.getByRole('status', { name: 'Control' }).textContent()).includes('You have control'), 'the page to take control');
  await waitFor(async () => (await page.getByRole('status', { name: 'Link state' }).textContent()) === 'ok', 'link ok');
  const battery = await page.getByRole('status', { name: 'Battery' }).textContent();
  assert.match(battery, /^\d+(\.\d+)? V$|^n\/a$/);
  assert.ok(await page.getByRole('button', { name: 'STOP (Esc)' }).isVisible());
  assert.deepEqual(Object.keys(await page.evaluate(() => window.armctlView.jointValues())).sort(),
    model.joints.map((j) => j.name).sort(), 'the 3D view has every joint of the model');
  await screenshot(page, 'xarm-load');
  assert.deepEqual(problems, []);
});

test('moving a slider moves the simulated arm, and the 3D view follows', async () => {
  await waitIdle(script);
  await slider('servo6').fill('30');
  await waitForPosition(script, 'servo6', 30, 0.6);
  await waitFor(async () => Math.abs((await viewValue('servo6')) - 30) < 0.6, 'the 3D view at servo6 = 30 deg');
});

test('live positions and the 3D view follow a move started elsewhere (>= 20 updates/s while moving)', async () => {
  await script.post('/api/v1/control', { take: true });
  await waitFor(async () => (await page.getByRole('status', { name: 'Control' }).textContent()).includes('another client has control'), 'watch mode');
  await waitIdle(script);
  const eventsBefore = await page.evaluate(() => window.armctlLive.events);
  const started = Date.now();
  await script.post('/api/v1/joints', { positions: { servo5: -25, servo4: 20 }, duration: 1.5 });
  await waitForPosition(script, 'servo5', -25, 0.6);
  const elapsed = (Date.now() - started) / 1000;
  const rate = ((await page.evaluate(() => window.armctlLive.events)) - eventsBefore) / elapsed;
  console.log(`BROWSER live events while moving: ${rate.toFixed(1)}/s`);
  assert.ok(rate >= 20, `the page got ${rate.toFixed(1)} state events per second while moving; at least 20 wanted`);
  await waitFor(async () => Math.abs((await sliderValue('servo5')) + 25) < 0.6, 'the servo5 slider at -25');
  await waitFor(async () => Math.abs((await viewValue('servo5')) + 25) < 0.6 && Math.abs((await viewValue('servo4')) - 20) < 0.6,
    'the 3D view at servo5 = -25, servo4 = 20');
  // Watching: a move from the page is refused with the server's message, and nothing moves.
  await screenshot(page, 'xarm-watch-mode');
  await page.getByRole('button', { name: 'Take control' }).click();
  await waitFor(async () => (await page.getByRole('status', { name: 'Control' }).textContent()).includes('You have control'), 'control back');
  const refused = await script.call('POST', '/api/v1/joints', { positions: { servo6: 0 } });
  assert.equal(refused.status, 409);
  assert.match(refused.json.error, /control/);
  await screenshot(page, 'xarm-move'); // the README's picture: the arm posed, in control
});

test('a refused request shows the server\'s message, and nothing is recorded', async () => {
  const answered = page.waitForResponse((r) => r.url().endsWith('/api/v1/points') && r.request().method() === 'POST');
  await page.getByRole('textbox', { name: 'Point name' }).fill('2bad name');
  await page.getByRole('button', { name: 'Record point' }).click();
  const response = await answered;
  assert.equal(response.status(), 400);
  const { error } = await response.json();
  assert.ok(error.length > 10, `the server says why: "${error}"`);
  const shown = page.getByRole('alert').first();
  await waitFor(async () => (await shown.textContent()).includes(error), `the page to show "${error}"`);
  expectRefused(problems, 400);
  assert.ok(!(await script.get('/api/v1/points')).points.some((p) => p.name === '2bad name'));
  await page.getByRole('button', { name: 'Dismiss error' }).first().click();
});

test('a joint target refused as busy is sent again by Enter, with one banner for its error', async () => {
  // A slow move from the page keeps the arm busy; a target typed meanwhile is refused (409).
  await pageMove({ servo2: 60 }, 3);
  const target = page.getByRole('spinbutton', { name: 'servo3 target (deg)' });
  await target.fill('20');
  const refused = page.waitForResponse((r) => r.url().endsWith('/api/v1/joints') && r.request().method() === 'POST');
  await target.press('Enter');
  assert.equal((await refused).status(), 409);
  const banners = page.getByRole('alert');
  await waitFor(async () => (await banners.count()) >= 1, 'the busy refusal to be shown');
  // Enter again on the same value sends it again; the same refusal keeps one banner.
  const again = page.waitForResponse((r) => r.url().endsWith('/api/v1/joints') && r.request().method() === 'POST');
  await target.press('Enter');
  assert.equal((await again).status(), 409);
  const texts = await banners.allTextContents();
  assert.equal(new Set(texts).size, texts.length, `one banner per error: ${JSON.stringify(texts)}`);
  expectRefused(problems, 409);
  expectRefused(problems, 409);
  await waitIdle(script);
  // Once the arm is free, Enter sends it and it is taken.
  const taken = page.waitForResponse((r) => r.url().endsWith('/api/v1/joints') && r.request().method() === 'POST');
  await target.press('Enter');
  assert.equal((await taken).status(), 200);
  await waitForPosition(script, 'servo3', 20);
  while (await banners.count()) await page.getByRole('button', { name: 'Dismiss error' }).first().click();
});

test('jog, gripper, torque and points from the Move view', async () => {
  // From a pose well inside the workspace (the example programs' home: tool forward, level),
  // jog the tool up 10 mm in a straight line: the pose read back has z 10 mm higher.
  await waitIdle(script);
  const home = { servo6: 0, servo5: 20, servo4: 40, servo3: 40, servo2: 0 };
  await pageMove(home);
  for (const [name, value] of Object.entries(home)) await waitForPosition(script, name, value, 0.6);
  await waitIdle(script);
  const z0 = (await script.state()).tool.z;
  await page.getByRole('spinbutton', { name: 'Jog step (mm)' }).fill('10');
  await clickAnswered(page.getByRole('button', { name: 'jog z plus' }), '/api/v1/jog');
  await waitFor(async () => {
    const s = await script.state();
    return s.motion === null && s.job === '' && Math.abs(s.tool.z - (z0 + 10)) < 1;
  }, `the tool at z = ${z0 + 10} mm`);
  await waitFor(async () => Math.abs(Number(await page.getByRole('status', { name: 'tool z (mm)' }).textContent()) - (z0 + 10)) < 1,
    'the page showing the new z');

  // Close the gripper: its joint leaves where it was.
  const model = await script.get('/api/v1/model');
  const gripper = model.joints.find((j) => j.gripper);
  if (gripper) {
    await clickAnswered(page.getByRole('button', { name: 'Open gripper' }), '/api/v1/gripper');
    await waitIdle(script);
    const g0 = await script.position(gripper.name);
    await clickAnswered(page.getByRole('button', { name: 'Close gripper' }), '/api/v1/gripper');
    await waitFor(async () => Math.abs((await script.position(gripper.name)) - g0) > 5, `${gripper.name} to close`);
    await waitIdle(script);
    await clickAnswered(page.getByRole('button', { name: 'Open gripper' }), '/api/v1/gripper');
    await waitFor(async () => Math.abs((await script.position(gripper.name)) - g0) < 1, `${gripper.name} open again`);
  }

  // Torque off and on again: accepted, and the page says so.
  await waitIdle(script);
  await page.getByRole('button', { name: 'Torque off' }).click();
  await waitFor(async () => (await page.getByRole('status', { name: 'Torque' }).textContent()).startsWith('torque off'), 'torque off');
  await page.getByRole('button', { name: 'Torque on' }).click();
  await waitFor(async () => (await page.getByRole('status', { name: 'Torque' }).textContent()) === 'torque on', 'torque on');

  // Record the current pose as "pick": listed on the page, and the server has its joints.
  await waitIdle(script);
  const here = (await script.state()).joints;
  await page.getByRole('textbox', { name: 'Point name' }).fill('pick');
  await page.getByRole('button', { name: 'Record point' }).click();
  await page.getByRole('button', { name: 'Go to point pick' }).waitFor();
  const pick = (await script.get('/api/v1/points')).points.find((p) => p.name === 'pick');
  assert.ok(pick, 'the server has the point');
  for (const j of here) assert.ok(Math.abs(pick.joints[j.name] - j.position) < 0.6, `pick ${j.name} = ${pick.joints[j.name]}, the arm at ${j.position}`);
  // Away, then "Go": the arm returns to the point.
  await pageMove({ servo6: -10 });
  await waitForPosition(script, 'servo6', -10, 0.6);
  await waitIdle(script);
  await page.getByRole('button', { name: 'Go to point pick' }).click();
  await waitForPosition(script, 'servo6', pick.joints.servo6, 0.6);
  await page.getByRole('button', { name: 'Delete point pick' }).click();
  await page.getByRole('button', { name: 'Go to point pick' }).waitFor({ state: 'detached' });
  assert.ok(!(await script.get('/api/v1/points')).points.some((p) => p.name === 'pick'));
});

test('hold to move: the tool moves while a button is held and comes to rest when it is let go', async () => {
  await waitIdle(script);
  const home = { servo6: 0, servo5: 20, servo4: 40, servo3: 40, servo2: 0 };
  await pageMove(home);
  for (const [name, value] of Object.entries(home)) await waitForPosition(script, name, value, 0.6);
  await waitIdle(script);
  const y0 = (await script.state()).tool.y;
  const holdToMove = page.getByRole('checkbox', { name: 'Hold to move' });
  await holdToMove.check();
  await page.getByRole('button', { name: 'jog y plus' }).hover();
  await page.mouse.down();
  await waitFor(async () => (await script.state()).tool.y > y0 + 5, 'the tool moving along y while the button is held');
  await page.mouse.up();
  // Let go: at rest within moments (two readings 300 ms apart agree), well short of where
  // it would be had it gone on.
  await waitFor(async () => {
    const a = (await script.state()).tool.y;
    await new Promise((resolve) => setTimeout(resolve, 300));
    return Math.abs((await script.state()).tool.y - a) < 0.3;
  }, 'the tool at rest after the button was let go');
  const moved = (await script.state()).tool.y - y0;
  assert.ok(moved > 5 && moved < 80, `moved ${moved.toFixed(1)} mm along y`);
  await holdToMove.uncheck();
  await waitIdle(script);
  assert.deepEqual(problems, []);
});

test('hold to move: the speed slider sets the speed sent; a held joint button moves that joint, and letting go stops it', async () => {
  await waitIdle(script);
  const home = { servo6: 0, servo5: 20, servo4: 40, servo3: 40, servo2: 0 };
  await pageMove(home);
  for (const [name, value] of Object.entries(home)) await waitForPosition(script, name, value, 0.6);
  await waitIdle(script);
  const sent = [];
  const record = (r) => { if (new URL(r.url()).pathname === '/api/v1/servo') sent.push(r.postDataJSON()); };
  page.on('request', record);
  const holdToMove = page.getByRole('checkbox', { name: 'Hold to move' });
  const jointPlus = page.getByRole('button', { name: 'joint servo6 plus' });
  assert.ok(await jointPlus.isDisabled(), 'joint buttons wait for "hold to move"');
  await holdToMove.check();
  try {
    // The tool's speed slider from the keyboard: Home (1 mm/s), then three steps up.
    const speed = page.getByRole('slider', { name: 'Hold speed (mm/s)', exact: true });
    await speed.focus();
    for (const key of ['Home', 'ArrowRight', 'ArrowRight', 'ArrowRight']) await page.keyboard.press(key);
    assert.equal(await page.getByRole('status', { name: 'Hold speed (mm/s) value' }).textContent(), '4 mm/s');
    await speed.fill('40');
    assert.equal(await page.getByRole('status', { name: 'Hold speed (mm/s) value' }).textContent(), '40 mm/s');
    await page.getByRole('button', { name: 'jog y minus' }).hover();
    await page.mouse.down();
    await waitFor(async () => sent.length > 0, 'a servo request while the button is held');
    await page.mouse.up();
    await waitFor(async () => sent.at(-1).speed === 0, 'the request that stops it when the button is let go');
    assert.deepEqual(sent[0], { axis: 'y', speed: -40, frame: 'base' }, 'the slider\'s speed, signed by the button');
    assert.deepEqual(sent.at(-1), { axis: 'y', speed: 0 });
    await waitIdle(script);

    // One joint, held: it alone moves, at the joint slider's share of its limit (10 % of 180 deg/s).
    const before = Object.fromEntries((await script.state()).joints.map((j) => [j.name, j.position]));
    await page.getByRole('slider', { name: 'Joint hold speed (% of its limit)', exact: true }).fill('10');
    assert.equal(await page.getByRole('status', { name: 'Joint hold speed (% of its limit) value' }).textContent(), '10 %');
    sent.length = 0;
    await jointPlus.hover();
    await page.mouse.down();
    await waitFor(async () => (await script.position('servo6')) > before.servo6 + 5, 'servo6 moving while its button is held');
    await page.mouse.up();
    await waitFor(async () => {
      const a = await script.position('servo6');
      await new Promise((resolve) => setTimeout(resolve, 300));
      return Math.abs((await script.position('servo6')) - a) < 0.3;
    }, 'servo6 at rest after the button was let go');
    const moved = (await script.position('servo6')) - before.servo6;
    assert.ok(moved > 5 && moved < 40, `servo6 moved ${moved.toFixed(1)} deg`);
    await waitFor(async () => sent.at(-1).speed === 0, 'the request that stops it when the button is let go');
    for (const name of ['servo5', 'servo4', 'servo3', 'servo2'])
      assert.ok(Math.abs((await script.position(name)) - before[name]) < 0.6, `${name} stayed`);
    assert.deepEqual(sent[0], { joint: 'servo6', speed: 18 });
    assert.deepEqual(sent.at(-1), { joint: 'servo6', speed: 0 });
  } finally {
    page.off('request', record);
    await holdToMove.uncheck();
  }
  assert.ok(await jointPlus.isDisabled(), 'joint buttons off again without "hold to move"');
  await waitIdle(script);
  assert.deepEqual(problems, []);
});

test('the move-to form: use the current pose, change z, move the tool there in a straight line', async () => {
  await tab('Move').click();
  await waitIdle(script);
  const home = { servo6: 0, servo5: 20, servo4: 40, servo3: 40, servo2: 0 };
  await pageMove(home);
  for (const [name, value] of Object.entries(home)) await waitForPosition(script, name, value, 0.6);
  const before = (await waitIdle(script)).tool;
  await page.getByRole('button', { name: 'Use current pose' }).click();
  const z = page.getByRole('spinbutton', { name: 'tool z target (mm)' });
  assert.ok(Math.abs(Number(await z.inputValue()) - before.z) < 0.5, `z target ${await z.inputValue()}, the tool at ${before.z}`);
  await z.fill(String(before.z - 15));
  await clickAnswered(page.getByRole('button', { name: 'Move tool' }), '/api/v1/tool');
  await waitFor(async () => {
    const s = await script.state();
    return s.motion === null && s.job === '' && Math.abs(s.tool.z - (before.z - 15)) < 1 &&
      Math.abs(s.tool.x - before.x) < 1 && Math.abs(s.tool.y - before.y) < 1;
  }, `the tool 15 mm lower, at z = ${before.z - 15} mm`);
});

test('group editor round trip: read frames, download, run, read back positions', async () => {
  await tab('Action groups').click();
  await page.getByRole('button', { name: 'Clear table' }).click();
  await page.getByRole('spinbutton', { name: 'Frame time (ms)' }).fill('400');
  const poses = [{ servo6: -20, servo5: 10, servo4: 15 }, { servo6: 25, servo5: -15, servo4: 30 }];
  for (const pose of poses) {
    await waitIdle(script);
    await pageMove(pose);
    for (const [name, value] of Object.entries(pose)) await waitForPosition(script, name, value, 0.6);
    await page.getByRole('button', { name: 'Read current positions' }).click();
  }
  await waitFor(async () => (await page.getByRole('status', { name: 'Group editor status' }).textContent()).startsWith('2 frames'), 'two frames');
  for (const [i, pose] of poses.entries()) {
    for (const [name, value] of Object.entries(pose)) {
      const cell = Number(await page.getByRole('spinbutton', { name: `frame ${i + 1} ${name} (deg)` }).inputValue());
      assert.ok(Math.abs(cell - value) < 0.6, `frame ${i + 1} ${name} = ${cell}, read from the arm at ${value}`);
    }
  }
  await page.getByRole('spinbutton', { name: 'Group number' }).fill('7');
  // The last move's job may still be settling (the arm within 0.6 deg is not yet at rest):
  // a download then would be refused as busy.
  await waitIdle(script);
  await page.getByRole('button', { name: 'Download', exact: true }).click();
  await waitFor(async () => (await page.getByRole('status', { name: 'Group editor status' }).textContent()).startsWith('Downloaded 2 frames'), 'the download');
  await screenshot(page, 'xarm-groups');
  // Away from the last frame, then run the group once: the arm ends at the last frame.
  await waitIdle(script);
  await pageMove({ servo6: 0, servo5: 0, servo4: 0 });
  await waitForPosition(script, 'servo6', 0, 0.6);
  await waitIdle(script);
  await page.getByRole('spinbutton', { name: 'Run count' }).fill('1');
  await page.getByRole('button', { name: 'Run', exact: true }).click();
  for (const [name, value] of Object.entries(poses[1])) await waitForPosition(script, name, value, 1);

  // Export as each file format, then import it back: the same frames.
  fs.mkdirSync(artifacts, { recursive: true });
  for (const format of ['group', 'rob']) {
    const downloadDone = page.waitForEvent('download');
    await page.getByRole('combobox', { name: 'Export format' }).selectOption(format);
    await page.getByRole('button', { name: 'Export' }).click();
    const file = path.join(artifacts, `exported.${format}`);
    await (await downloadDone).saveAs(file);
    assert.ok(fs.statSync(file).size > 0, `${file} is not empty`);
    await page.getByRole('button', { name: 'Clear table' }).click();
    await page.getByLabel('Import group file').setInputFiles(file);
    await waitFor(async () => (await page.getByRole('status', { name: 'Group editor status' }).textContent()).startsWith('Imported 2 frames'), `the ${format} import`);
    for (const [name, value] of Object.entries(poses[1])) {
      const cell = Number(await page.getByRole('spinbutton', { name: `frame 2 ${name} (deg)` }).inputValue());
      assert.ok(Math.abs(cell - value) < 0.6, `${format}: imported frame 2 ${name} = ${cell}, exported ${value}`);
    }
  }
});

test('group speed, a continuous run, stop group, erase', async () => {
  await waitIdle(script);
  await clickAnswered(page.getByRole('button', { name: 'Set speed' }), '/api/v1/groups/speed');
  await page.getByRole('checkbox', { name: 'Run continuously' }).check();
  const start = await script.position('servo6');
  await clickAnswered(page.getByRole('button', { name: 'Run', exact: true }), '/run');
  // Continuous: the arm goes on between the two frames; still moving after a full pass.
  await waitFor(async () => Math.abs((await script.position('servo6')) - start) > 10, 'the run to move servo6');
  await waitFor(async () => Math.abs((await script.position('servo6')) - start) < 5, 'the run to come back (a second pass)');
  await clickAnswered(page.getByRole('button', { name: 'Stop group' }), '/api/v1/groups/stop');
  const stopped = await waitIdle(script);
  const events = await page.evaluate(() => window.armctlLive.events);
  await page.waitForFunction((n) => window.armctlLive.events >= n + 3, events);
  assert.ok(Math.abs((await script.position('servo6')) - stopped.joints.find((j) => j.name === 'servo6').position) < 0.2, 'the group stopped');
  await page.getByRole('checkbox', { name: 'Run continuously' }).uncheck();
  // Erased: running it again moves nothing (and a refusal, if the server reports one, is
  // shown with its message).
  await waitIdle(script);
  await pageMove({ servo6: 0 });
  await waitForPosition(script, 'servo6', 0, 0.6);
  await waitIdle(script);
  await clickAnswered(page.getByRole('button', { name: 'Erase' }), '/api/v1/groups/7');
  await waitFor(async () => (await page.getByRole('status', { name: 'Group editor status' }).textContent()).startsWith('Group 7 erased'), 'the erase');
  const answered = page.waitForResponse((r) => r.url().endsWith('/api/v1/groups/7/run'));
  await page.getByRole('button', { name: 'Run', exact: true }).click();
  const run = await answered;
  if (!run.ok()) {
    const { error } = await run.json();
    await waitFor(async () => (await page.getByRole('alert').first().textContent()).includes(error), `the page to show "${error}"`);
    expectRefused(problems, run.status());
    await page.getByRole('button', { name: 'Dismiss error' }).first().click();
  }
  const eventsAfterRun = await page.evaluate(() => window.armctlLive.events);
  await page.waitForFunction((n) => window.armctlLive.events >= n + 3, eventsAfterRun);
  assert.ok(Math.abs(await script.position('servo6')) < 0.6, 'an erased group moves nothing');
});

test('a program with an error shows it at its line', async () => {
  await tab('Program').click();
  const source = 'ptp joints(0deg, 0deg, 0deg, 0deg, 0deg) speed=40%\nwait 0.1s\nlin nowhere speed=20mm/s\n';
  const check = await script.post('/api/v1/program/check', { source });
  assert.equal(check.ok, false);
  const line = check.errors[0].line;
  assert.equal(line, 3, 'the server places the unknown point on line 3');
  await page.getByRole('textbox', { name: 'Program source' }).fill(source);
  await page.getByRole('button', { name: 'Check' }).click();
  await page.locator(`.gutter .line.error[data-line="${line}"]`).waitFor();
  assert.equal(await page.locator('.gutter .line.error').count(), new Set(check.errors.map((e) => e.line)).size);
  const listed = await page.getByRole('list', { name: 'Program errors' }).textContent();
  const { column, message } = check.errors[0];
  assert.ok(listed.includes(`line ${line}${column > 0 ? `, column ${column}` : ''}: ${message}`), listed);
  await screenshot(page, 'xarm-program-error');
});

test('a program run shows progress: current line, time left, output', async () => {
  const source = [
    'ptp joints(0deg, 0deg, 0deg, 0deg, 0deg) speed=30%',
    'ptp joints(40deg, 20deg, 30deg, 20deg, 0deg) speed=30%',
    'print "halfway"',
    'ptp joints(-40deg, 10deg, 20deg, 10deg, 0deg) speed=30%',
    'ptp joints(0deg, 0deg, 0deg, 0deg, 0deg) speed=30%',
  ].join('\n');
  await page.getByRole('textbox', { name: 'Program source' }).fill(source);
  await waitIdle(script);
  await page.getByRole('button', { name: 'Run', exact: true }).click();
  const progress = page.getByRole('status', { name: 'Program progress' });
  const first = await waitFor(async () => (await progress.textContent()).match(/^running: line (\d+).*; ([\d.]+) s left/), 'the run to show its line and time left');
  await page.locator('.gutter .line.current').waitFor();
  await screenshot(page, 'xarm-program-run');
  // Pause holds the run (the state says so, the button offers Resume), Resume goes on.
  await page.getByRole('button', { name: 'Pause' }).click();
  await waitFor(async () => (await progress.textContent()).startsWith('paused:'), 'the run paused');
  await waitFor(async () => (await script.state()).joints.every((j) => Math.abs(j.velocity) < 1e-6), 'the arm held');
  await page.getByRole('button', { name: 'Resume' }).click();
  await waitFor(async () => (await progress.textContent()).startsWith('running:'), 'the run resumed');
  const later = await waitFor(async () => {
    const m = (await progress.textContent()).match(/^running: line (\d+).*; ([\d.]+) s left/);
    return m && Number(m[2]) < Number(first[2]) && m;
  }, 'the time left to go down');
  assert.ok(Number(later[1]) >= 1);
  await waitFor(async () => (await page.getByLabel('Program output').textContent()).includes('halfway'), 'the print');
  await waitFor(async () => (await progress.textContent()) === 'idle', 'the end of the run', 60000);
  assert.equal(await page.locator('.gutter .line.current').count(), 0);
});

test('Stop program ends a run on the path, the arm at rest short of the end', async () => {
  await tab('Program').click();
  await waitIdle(script);
  const source = [
    'ptp joints(0deg, 0deg, 0deg, 0deg, 0deg) speed=30%',
    'ptp joints(-90deg, 0deg, 0deg, 0deg, 0deg) speed=10%',
    'print "not reached"',
  ].join('\n');
  await page.getByRole('textbox', { name: 'Program source' }).fill(source);
  await page.getByRole('button', { name: 'Run', exact: true }).click();
  const progress = page.getByRole('status', { name: 'Program progress' });
  await waitFor(async () => /^running: line 2/.test(await progress.textContent()), 'the run at line 2');
  await waitFor(async () => (await script.position('servo6')) < -5, 'servo6 on its way');
  await page.getByRole('button', { name: 'Stop program' }).click();
  await waitFor(async () => (await progress.textContent()) === 'idle', 'the run ended');
  const stopped = await waitIdle(script);
  const at = stopped.joints.find((j) => j.name === 'servo6').position;
  assert.ok(at < -5 && at > -85, `servo6 stopped at ${at}, short of -90`);
  assert.ok(!(await page.getByLabel('Program output').textContent()).includes('not reached'));
});

async function stopsAMove(how) {
  await tab('Move').click();
  await waitIdle(script);
  await page.getByRole('slider', { name: 'Joint speed' }).fill('0.05');
  await slider('servo6').fill('-100');
  const start = await script.position('servo6');
  await waitFor(async () => Math.abs((await script.position('servo6')) - start) > 2, 'the move to start');
  const pressed = Date.now();
  await how();
  // Halted: no job, no motion, every joint at rest, well short of the target.
  const stopped = await waitIdle(script);
  console.log(`BROWSER STOP to rest: ${Date.now() - pressed} ms`);
  const at = stopped.joints.find((j) => j.name === 'servo6').position;
  assert.ok(at > -90, `servo6 stopped at ${at}, well short of -100`);
  // And it stays there: three more snapshots reach the page (the stream sends one at least
  // every 0.5 s when idle), the arm has not moved.
  const events = await page.evaluate(() => window.armctlLive.events);
  await page.waitForFunction((n) => window.armctlLive.events >= n + 3, events);
  const later = await script.position('servo6');
  assert.ok(Math.abs(later - at) < 0.2, `the arm stays where it stopped (${at}), not at ${later}`);
}

test('STOP halts a move (the button)', async () => {
  await stopsAMove(() => page.getByRole('button', { name: 'STOP (Esc)' }).click());
});

test('STOP halts a move (the Esc key, from anywhere on the page)', async () => {
  await stopsAMove(async () => {
    await page.getByRole('spinbutton', { name: 'Jog step (mm)' }).focus();
    await page.keyboard.press('Escape');
  });
});
