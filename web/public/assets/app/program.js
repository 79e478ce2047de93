// The program editor: check (POST /api/v1/program/check; errors marked at their line), run,
// pause / resume, stop; while a program runs, its current line is highlighted and the time
// left shown (state.program). The points file is optional (names used by the program).
import { api } from './api.js';
import { el, $, fmt, busy } from './dom.js';
import { onState } from './live.js';

const EXAMPLE = {
  xarm: `# A short xArm program: joint targets need no points file.
ptp joints(0deg, 20deg, 40deg, 40deg, 0deg) speed=40%
wait 0.2s
ptp joints(30deg, 10deg, 30deg, 20deg, 0deg) speed=40%
print "at the side"
ptp joints(0deg, 0deg, 0deg, 0deg, 0deg) speed=40%
`,
  scara: `# A short SCARA program: joint targets need no points file.
ptp joints(100mm, 20deg, -30deg, 10deg, 0deg, 0deg) speed=30%
wait 0.2s
ptp joints(150mm, -20deg, 30deg, 0deg, 0deg, 0deg) speed=30%
print "across"
ptp joints(100mm, 0deg, 0deg, 0deg, 0deg, 0deg) speed=30%
`,
};

export function initProgram(model) {
  const root = $('#program');
  const source = el('textarea', { spellcheck: false, wrap: 'off', rows: 16, 'aria-label': 'Program source' });
  source.value = EXAMPLE[model.arm] || '';
  const points = el('textarea', { spellcheck: false, wrap: 'off', rows: 4, 'aria-label': 'Points file (optional)', placeholder: 'home joints=0deg,20deg,40deg,40deg,0deg' });
  const gutter = el('div', { class: 'gutter', 'aria-hidden': 'true' });
  const currentMark = el('div', { class: 'line-mark current', hidden: true });
  const errorList = el('ul', { class: 'program-errors', 'aria-label': 'Program errors' });
  const result = el('p', { role: 'status', 'aria-label': 'Check result', class: 'muted' }, '');
  const progress = el('p', { role: 'status', 'aria-label': 'Program progress' }, 'idle');
  const prints = el('pre', { class: 'prints', 'aria-label': 'Program output' });
  const speed = el('input', { type: 'range', min: 0.05, max: 1, step: 0.05, value: 0.5, 'aria-label': 'Program speed' });
  const speedValue = el('output', {}, '50%');
  speed.addEventListener('input', () => { speedValue.textContent = `${Math.round(speed.value * 100)}%`; });
  // PTPs whose direct motion would collide go around the scene's objects (docs/scene.md).
  const avoid = el('input', { type: 'checkbox', 'aria-label': 'Go around obstacles' });
  let errorLines = new Map();
  let currentLine = 0;

  function renderGutter() {
    const lines = source.value.split('\n').length;
    gutter.replaceChildren(...Array.from({ length: lines }, (_, i) => {
      const n = i + 1;
      const message = errorLines.get(n);
      return el('div', {
        class: ['line', message ? 'error' : '', n === currentLine ? 'current' : ''].join(' ').trim(),
        'data-line': n, title: message || '',
      }, String(n));
    }));
    gutter.scrollTop = source.scrollTop;
    placeMark();
  }
  function lineHeight() { return parseFloat(getComputedStyle(source).lineHeight) || 18; }
  function placeMark() {
    if (!currentLine) { currentMark.hidden = true; return; }
    currentMark.hidden = false;
    const top = parseFloat(getComputedStyle(source).paddingTop) || 0;
    currentMark.style.top = `${top + (currentLine - 1) * lineHeight() - source.scrollTop}px`;
    currentMark.style.height = `${lineHeight()}px`;
  }
  function goToLine(line, column = 1) {
    const lines = source.value.split('\n');
    let offset = 0;
    for (let i = 0; i < line - 1 && i < lines.length; i += 1) offset += lines[i].length + 1;
    offset += Math.max(0, column - 1);
    source.focus();
    source.setSelectionRange(offset, offset);
    source.scrollTop = Math.max(0, (line - 3) * lineHeight());
  }
  // An error's place as a user reads it: the points file's own lines are not the program's,
  // and a column of 0 means only the line is known (the planner's errors).
  const place = (e) => `${e.file === 'points' ? 'points file ' : ''}line ${e.line}${e.column > 0 ? `, column ${e.column}` : ''}`;
  function showErrors(errors) {
    errorLines = new Map();
    for (const e of errors) if (e.file !== 'points' && !errorLines.has(e.line)) errorLines.set(e.line, e.message);
    errorList.replaceChildren(...errors.map((e) => el('li', {},
      e.file === 'points'
        ? el('span', {}, place(e))
        : el('button', { type: 'button', class: 'link', onclick: () => goToLine(e.line, e.column) }, place(e)),
      `: ${e.message}`)));
    if (errors.some((e) => e.file === 'points')) points.closest('details').open = true;
    renderGutter();
  }
  source.addEventListener('input', () => { if (errorLines.size) { errorLines = new Map(); errorList.replaceChildren(); result.textContent = 'changed since the check'; } renderGutter(); });
  source.addEventListener('scroll', () => { gutter.scrollTop = source.scrollTop; placeMark(); });

  const body = () => {
    const b = { source: source.value };
    if (points.value.trim()) b.points = points.value;
    if (avoid.checked) b.avoid = true;
    return b;
  };
  const check = async () => {
    const answer = await api.post('/api/v1/program/check', body());
    showErrors(answer.errors || []);
    result.textContent = answer.ok
      ? `OK: no errors; the run takes about ${fmt(answer.duration_s, 1)} s`
      : `${answer.errors.length} error${answer.errors.length === 1 ? '' : 's'}`;
    result.className = answer.ok ? 'ok' : 'bad';
    return answer;
  };
  const run = async () => {
    const answer = await check();
    if (!answer.ok) return;
    prints.textContent = '';
    await api.post('/api/v1/program/run', { ...body(), speed: Number(speed.value) });
  };
  const pauseButton = el('button', { type: 'button', onclick: (e) => busy(e.currentTarget, () =>
    api.post(pauseButton.dataset.state === 'paused' ? '/api/v1/program/resume' : '/api/v1/program/pause', {})) }, 'Pause');
  const button = (label, fn) => el('button', { type: 'button', onclick: (e) => busy(e.currentTarget, fn) }, label);

  root.append(
    el('h2', {}, 'Program'),
    el('div', { class: 'row' },
      button('Check', check), button('Run', run), pauseButton,
      button('Stop program', () => api.post('/api/v1/program/stop', {})),
      el('label', {}, ' Speed ', speed, ' '), speedValue,
      el('label', {}, avoid, ' go around obstacles')),
    el('div', { class: 'editor' }, gutter, el('div', { class: 'code' }, currentMark, source)),
    result, errorList, progress,
    el('details', {}, el('summary', {}, 'Points file (optional)'), points),
    el('h3', {}, 'Output'), prints);
  renderGutter();

  onState((state) => {
    const p = state.program;
    const running = p && p.state !== 'idle';
    const line = running ? p.line : 0;
    if (line !== currentLine) { currentLine = line; renderGutter(); }
    pauseButton.dataset.state = p ? p.state : 'idle';
    pauseButton.textContent = p && p.state === 'paused' ? 'Resume' : 'Pause';
    progress.textContent = running
      ? `${p.state}: line ${p.line}${p.column ? `, column ${p.column}` : ''}; ${fmt(p.left_s, 1)} s left`
      : 'idle';
    progress.dataset.line = line;
    const text = (p && p.prints ? p.prints : []).join('\n');
    if (p && prints.textContent !== text) prints.textContent = text;
  });
}
