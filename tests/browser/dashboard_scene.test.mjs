// The planning scene on the dashboard (issue 23 "Dashboard", issue 24's frame toggle), on
// both simulated arms: scene objects drawn in the 3D view (read back from its three.js graph),
// held parts moving with the tool, the links' collision shapes on request; objects added,
// moved and removed from the page, field errors before anything is sent, the scene saved to
// its file (and the 409 without one); a refused move's two bodies red with the contact
// point, for a move, a program's line and a motion the look-ahead stopped; "avoid obstacles"
// going around, for a tool move and for a program's check; hold to move sending the frame chosen.
import { describe, test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {
  waitFor, waitForPosition, waitIdle, screenshot, expectRefused,
  dashboardForFile, startServer, launchBrowser, openDashboard, apiClient, pageMove,
} from './harness.mjs';

const view = (page, reader) => page.evaluate((r) => window.armctlView[r](), reader);
const objectNamed = async (page, name) => (await view(page, 'sceneObjects')).find((o) => o.name === name);
const near = (a, b, tolerance = 0.5) => a.every((v, i) => Math.abs(v - b[i]) <= tolerance);
// A scene change sent by the page itself (it has control), as its panel sends one.
const pagePut = (page, p, body) => page.evaluate(async ({ p: path_, b }) => {
  const { api } = await import('/assets/app/api.js');
  await api.put(path_, b);
}, { p, b: body });

const pagePost = (page, p, body) => page.evaluate(async ({ p: path_, b }) => {
  const { api } = await import('/assets/app/api.js');
  await api.post(path_, b);
}, { p, b: body });

// The page's Add object form filled in: `name`, `shape`, and each field by its label after
// "New object " ('radius (mm)': 20), in the order given (a shape shows its own size fields).
async function fillNewObject(page, fields) {
  for (const [key, value] of Object.entries(fields)) {
    if (key === 'name') await page.getByRole('textbox', { name: 'New object name' }).fill(value);
    else if (key === 'shape') await page.getByRole('combobox', { name: 'New object shape' }).selectOption(value);
    else await page.getByRole('spinbutton', { name: `New object ${key}` }).fill(String(value));
  }
}

// The console's line for a refused request comes a moment after the answer: waited for,
// then taken off the list (expectRefused).
async function refusedLogged(problems, status) {
  await waitFor(() => problems.some((p) => p.includes(`status of ${status}`)), `the ${status} in the console`);
  expectRefused(problems, status);
}

// Records the bodies of the page's POSTs to `pathname` while `during` runs.
async function sentTo(page, pathname, during) {
  const sent = [];
  const record = (r) => { if (new URL(r.url()).pathname === pathname && r.method() === 'POST') sent.push(r.postDataJSON()); };
  page.on('request', record);
  try { await during(); } finally { page.off('request', record); }
  return sent;
}

// Holds "jog x plus" with hold to move in `frame`; the servo posts sent meanwhile.
async function holdX(page, script, frame) {
  await page.getByRole('combobox', { name: 'Hold to move frame' }).selectOption(frame);
  const hold = page.getByRole('checkbox', { name: 'Hold to move' });
  await hold.check();
  const sent = await sentTo(page, '/api/v1/servo', async () => {
    const start = await script.state();
    await page.getByRole('button', { name: 'jog x plus' }).hover();
    await page.mouse.down();
    await waitFor(async () => {
      const now = (await script.state()).tool;
      return Math.hypot(now.x - start.tool.x, now.y - start.tool.y, now.z - start.tool.z) > 2;
    }, `the tool moving while held (${frame} frame)`);
    await page.mouse.up();
  });
  await hold.uncheck();
  await waitIdle(script);
  return sent;
}

describe('xArm', () => {
  let page;
  let problems;
  let script;
  dashboardForFile('xarm', (s) => ({ page, problems, script } = s));

  test('scene objects are drawn where the scene puts them; a held part moves with the tool; collision shapes on request', async () => {
    await waitFor(async () => (await page.getByRole('status', { name: 'Control' }).textContent()).includes('You have control'), 'control');
    await pagePut(page, '/api/v1/scene', { objects: [
      { name: 'desk', table: { top: 0, size: [800, 600], center: [150, 0] } },
      { name: 'box', box: [50, 50, 80], at: [150, -100, 40] },
      { name: 'camera', keep_out: true, box: [200, 100, 300], at: [-200, 0, 150] },
      { name: 'ball', sphere: { radius: 15 }, at: [300, 200, 15] },
      { name: 'part', cylinder: { radius: 10, length: 40 }, at: [0, 0, 0], attached: 'tool' },
      { name: 'pipe', capsule: { radius: 15, length: 200 }, at: [0, 250, 40], rpy: [0, 90, 0] },
    ] });
    await waitFor(async () => (await view(page, 'sceneObjects')).length === 6, 'six objects drawn');
    const pipe = await objectNamed(page, 'pipe');
    assert.deepEqual([pipe.kind, pipe.at], ['capsule', [0, 250, 40]]);
    const box = await objectNamed(page, 'box');
    assert.deepEqual([box.role, box.kind], ['obstacle', 'box']);
    assert.ok(near(box.at, [150, -100, 40]), JSON.stringify(box));
    assert.ok(near((await objectNamed(page, 'desk')).at, [150, 0, -25]), 'the desk slab under its top');
    assert.equal((await objectNamed(page, 'camera')).role, 'keep_out');
    assert.ok(near((await objectNamed(page, 'ball')).at, [300, 200, 15]));
    // The held part hangs at the tool point: where the state says the tool is, before and
    // after the arm moves.
    const heldAtTool = async () => {
      const tool = (await script.state()).tool;
      const part = await objectNamed(page, 'part');
      return part.attached && near(part.at, [tool.x, tool.y, tool.z], 1.5) && part.at;
    };
    const before = await waitFor(heldAtTool, 'the held part at the tool point');
    await waitIdle(script);
    await pageMove(page, { servo6: 30, servo4: 20 });
    await waitForPosition(script, 'servo6', 30, 0.6);
    await waitIdle(script);
    const afterMove = await waitFor(heldAtTool, 'the held part at the tool point after the move');
    assert.ok(!near(before, afterMove, 5), `the held part moved with the tool: ${before} -> ${afterMove}`);

    // The links' collision shapes: there, hidden until ticked.
    const shapes = await view(page, 'collisionShapes');
    assert.ok(shapes.count >= 10, `the xArm's URDF has its collision shapes (${shapes.count})`);
    assert.equal(shapes.visible, 0);
    await page.getByRole('checkbox', { name: 'Show collision shapes' }).check();
    assert.equal((await view(page, 'collisionShapes')).visible, shapes.count);
    await screenshot(page, 'scene-xarm-objects');
    await page.getByRole('checkbox', { name: 'Show collision shapes' }).uncheck();
    assert.equal((await view(page, 'collisionShapes')).visible, 0);
    assert.equal(await view(page, 'fence'), null, 'no fence in this scene');
    // The server gives no fence yet: a state that carries one (as it will) draws it, and a
    // state with "fence": null takes it away.
    const fence = { min: [-100, -200, 0], max: [300, 200, 350] };
    const publishFence = (f) => page.evaluate(async (value) => {
      const live = await import('/assets/app/live.js');
      live.publish({ ...live.latestState(), fence: value });
    }, f);
    await publishFence(fence);
    assert.deepEqual(await view(page, 'fence'), fence);
    await publishFence(null);
    assert.equal(await view(page, 'fence'), null);
    await pageMove(page, { servo6: 0, servo4: 0 });
    await waitForPosition(script, 'servo6', 0, 0.6);
    await waitIdle(script);
    assert.deepEqual(problems, []);
  });

  test('a refused tool move shows the two bodies red and the contact point; with "avoid obstacles" it goes around', async () => {
    await pagePut(page, '/api/v1/scene', { objects: [
      { name: 'desk', table: { top: 0, size: [800, 600], center: [150, 0] } },
      { name: 'box', box: [50, 50, 80], at: [150, -100, 40] },
    ] });
    await waitFor(async () => (await view(page, 'sceneObjects')).length === 2, 'the desk scene drawn');
    await waitIdle(script);
    for (const [axis, value] of [['x', 150], ['y', -190], ['z', 40]]) {
      await page.getByRole('spinbutton', { name: `tool ${axis} target (mm)` }).fill(String(value));
    }
    const straight = page.getByRole('checkbox', { name: 'Straight line' });
    await straight.check();
    assert.ok(await page.getByRole('checkbox', { name: 'Avoid obstacles' }).isDisabled(), 'no detour for a straight line');
    await straight.uncheck();
    const refused = page.waitForResponse((r) => new URL(r.url()).pathname === '/api/v1/tool');
    await page.getByRole('button', { name: 'Move tool' }).click();
    assert.equal((await refused).status(), 400);
    await refusedLogged(problems, 400);
    const shown = await waitFor(() => view(page, 'collision'), 'the collision drawn');
    assert.ok(shown.bodies.some((b) => b.kind === 'object' && b.name === 'box'), JSON.stringify(shown));
    assert.ok(shown.bodies.some((b) => b.kind === 'link'), JSON.stringify(shown));
    assert.ok(shown.red >= 2, `the box and the link's shapes red (${shown.red} meshes)`);
    assert.equal((await objectNamed(page, 'box')).red, true);
    assert.equal((await objectNamed(page, 'desk')).red, false);
    assert.ok(near(shown.point, [150, -100, 40], 60), `the contact point at the box: ${shown.point}`);
    // The arm drawn where it would touch: the red link's shapes reach the contact point.
    assert.equal(shown.ghost, true);
    assert.ok(shown.redLinkDistance !== null && shown.redLinkDistance < 3, `the red link ${shown.redLinkDistance} mm from the contact point`);
    const note = page.getByRole('alert', { name: 'Collision' });
    assert.match(await note.textContent(), /^Refused, nothing moved: would collide .*link '.+' with box 'box'/);
    assert.equal(await page.getByRole('spinbutton', { name: 'tool x target (mm)' }).inputValue(), '150');
    await page.evaluate(() => window.scrollTo(0, 0));
    await screenshot(page, 'scene-xarm-refused');
    await waitIdle(script);

    // Around: answered with the detour, the red cleared, the arm there with no error.
    await page.getByRole('checkbox', { name: 'Avoid obstacles' }).check();
    const sent = await sentTo(page, '/api/v1/tool', async () => {
      const answered = page.waitForResponse((r) => new URL(r.url()).pathname === '/api/v1/tool');
      await page.getByRole('button', { name: 'Move tool' }).click();
      const r = await answered;
      assert.equal(r.status(), 200, await r.text());
      assert.ok((await r.json()).avoided.waypoints >= 1);
    });
    assert.equal(sent[0].avoid, true);
    await waitFor(async () => (await view(page, 'collision')) === null, 'the red cleared by the move taken');
    assert.equal((await objectNamed(page, 'box')).red, false);
    assert.ok(await note.isHidden());
    await waitFor(async () => {
      const s = await script.state();
      return s.job === '' && Math.hypot(s.tool.x - 150, s.tool.y + 190, s.tool.z - 40) < 1.5 && s;
    }, 'the tool behind the box');
    assert.equal((await script.state()).last_error, '');
    await page.getByRole('checkbox', { name: 'Avoid obstacles' }).uncheck();
    await pagePut(page, '/api/v1/scene', { objects: [] });
    await pageMove(page, { servo6: 0, servo5: 0, servo4: 0, servo3: 0 });
    await waitForPosition(script, 'servo3', 0, 0.6);
    await waitIdle(script);
    assert.deepEqual(problems, []);
  });

  test('objects are added, moved and removed from the page; bad fields say why and send nothing; no scene file is a 409', async () => {
    await waitFor(async () => (await view(page, 'sceneObjects')).length === 0, 'an empty scene');
    await page.getByRole('textbox', { name: 'New object name' }).fill('crate');
    await page.getByRole('combobox', { name: 'New object shape' }).selectOption('box');
    await page.getByRole('spinbutton', { name: 'New object size y (mm)' }).fill('-5');
    await page.getByRole('spinbutton', { name: 'New object z (mm)' }).fill('');
    const sent = await sentTo(page, '/api/v1/scene/objects/crate', async () => {
      await page.getByRole('button', { name: 'Add object' }).click();
    });
    assert.match(await page.getByText('New object size y (mm): -5 is outside 0.1..10000 mm').textContent(), /outside/);
    assert.ok(await page.getByText('New object z (mm): required').isVisible());
    assert.equal(await page.getByRole('spinbutton', { name: 'New object size y (mm)' }).getAttribute('aria-invalid'), 'true');
    assert.deepEqual(sent, [], 'nothing sent');
    await page.getByRole('textbox', { name: 'New object name' }).fill('a box');
    await page.getByRole('button', { name: 'Add object' }).click();
    assert.ok(await page.getByText('New object name: 1..40 of a-z A-Z 0-9 _ - .').isVisible());

    await fillNewObject(page, { name: 'crate', 'size y (mm)': 40, 'z (mm)': 30, shape: 'cylinder', 'radius (mm)': 20, 'length (mm)': 60 });
    await page.getByRole('button', { name: 'Add object' }).click();
    await waitFor(async () => (await script.get('/api/v1/scene')).objects.length === 1, 'the cylinder in the scene');
    const added = (await script.get('/api/v1/scene')).objects[0];
    assert.deepEqual([added.name, added.cylinder, added.at], ['crate', { radius: 20, length: 60 }, [150, 0, 30]]);
    await waitFor(async () => (await objectNamed(page, 'crate'))?.kind === 'cylinder', 'the cylinder drawn');
    assert.equal(await page.getByRole('status', { name: 'Scene status' }).textContent(), 'crate added');

    // Moved: its y edited in its row.
    await page.getByRole('spinbutton', { name: 'crate y (mm)' }).fill('120');
    await page.getByRole('button', { name: 'Move crate', exact: true }).click();
    await waitFor(async () => near((await script.get('/api/v1/scene')).objects[0].at, [150, 120, 30]), 'the crate moved on the server');
    await waitFor(async () => near((await objectNamed(page, 'crate')).at, [150, 120, 30]), 'the crate moved in the view');
    assert.deepEqual((await script.get('/api/v1/scene')).objects[0].cylinder, { radius: 20, length: 60 }, 'its shape kept');

    // Past the scene file's limits: said at the field, nothing sent.
    await page.getByRole('spinbutton', { name: 'New object length (mm)' }).fill('20000');
    await page.getByRole('button', { name: 'Add object' }).click();
    assert.ok(await page.getByText('New object length (mm): 20000 is outside 0.1..10000 mm').isVisible());

    // No scene file: the save is refused with the server's words.
    await page.getByRole('button', { name: 'Save to scene file' }).click();
    await waitFor(async () => (await page.getByRole('alert', { name: 'Scene error' }).textContent()).includes('--scene FILE'), 'the 409 shown');
    await refusedLogged(problems, 409);
    assert.match(await page.getByLabel('Scene file').textContent(), /No scene file/);

    await page.getByRole('button', { name: 'Remove crate' }).click();
    await waitFor(async () => (await script.get('/api/v1/scene')).objects.length === 0, 'the crate removed');
    await waitFor(async () => (await view(page, 'sceneObjects')).length === 0, 'the crate gone from the view');

    // A capsule at a slant: turned 45 deg about y. An angle past the file's limits says so.
    await fillNewObject(page, { name: 'pipe', shape: 'capsule', 'radius (mm)': 15, 'length (mm)': 200, 'y (mm)': 250, 'pitch (deg)': 400 });
    const none = await sentTo(page, '/api/v1/scene/objects/pipe', async () => {
      await page.getByRole('button', { name: 'Add object' }).click();
    });
    assert.ok(await page.getByText('New object pitch (deg): 400 is outside -360..360 deg').isVisible());
    assert.deepEqual(none, [], 'nothing sent');
    await page.getByRole('spinbutton', { name: 'New object pitch (deg)' }).fill('45');
    await page.getByRole('button', { name: 'Add object' }).click();
    await waitFor(async () => (await script.get('/api/v1/scene')).objects.length === 1, 'the capsule in the scene');
    const pipe = (await script.get('/api/v1/scene')).objects[0];
    assert.deepEqual([pipe.capsule, pipe.at], [{ radius: 15, length: 200 }, [150, 250, 30]]);
    assert.ok(near(pipe.rpy, [0, 45, 0], 1e-6), JSON.stringify(pipe.rpy));
    await waitFor(async () => (await objectNamed(page, 'pipe'))?.kind === 'capsule', 'the capsule drawn');
    await page.getByRole('spinbutton', { name: 'New object pitch (deg)' }).fill('0');
    await page.getByRole('button', { name: 'Remove pipe' }).click();
    await waitFor(async () => (await view(page, 'sceneObjects')).length === 0, 'the capsule gone from the view');
    assert.deepEqual(problems, []);
  });

  test('hold to move sends the frame chosen: base, then tool', async () => {
    await waitIdle(script);
    await pageMove(page, { servo6: 0, servo5: 20, servo4: 40, servo3: 40, servo2: 0 });
    await waitForPosition(script, 'servo3', 40, 0.6);
    await waitIdle(script);
    const base = await holdX(page, script, 'base');
    assert.ok(base.length >= 1 && base.filter((b) => b.speed !== 0).every((b) => b.frame === 'base'), JSON.stringify(base));
    const tool = await holdX(page, script, 'tool');
    assert.ok(tool.length >= 1 && tool.filter((b) => b.speed !== 0).every((b) => b.frame === 'tool' && b.axis === 'x'), JSON.stringify(tool));
    assert.deepEqual(problems, []);
  });

  test('a program line through the box is an error at its line; "go around obstacles" checks it', async () => {
    await pageMove(page, { servo6: 0, servo5: 0, servo4: 0, servo3: 0, servo2: 0 });
    await waitForPosition(script, 'servo3', 0, 0.6);
    await waitIdle(script);
    await pagePut(page, '/api/v1/scene', { objects: [
      { name: 'desk', table: { top: 0, size: [800, 600], center: [150, 0] } },
      { name: 'box', box: [50, 50, 80], at: [150, -100, 40] },
    ] });
    await waitIdle(script);
    await page.getByRole('tab', { name: 'Program' }).click();
    await page.getByRole('textbox', { name: 'Program source' }).fill('wait 0.1s\nptp pose(x=150mm, y=-190mm, z=40mm)\n');
    const result = page.getByRole('status', { name: 'Check result' });
    const sent = await sentTo(page, '/api/v1/program/check', async () => {
      await page.getByRole('button', { name: 'Check', exact: true }).click();
      await waitFor(async () => (await result.textContent()) === '1 error', 'the line refused');
      assert.match(await page.getByRole('list', { name: 'Program errors' }).textContent(), /line 2: .*box 'box'/);
      // The 3D view draws the line's collision as it draws a refused move's.
      const shown = await waitFor(async () => view(page, 'collision'), 'the program line\'s collision drawn');
      assert.ok(shown.bodies.some((b) => b.kind === 'object' && b.name === 'box'), JSON.stringify(shown.bodies));
      assert.ok(shown.red > 0 && shown.ghost, JSON.stringify(shown));
      await waitFor(async () => (await objectNamed(page, 'box'))?.red, 'the box drawn red');
      assert.match(await page.locator('#collision-note').textContent(), /^Refused, nothing moved: line 2: .*box 'box'/);
      await page.getByRole('checkbox', { name: 'Go around obstacles' }).check();
      await page.getByRole('button', { name: 'Check', exact: true }).click();
      await waitFor(async () => (await result.textContent()).startsWith('OK: no errors'), 'checked going around');
      await waitFor(async () => (await view(page, 'collision')) === null, 'the red cleared by the check that passed');
    });
    assert.deepEqual(sent.map((b) => b.avoid), [undefined, true]);
    await page.getByRole('checkbox', { name: 'Go around obstacles' }).uncheck();
    await page.getByRole('tab', { name: 'Move' }).click();
    await pagePut(page, '/api/v1/scene', { objects: [] });
    assert.deepEqual(problems, []);
  });

  test('a motion stopped before a box put in its way is drawn from the live state', async () => {
    await pagePost(page, '/api/v1/tool', { x: 150, y: 100, z: 40 });
    await waitFor(async () => {
      const s = await script.state();
      return s.job === '' && Math.hypot(s.tool.x - 150, s.tool.y - 100, s.tool.z - 40) < 1.5;
    }, 'the tool at y 100');
    // The box goes where the move ends once the move is under way: the look-ahead stops it.
    await pagePost(page, '/api/v1/tool', { x: 150, y: -100, z: 40 });
    await pagePut(page, '/api/v1/scene', { objects: [{ name: 'box', box: [50, 50, 80], at: [150, -100, 40] }] });
    await waitIdle(script);
    const state = await script.state();
    assert.equal(state.last_collision.while_moving, true, JSON.stringify(state.last_collision));
    assert.ok(state.tool.y > -75, `the tool stopped outside the box: y ${state.tool.y}`);
    const shown = await waitFor(async () => view(page, 'collision'), 'the stop drawn');
    assert.ok(shown.bodies.some((b) => b.kind === 'object' && b.name === 'box'), JSON.stringify(shown.bodies));
    await waitFor(async () => (await objectNamed(page, 'box'))?.red, 'the box drawn red');
    assert.match(await page.locator('#collision-note').textContent(), /^Stopped before contact: .*box 'box'/);
    await pagePut(page, '/api/v1/scene', { objects: [] });
    await pageMove(page, { servo6: 0, servo5: 0, servo4: 0, servo3: 0 });
    await waitForPosition(script, 'servo3', 0, 0.6);
    await waitIdle(script);
    assert.deepEqual(problems, []);
  });
});

describe('SCARA with a scene file', () => {
  let server;
  let browser;
  let page;
  let problems;
  let script;
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armctl-scene-page-'));
  const file = path.join(dir, 'bench.json');

  before(async () => {
    fs.writeFileSync(file, JSON.stringify({ objects: [{ name: 'crate', box: [60, 60, 60], at: [685, 0, 200] }] }));
    server = await startServer({ arm: 'scara', extra: ['--scene', file] });
    browser = await launchBrowser();
    ({ page, problems } = await openDashboard(browser, server));
    script = apiClient(server);
  });
  after(async () => {
    await browser?.close();
    const exit = await server?.stop();
    assert.ok(!exit || exit.code === 0 || exit.signal === 'SIGTERM', `armctl serve ended with ${JSON.stringify(exit)}: ${server?.output}`);
    fs.rmSync(dir, { recursive: true, force: true });
    assert.deepEqual(problems ?? [], [], 'no console errors during the whole run');
  });

  test('the scene file\'s box is drawn; a straight move down into it is refused red; hold to move sends "tool"', async () => {
    await waitFor(async () => (await page.getByRole('status', { name: 'Control' }).textContent()).includes('You have control'), 'control');
    await waitFor(async () => (await view(page, 'sceneObjects')).length === 1, 'the crate drawn');
    assert.ok(near((await objectNamed(page, 'crate')).at, [685, 0, 200]));
    assert.ok((await view(page, 'collisionShapes')).count >= 5, 'the SCARA\'s collision shapes');
    assert.match(await page.getByLabel('Scene file').textContent(), /bench\.json/);
    await waitIdle(script);
    for (const [axis, value] of [['x', 685], ['y', 0], ['z', 200]]) {
      await page.getByRole('spinbutton', { name: `tool ${axis} target (mm)` }).fill(String(value));
    }
    await page.getByRole('checkbox', { name: 'Straight line' }).check();
    const refused = page.waitForResponse((r) => new URL(r.url()).pathname === '/api/v1/tool');
    await page.getByRole('button', { name: 'Move tool' }).click();
    assert.equal((await refused).status(), 400);
    await refusedLogged(problems, 400);
    const shown = await waitFor(() => view(page, 'collision'), 'the collision drawn');
    assert.ok(shown.bodies.some((b) => b.kind === 'object' && b.name === 'crate'), JSON.stringify(shown));
    assert.equal((await objectNamed(page, 'crate')).red, true);
    assert.ok(near(shown.point, [685, 0, 200], 60), `the contact point at the crate: ${shown.point}`);
    assert.ok(shown.ghost && shown.redLinkDistance < 3, `the red link ${shown.redLinkDistance} mm from the contact point`);
    await page.evaluate(() => window.scrollTo(0, 0));
    await screenshot(page, 'scene-scara-refused');
    // A move taken clears it.
    await waitIdle(script);
    await page.getByRole('spinbutton', { name: 'tool z target (mm)' }).fill('330');
    const answered = page.waitForResponse((r) => new URL(r.url()).pathname === '/api/v1/tool');
    await page.getByRole('button', { name: 'Move tool' }).click();
    assert.equal((await answered).status(), 200);
    await waitFor(async () => (await view(page, 'collision')) === null, 'the red cleared');
    await waitIdle(script);

    // Hold to move from a bent arm (stretched out, x has no room to grow).
    for (const [axis, value] of [['x', 500], ['y', 100], ['z', 330]]) {
      await page.getByRole('spinbutton', { name: `tool ${axis} target (mm)` }).fill(String(value));
    }
    await page.getByRole('checkbox', { name: 'Straight line' }).uncheck();
    const bent = page.waitForResponse((r) => new URL(r.url()).pathname === '/api/v1/tool');
    await page.getByRole('button', { name: 'Move tool' }).click();
    assert.equal((await bent).status(), 200);
    await waitFor(async () => Math.abs((await script.state()).tool.x - 500) < 1.5, 'the tool at x 500');
    await waitIdle(script);
    const tool = await holdX(page, script, 'tool');
    assert.ok(tool.filter((b) => b.speed !== 0).every((b) => b.frame === 'tool'), JSON.stringify(tool));
    assert.deepEqual(problems, []);
  });

  test('an object added on the page is saved to the scene file', async () => {
    await page.getByRole('textbox', { name: 'New object name' }).fill('ball');
    await page.getByRole('combobox', { name: 'New object shape' }).selectOption('sphere');
    await page.getByRole('spinbutton', { name: 'New object radius (mm)' }).fill('30');
    for (const [axis, value] of [['x', 400], ['y', 300], ['z', 30]]) {
      await page.getByRole('spinbutton', { name: `New object ${axis} (mm)` }).fill(String(value));
    }
    await page.getByRole('button', { name: 'Add object' }).click();
    await waitFor(async () => (await objectNamed(page, 'ball'))?.kind === 'sphere', 'the ball drawn');
    await page.getByRole('button', { name: 'Save to scene file' }).click();
    await waitFor(async () => (await page.getByRole('status', { name: 'Scene status' }).textContent()) === `Saved 2 objects to ${file}`, 'saved');
    const saved = JSON.parse(fs.readFileSync(file, 'utf8'));
    assert.deepEqual(saved.objects.map((o) => o.name), ['crate', 'ball']);
    assert.deepEqual(saved.objects[1].sphere, { radius: 30 });
    assert.deepEqual(problems, []);
  });
});
