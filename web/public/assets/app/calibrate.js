// The Calibrate tab: the guided calibration (docs/calibration.md "Dashboard") over
// /api/v1/calibration/STEP. The server's session runs every step and holds the answers; this
// module only shows the steps in order, each with Run / Redo / Skip, asks the user's
// answers, and lists the pending changes. The 3D view highlights the joint being wiggled or
// nudged. Nothing is written until Confirm; Cancel (or leaving the page) writes nothing.
import { api, reloadKeepingControl } from './api.js';
import { el, $, fmt, busy } from './dom.js';
import { highlightJoint } from './view3d.js';

const PATH = '/api/v1/calibration/';

export function initCalibrate(model) {
  const root = $('#calibrate');
  const unitOf = (name) => model.joints.find((j) => j.name === name) || model.joints[0];
  // A joint's value as the API gives it (deg or mm), with its unit.
  const shown = (name, value) => `${fmt(value, 2)} ${unitOf(name).unit}`;
  let session = null; // the start answer: marks, sheet, file

  const call = async (step, body = {}) => {
    const answer = await api.post(PATH + step, body);
    if (answer && 'describe' in answer) showPending(answer);
    return answer;
  };

  // ---- the session: start, pending changes, confirm, cancel
  const fileText = el('p', { class: 'muted', role: 'status', 'aria-label': 'Calibration file' },
    'Nothing runs until you start; nothing is written until you confirm.');
  const pending = el('pre', { class: 'pending', 'aria-label': 'Pending changes' }, '');
  const result = el('p', { role: 'status', 'aria-label': 'Calibration result' }, '');
  const steps = el('ol', { class: 'steps', 'aria-label': 'Calibration steps' });
  // The pictures the direction and zero steps refer to: the arm at each joint's mark (grey)
  // and moved positive (blue), drawn by the server from its arm file.
  const pictures = el('img', { class: 'joint-pictures', alt: 'Each joint at its mark (grey) and moved positive (blue)' });
  const picturesBox = el('details', {}, el('summary', {}, 'Pictures of the joints (each at its mark, and moved positive)'), pictures);
  const jointSelect = el('select', { 'aria-label': 'Calibration joint' },
    model.joints.map((j) => el('option', { value: j.name }, j.name)));
  const body = el('div', { hidden: true }, picturesBox, el('div', { class: 'row' }, el('strong', {}, 'Joint '), jointSelect),
    steps, el('h3', {}, 'Pending changes'), pending,
    el('div', { class: 'row' },
      el('button', { type: 'button', onclick: (e) => busy(e.currentTarget, confirm) }, 'Confirm and write'),
      el('button', { type: 'button', onclick: (e) => busy(e.currentTarget, cancel) }, 'Cancel calibration')));

  function showPending(answer) {
    pending.textContent = answer.refused ? `refused: ${answer.refused}` : answer.describe;
  }
  function end(text) {
    session = null;
    highlightJoint(null);
    body.hidden = true;
    result.textContent = text;
  }
  async function start() {
    session = await api.post(`${PATH}start`, {});
    fileText.textContent = `Arm file ${session.file}; confirmed changes are written there, the old file kept as ${session.previous}.`;
    result.textContent = '';
    showPending(session);
    for (const s of stepRows) s.reset();
    body.hidden = false;
    if (!pictures.src) {
      const svg = await api.get(`${PATH}pictures`);
      pictures.src = URL.createObjectURL(new Blob([svg], { type: 'image/svg+xml' }));
    }
  }
  async function confirm() {
    const answer = await api.post(`${PATH}confirm`, {});
    end(`Written to ${answer.written.file} (previous: ${answer.written.previous}). The arm drives with it now; `
      + 'reload the page to see its new limits in the panels. ');
    result.append(el('button', { type: 'button', onclick: reloadKeepingControl }, 'Reload the page'));
  }
  async function cancel() {
    await api.post(`${PATH}cancel`, {});
    end('Cancelled: nothing written.');
  }

  // ---- one step: a row with Run / Redo / Skip and a place for its questions
  function stepRow(title, help, run) {
    const state = el('span', { class: 'muted', role: 'status', 'aria-label': `${title} state` }, 'not run');
    const ask = el('div', { class: 'ask' });
    const row = el('li', { 'aria-label': title });
    const go = (e) => busy(e.currentTarget, async () => {
      ask.replaceChildren();
      state.textContent = 'running';
      try { await run(ask, (text) => { state.textContent = text; }); } catch (err) {
        state.textContent = `failed: ${err.message}`;
        highlightJoint(null);
      }
    });
    const runButton = el('button', { type: 'button', 'aria-label': `Run ${title}`, onclick: go }, 'Run');
    const redoButton = el('button', { type: 'button', 'aria-label': `Redo ${title}`, onclick: go, hidden: true }, 'Redo');
    const skip = el('button', { type: 'button', 'aria-label': `Skip ${title}`, onclick: () => {
      ask.replaceChildren();
      highlightJoint(null);
      state.textContent = 'skipped';
    } }, 'Skip');
    runButton.addEventListener('click', () => { runButton.hidden = true; redoButton.hidden = false; });
    row.append(el('div', { class: 'row' }, el('strong', {}, title), runButton, redoButton, skip, state),
      el('p', { class: 'muted' }, help), ask);
    steps.append(row);
    return { reset: () => { state.textContent = 'not run'; ask.replaceChildren(); runButton.hidden = false; redoButton.hidden = true; } };
  }
  const joint = () => jointSelect.value;
  // A question with buttons; resolves with the chosen button's value.
  const choose = (ask, question, choices) => new Promise((resolve) => {
    ask.replaceChildren(el('div', { class: 'row' }, el('span', {}, question),
      choices.map(([label, value]) => el('button', { type: 'button', onclick: () => resolve(value) }, label))));
  });
  // Torque off for a step done by hand; on again however it ends.
  const byHand = async (f) => {
    await call('release');
    try { return await f(); } finally { await call('hold'); }
  };

  const stepRows = [
    stepRow('Find', 'Lists what answers. On the xArm an ID without an answer has no servo or two (docs/calibration.md).',
      async (ask, done) => {
        const r = await call('find');
        ask.replaceChildren(el('pre', {}, r.find.text));
        done(r.find.silent.length ? `silent IDs: ${r.find.silent.join(', ')}` : 'every joint answers');
      }),
    stepRow('Which joint', 'Wiggles the chosen joint (highlighted in the 3D view); say which one moved.',
      async (ask, done) => {
        const j = joint();
        highlightJoint(j);
        await call('wiggle', { joint: j });
        const moved = el('select', { 'aria-label': 'Joint that moved' }, model.joints.map((m) => el('option', { value: m.name, selected: m.name === j }, m.name)));
        const answered = new Promise((resolve) => {
          ask.replaceChildren(el('div', { class: 'row' }, el('span', {}, `Which joint moved? (the highlighted one is ${j})`), moved,
            el('button', { type: 'button', onclick: () => resolve(moved.value) }, 'Answer')));
        });
        const r = await call('which', { joint: j, moved: await answered });
        highlightJoint(null);
        ask.replaceChildren(r.same ? '' : el('p', { role: 'alert' }, r.advice));
        done(r.same ? `${j}: right` : `${j}: mix-up`);
      }),
    stepRow('Direction', 'Moves the chosen joint a little its positive way (highlighted); say whether it went as the picture shows.',
      async (ask, done) => {
        const j = joint();
        highlightJoint(j);
        await call('nudge', { joint: j });
        const asShown = await choose(ask, `Did ${j} go the way the picture shows?`, [['Yes, as shown', true], ['No, the other way', false]]);
        await call('direction', { joint: j, went_as_shown: asShown });
        highlightJoint(null);
        ask.replaceChildren();
        done(asShown ? `${j}: as shown` : `${j}: flipped (pending)`);
      }),
    stepRow('Zero', 'Torque off: put the chosen joint at its mark by hand, then say so.', async (ask, done) => {
      const j = joint();
      const mark = session.marks[j];
      await byHand(async () => {
        await choose(ask, `Move ${j} by hand to its mark (${shown(j, mark)}), then`, [['At the mark', true]]);
        const r = await call('zero', { joint: j, mark });
        ask.replaceChildren(el('p', {}, r.zero.text));
        done(r.zero.kind === 'servo_offset' ? `${j}: servo offset ${r.zero.servo_offset}` : `${j}: zero moves by ${shown(j, r.zero.shift)}`);
      });
    }),
    stepRow('Limits', 'Torque off: move the chosen joint by hand to one end, then the other.', async (ask, done) => {
      const j = joint();
      await byHand(async () => {
        await choose(ask, `Move ${j} to one end of its travel, then`, [['At one end', true]]);
        const a = (await call('read', { joint: j })).value;
        await choose(ask, 'Now to its other end, then', [['At the other end', true]]);
        const b = (await call('read', { joint: j })).value;
        const r = await call('limits', { joint: j, end_a: a, end_b: b });
        ask.replaceChildren();
        done(`${j}: ${shown(j, r.limits.lower)} .. ${shown(j, r.limits.upper)}`);
      });
    }),
    stepRow('Gripper', 'Torque off: open the gripper by hand, then close it.', async (ask, done) => {
      const g = model.joints.find((m) => m.gripper);
      if (!g) return done('this arm has no gripper');
      await byHand(async () => {
        await choose(ask, 'Open the gripper by hand, then', [['Open', true]]);
        const open = (await call('read', { joint: g.name })).value;
        await choose(ask, 'Close it by hand, then', [['Closed', true]]);
        const closed = (await call('read', { joint: g.name })).value;
        const r = await call('gripper', { open, closed });
        ask.replaceChildren();
        done(`open ${shown(g.name, r.gripper.open)}, closed ${shown(g.name, r.gripper.closed)}`);
      });
    }),
    stepRow('Touch and verify', 'Torque off: put the tool point on each mark of the printed sheet; then verify.', async (ask, done) => {
      await byHand(async () => {
        for (const p of session.sheet) {
          const at = p.position.map((v) => fmt(v, 1)).join(' ');
          const v = await choose(ask, `Tool on mark ${p.name} (${at} mm), then`, [['On the mark', 'touch'], ['Skip the mark', 'skip'], ['Done', 'done']]);
          if (v === 'done') break;
          if (v === 'touch') await call('touch', { name: p.name, position: p.position });
        }
      });
      const r = await call('verify');
      ask.replaceChildren(el('pre', {}, r.verify.points.map((p) => `${p.name}: ${fmt(p.distance, 2)} mm`).join('\n')));
      done(`rms ${fmt(r.verify.rms, 2)} mm, worst ${r.verify.worst}`);
    }),
    stepRow('Fit', 'Fits zeros and link lengths to 10..30 touched points (optional).', async (ask, done) => {
      const r = await call('fit');
      ask.replaceChildren(el('pre', {}, r.fit.estimates.map((e) => `${e.parameter}: ${e.kind === 'zero' ? shown(e.joint, e.correction) : `${fmt(e.correction, 3)} mm`}`).join('\n')));
      done(`rms ${fmt(r.fit.before.rms, 2)} mm before, ${fmt(r.fit.after.rms, 2)} mm after`);
    }),
  ];

  root.append(el('div', { class: 'row' },
    el('button', { type: 'button', onclick: (e) => busy(e.currentTarget, start) }, 'Start calibration')), fileText, result, body);
}
