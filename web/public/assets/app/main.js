// The dashboard: reads the arm's model, builds every panel from it (so one page serves
// both arms), then follows the live state.
import { api } from './api.js';
import { $ } from './dom.js';
import { startLive, latestState } from './live.js';
import { initStatus, takeControlIfFree, showError } from './status.js';
import { initJoints } from './joints.js';
import { initView3d } from './view3d.js';
import { initTool } from './tool.js';
import { initPoints } from './points.js';
import { initGroups } from './groups.js';
import { initProgram } from './program.js';
import { initCalibrate } from './calibrate.js';
import { initScene } from './scene.js';

function initTabs() {
  const tabs = [...document.querySelectorAll('[role=tab]')];
  const choose = (tab) => {
    for (const t of tabs) {
      const chosen = t === tab;
      t.setAttribute('aria-selected', String(chosen));
      t.tabIndex = chosen ? 0 : -1;
      $(`#${t.getAttribute('aria-controls')}`).hidden = !chosen;
    }
  };
  tabs.forEach((tab, i) => {
    tab.addEventListener('click', () => choose(tab));
    tab.addEventListener('keydown', (e) => {
      const step = e.key === 'ArrowRight' ? 1 : e.key === 'ArrowLeft' ? -1 : 0;
      if (!step) return;
      const next = tabs[(i + step + tabs.length) % tabs.length];
      choose(next);
      next.focus();
    });
  });
}

async function start() {
  initTabs();
  let model;
  try {
    model = await api.get('/api/v1/model');
  } catch (e) {
    showError(`The arm's model cannot be read: ${e.message}`);
    return;
  }
  initStatus(model);
  initJoints(model);
  initTool(model);
  initPoints(model);
  initGroups(model);
  initProgram(model);
  initCalibrate(model);
  initScene();
  await startLive();
  // The first page to open takes control; a page opened while another has it watches.
  await takeControlIfFree(latestState());
  try {
    await initView3d(model);
  } catch (e) {
    showError(`3D view: ${e.message}`);
  }
  document.body.dataset.ready = 'true';
}

start();
