// The 3D view: the arm's URDF (GET /api/v1/urdf, its <visual> cylinders and boxes) drawn
// with three.js, each joint set from the live positions; its <collision> shapes too, hidden
// until "collision shapes" is ticked; and the planning scene (scene3d.js). It draws only
// when something changed (a new position, the user turning the view): four agents may
// share two cores.
// window.armctlView.jointValues() reads the model's joint values back (deg / mm), so the
// browser tests check what the view shows, not what the page was told; scene3d.js adds its
// own readers. Without WebGL the scene graph is still built (the readers work), not drawn.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import URDFLoader from 'urdf-loader';
import { api } from './api.js';
import { $, el } from './dom.js';
import { onState } from './live.js';
import { initScene3d } from './scene3d.js';

const DEG = Math.PI / 180;

// The calibration's guide (calibrate.js): highlightJoint(name) tints the links joint `name`
// moves, null clears it; window.armctlView.highlighted() reads it back for the tests.
let highlight = () => {};
export function highlightJoint(name) { highlight(name); }

// deg -> rad for revolute joints, mm -> m for prismatic: the URDF's SI units.
function toUrdf(joint, value) { return joint.kind === 'prismatic' ? value / 1000 : value * DEG; }
function fromUrdf(joint, value) { return joint.kind === 'prismatic' ? value * 1000 : value / DEG; }

function webglAvailable() {
  try {
    const canvas = document.createElement('canvas');
    return Boolean(canvas.getContext('webgl2') || canvas.getContext('webgl'));
  } catch { return false; }
}

// The link collision shapes: see-through orange, drawn over the visuals they enclose.
function styleColliders(robot) {
  const material = new THREE.MeshStandardMaterial({ color: 0xff9a1f, transparent: true, opacity: 0.35, depthWrite: false });
  const colliders = [];
  robot.traverse((node) => {
    if (!node.isURDFCollider) return;
    node.traverse((mesh) => { if (mesh.isMesh) mesh.material = material; });
    node.visible = false;
    colliders.push(node);
  });
  return colliders;
}

export async function initView3d(model) {
  const host = $('#view3d');
  const note = $('#view3d-note');
  const modelJoints = new Map(model.joints.map((j) => [j.name, j]));
  const view = { ready: false, updates: 0, jointValues: () => ({}) };
  window.armctlView = view;

  const urdf = await api.get('/api/v1/urdf');
  const loader = new URDFLoader();
  loader.parseCollision = true;
  const robot = loader.parse(urdf);
  robot.rotation.x = -Math.PI / 2; // URDF is z-up, three.js y-up
  const colliders = styleColliders(robot);

  let highlighted = null;
  let redraw = () => {};
  const tinted = new Map(); // mesh -> its own material, while it wears the highlight's
  view.highlighted = () => highlighted;
  highlight = (name) => {
    for (const [mesh, material] of tinted) {
      mesh.material.dispose(); // the highlight's clone
      mesh.material = material;
    }
    tinted.clear();
    highlighted = name && robot.joints[name] ? name : null;
    if (highlighted) {
      robot.joints[highlighted].traverse((o) => {
        if (!o.isMesh) return;
        tinted.set(o, o.material);
        o.material = o.material.clone();
        if (o.material.color) o.material.color.set(0xff8c00);
      });
    }
    redraw();
  };

  view.jointValues = () => {
    const values = {};
    for (const [name, joint] of Object.entries(robot.joints)) {
      const mj = modelJoints.get(name);
      if (mj && joint.jointType !== 'fixed') values[name] = fromUrdf(mj, joint.angle);
    }
    return values;
  };

  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf4f6f8);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  sun.position.set(1, 2, 1.5);
  scene.add(sun);
  const grid = new THREE.GridHelper(1.2, 24, 0x8899aa, 0xd0d7de);
  scene.add(grid);
  scene.add(robot);

  const gl = webglAvailable();
  let requestRender = () => { scene.updateMatrixWorld(); };
  let renderer = null;
  let camera = null;
  if (gl) {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    host.append(renderer.domElement);
    renderer.domElement.setAttribute('aria-label', `3D view of the ${model.arm}`);
    renderer.domElement.setAttribute('role', 'img');
  } else {
    note.textContent = 'The 3D view needs WebGL, which this browser does not offer; the joint values still follow.';
  }

  if (renderer) {
    // Frame the arm: its size at zero decides the camera distance.
    const box = new THREE.Box3().setFromObject(robot);
    const size = box.getSize(new THREE.Vector3()).length() || 0.5;
    const centre = box.getCenter(new THREE.Vector3());
    camera = new THREE.PerspectiveCamera(40, 1, 0.01, 20);
    camera.position.set(centre.x + size * 1.1, centre.y + size * 0.7, centre.z + size * 1.3);
    const controls = new OrbitControls(camera, renderer.domElement);
    controls.target.copy(centre);
    controls.update();

    let pending = false;
    const render = () => {
      pending = false;
      renderer.render(scene, camera);
      view.updates += 1;
    };
    requestRender = () => {
      if (pending) return;
      pending = true;
      requestAnimationFrame(render);
    };
    controls.addEventListener('change', requestRender);

    const resize = () => {
      const width = host.clientWidth || 400;
      const height = host.clientHeight || 300;
      renderer.setSize(width, height, false);
      camera.aspect = width / height;
      camera.updateProjectionMatrix();
      requestRender();
    };
    new ResizeObserver(resize).observe(host);
    resize();
  }
  redraw = () => requestRender(); // the highlight's

  // The link collision shapes (what the planner checks), on request.
  const showColliders = el('input', { type: 'checkbox', 'aria-label': 'Show collision shapes',
    onchange: () => {
      for (const c of colliders) c.visible = showColliders.checked;
      requestRender();
    } });
  host.after(el('div', { class: 'row view-options' },
    el('label', {}, showColliders, ' collision shapes'),
    colliders.length ? '' : el('span', { class: 'muted' }, ' (the URDF has none)')));
  view.collisionShapes = () => ({
    count: colliders.length,
    visible: colliders.filter((c) => c.visible).length,
  });

  function applyState(state) {
    let changed = false;
    for (const j of state.joints || []) {
      const mj = modelJoints.get(j.name);
      if (mj && robot.joints[j.name]) changed = robot.setJointValue(j.name, toUrdf(mj, j.position)) || changed;
    }
    return changed;
  }
  onState((state) => { if (applyState(state)) requestRender(); });
  await initScene3d({ scene, robot, model, view, requestRender: () => requestRender() });
  requestRender();
  view.ready = true;
}
