// The planning scene in the 3D view (docs/scene.md): the table, boxes, cylinders, capsules and spheres
// as GET /api/v1/scene gives them, keep-out zones see-through red, parts held by the tool
// hung from the tool link so that they move with it; the fence (a workspace box) when the
// model, the scene or the state has one ({"fence": {"min": [x, y, z], "max": [x, y, z]}} mm);
// and a refused move drawn where it would collide: a see-through grey ghost of the arm at the
// joints of the contact, its colliding link's shapes and the scene object in red, and a red
// dot where they touch, until the next move is taken.
// window.armctlView gains sceneObjects(), fence() and collision(): what the view draws, read
// back from the three.js graph in the base frame (mm), for the browser tests.
import * as THREE from 'three';
import { onApiError, onApiAnswer } from './api.js';
import { $ } from './dom.js';
import { onState } from './live.js';
import { onScene } from './scene.js';

const DEG = Math.PI / 180;
const MM = 1 / 1000;
// deg -> rad for revolute joints, mm -> m for prismatic: the URDF's SI units.
const toUrdf = (joint, value) => (joint.kind === 'prismatic' ? value * MM : value * DEG);
const TABLE_THICKNESS_MM = 50; // docs/scene.md: a slab this thick under its top
const DEFAULT_TABLE_MM = 2000;
const RED = 0xe0221b;

const COLOURS = {
  obstacle: { color: 0x5b7fa6, opacity: 0.75 },
  table: { color: 0xb08d57, opacity: 0.35 },
  keep_out: { color: 0xd9534f, opacity: 0.18 },
  held: { color: 0x3c9a5f, opacity: 0.8 },
};

function roleOf(object) {
  if (object.table) return 'table';
  if (object.keep_out) return 'keep_out';
  if (object.attached) return 'held';
  return 'obstacle';
}

// The shape's geometry (m) and where it stands in its parent (base or tool frame), from the
// scene file's form of an object.
function shapeOf(object) {
  if (object.table) {
    const t = object.table;
    const [w, d] = t.size || [DEFAULT_TABLE_MM, DEFAULT_TABLE_MM];
    const [cx, cy] = t.center || [0, 0];
    return { kind: 'table', geometry: new THREE.BoxGeometry(w * MM, d * MM, TABLE_THICKNESS_MM * MM),
      at: [cx, cy, (t.top || 0) - TABLE_THICKNESS_MM / 2], rpy: [0, 0, 0] };
  }
  let geometry;
  let kind;
  if (object.box) {
    kind = 'box';
    geometry = new THREE.BoxGeometry(...object.box.map((v) => v * MM));
  } else if (object.cylinder) {
    kind = 'cylinder';
    geometry = new THREE.CylinderGeometry(object.cylinder.radius * MM, object.cylinder.radius * MM, object.cylinder.length * MM, 32);
    geometry.rotateX(Math.PI / 2); // three.js cylinders stand along y; the scene's along z
  } else if (object.capsule) {
    // Its length is the straight part's, between the centres of its two half spheres (as FCL's).
    kind = 'capsule';
    geometry = new THREE.CapsuleGeometry(object.capsule.radius * MM, object.capsule.length * MM, 8, 32);
    geometry.rotateX(Math.PI / 2);
  } else if (object.sphere) {
    kind = 'sphere';
    geometry = new THREE.SphereGeometry(object.sphere.radius * MM, 32, 16);
  } else {
    return null;
  }
  return { kind, geometry, at: object.at || [0, 0, 0], rpy: object.rpy || [0, 0, 0] };
}

// A pose in the scene's form: at (mm) and rpy (deg, Z-Y-X as the arm's poses).
function place(node, at, rpy) {
  node.position.set(at[0] * MM, at[1] * MM, at[2] * MM);
  node.rotation.set(rpy[0] * DEG, rpy[1] * DEG, rpy[2] * DEG, 'ZYX');
}

function material({ color, opacity }) {
  return new THREE.MeshStandardMaterial({ color, transparent: opacity < 1, opacity, depthWrite: opacity >= 0.5 });
}

export async function initScene3d({ scene, robot, model, view, requestRender }) {
  // The arm's base frame (z up, as the URDF): scene objects are placed in it.
  const base = new THREE.Group();
  base.name = 'scene base frame';
  base.rotation.x = -Math.PI / 2;
  scene.add(base);
  const objects = new THREE.Group();
  objects.name = 'scene objects';
  base.add(objects);
  // Held parts: in the tool frame, which hangs in the URDF's tool link.
  const toolLink = robot.links[model.tool_link];
  const toolFrame = new THREE.Group();
  toolFrame.name = 'tool frame';
  if (model.tool_offset) place(toolFrame, model.tool_offset.at, model.tool_offset.rpy);
  (toolLink || robot).add(toolFrame);
  const held = new THREE.Group();
  toolFrame.add(held);

  const drawn = new Map(); // name -> { mesh, object, role, kind }
  const clearGroup = (group) => {
    for (const child of [...group.children]) {
      group.remove(child);
      child.traverse((n) => { n.geometry?.dispose(); });
    }
  };

  function drawScene(sceneJson) {
    clearGroup(objects);
    clearGroup(held);
    drawn.clear();
    for (const object of sceneJson.objects || []) {
      const shape = shapeOf(object);
      if (!shape) continue;
      const role = roleOf(object);
      const mesh = new THREE.Mesh(shape.geometry, material(COLOURS[role]));
      mesh.name = `scene object ${object.name}`;
      mesh.userData = { sceneObject: object.name, role, kind: shape.kind };
      place(mesh, shape.at, shape.rpy);
      if (role === 'keep_out') {
        mesh.add(new THREE.LineSegments(new THREE.EdgesGeometry(shape.geometry),
          new THREE.LineBasicMaterial({ color: COLOURS.keep_out.color })));
      }
      (object.attached ? held : objects).add(mesh);
      drawn.set(object.name, { mesh, object, role, kind: shape.kind });
    }
    showCollision(collision); // the names may be back
    requestRender();
  }

  // The fence: a wire box, from whichever JSON carries one.
  let fenceText = '';
  let fenceBox = null;
  function drawFence(fence) {
    const text = JSON.stringify(fence || null);
    if (text === fenceText) return;
    fenceText = text;
    if (fenceBox) { base.remove(fenceBox); fenceBox.geometry.dispose(); fenceBox = null; }
    if (fence && Array.isArray(fence.min) && Array.isArray(fence.max)) {
      const size = fence.max.map((v, i) => Math.max(v - fence.min[i], 0.1) * MM);
      fenceBox = new THREE.LineSegments(new THREE.EdgesGeometry(new THREE.BoxGeometry(...size)),
        // Grey while switched off (docs/scene.md "Fence and reduced mode"): still there, not checked.
        new THREE.LineBasicMaterial({ color: fence.on === false ? 0x9aa0a6 : 0x1f6feb }));
      fenceBox.name = 'fence';
      fenceBox.userData = { fence };
      fenceBox.position.set(...fence.min.map((v, i) => (v + fence.max[i]) / 2 * MM));
      base.add(fenceBox);
    }
    requestRender();
  }

  // A refusal's two bodies in red and where they would touch.
  const note = $('#collision-note');
  const marker = new THREE.Mesh(new THREE.SphereGeometry(0.008, 16, 8),
    new THREE.MeshBasicMaterial({ color: RED, depthTest: false }));
  marker.name = 'contact point';
  marker.renderOrder = 10;
  marker.visible = false;
  base.add(marker);
  const redMaterial = new THREE.MeshStandardMaterial({ color: RED, transparent: true, opacity: 0.7, depthWrite: false });
  // The arm where it would collide: a copy of the model, see-through, its shapes hidden
  // except the colliding link's (red).
  const ghost = robot.clone();
  ghost.name = 'arm at the contact';
  const ghostMaterial = new THREE.MeshStandardMaterial({ color: 0x8a94a0, transparent: true, opacity: 0.3, depthWrite: false });
  ghost.traverse((n) => {
    if (n.isMesh) n.material = ghostMaterial;
    if (n.isURDFCollider) n.visible = false;
  });
  ghost.visible = false;
  robot.parent.add(ghost);
  const modelJoints = new Map(model.joints.map((j) => [j.name, j]));
  let collision = null;     // the refusal's detail while shown
  let reddened = [];        // [{ node, material, visible }] to put back
  const redden = (node) => {
    node.traverse((n) => {
      if (n.isMesh || n.isURDFCollider) reddened.push({ node: n, material: n.material, visible: n.visible });
      if (n.isMesh) n.material = redMaterial;
      n.visible = true;
    });
  };
  function unredden() {
    for (const { node, material: m, visible } of reddened) {
      if (node.isMesh) node.material = m;
      node.visible = visible;
    }
    reddened = [];
  }
  function showCollision(detail, message) {
    unredden();
    collision = detail;
    marker.visible = Boolean(detail);
    ghost.visible = Boolean(detail && detail.joints);
    if (!detail) {
      if (note) { note.hidden = true; note.textContent = ''; }
      requestRender();
      return;
    }
    for (const [name, value] of Object.entries(detail.joints || {})) {
      if (modelJoints.has(name) && ghost.joints[name]) ghost.setJointValue(name, toUrdf(modelJoints.get(name), value));
    }
    // A link is red where it would touch (on the ghost); without the joints, on the arm.
    const arm = ghost.visible ? ghost : robot;
    for (const body of detail.bodies || []) {
      if (body.kind === 'object' && drawn.has(body.name)) redden(drawn.get(body.name).mesh);
      if (body.kind === 'link' && arm.links[body.name]) {
        for (const child of arm.links[body.name].children) if (child.isURDFCollider) redden(child);
      }
    }
    const p = detail.point || [0, 0, 0];
    marker.position.set(p[0] * MM, p[1] * MM, p[2] * MM);
    if (note && message !== undefined) {
      note.hidden = false;
      note.textContent = detail.while_moving ? `Stopped before contact: ${message}` : `Refused, nothing moved: ${message}`;
    }
    requestRender();
  }

  const MOVES = /\/api\/v1\/(joints|tool|jog|program\/run)$/;
  // A program's line that would collide: its placed error carries the collision.
  const programCollision = (errors) => (errors || []).find((e) => e.collision);
  onApiError((error) => {
    const placed = error.body && programCollision(error.body.errors);
    if (error.body && error.body.collision) showCollision(error.body.collision, error.message);
    else if (placed) showCollision(placed.collision, `line ${placed.line}: ${placed.message}`);
  });
  onApiAnswer((method, path, answer) => {
    if (collision && method === 'POST' && MOVES.test(path) && answer && (answer.moving || answer.started)) showCollision(null);
    if (method === 'POST' && path === '/api/v1/program/check' && answer) {
      const placed = programCollision(answer.errors);
      if (placed) showCollision(placed.collision, `line ${placed.line}: ${placed.message}`);
      else if (collision) showCollision(null);
    }
  });

  onScene(drawScene);
  drawFence(model.fence);
  // A motion the look-ahead stopped before contact (or a job refused on a collision) is in
  // the live state: drawn once when it appears, as a refusal the page asked for is.
  let lastCollision = '';
  onState((state) => {
    if ('fence' in state) drawFence(state.fence);
    const key = state.last_collision ? JSON.stringify(state.last_collision) + state.last_error : '';
    if (key && key !== lastCollision) showCollision(state.last_collision, state.last_error);
    lastCollision = key;
  });
  onScene((s) => { if ('fence' in s) drawFence(s.fence); });

  // Readers for the tests: what is drawn, in the base frame (mm).
  const inBase = (node) => {
    node.updateWorldMatrix(true, false);
    const p = base.worldToLocal(node.getWorldPosition(new THREE.Vector3()));
    return [p.x / MM, p.y / MM, p.z / MM].map((v) => Math.round(v * 10) / 10);
  };
  view.sceneObjects = () => [...drawn.entries()].map(([name, d]) => ({
    name, role: d.role, kind: d.kind, at: inBase(d.mesh), visible: d.mesh.visible,
    red: d.mesh.material === redMaterial, attached: Boolean(d.object.attached),
  }));
  view.fence = () => (fenceBox ? fenceBox.userData.fence : null);
  // How far the contact point is from the red link's shapes as drawn (mm; 0 inside): the
  // ghost stands where the arm would touch.
  const redLinkDistance = () => {
    const meshes = reddened.filter((r) => r.node.isMesh && r.node !== marker && !r.node.userData.sceneObject).map((r) => r.node);
    if (!meshes.length) return null;
    scene.updateMatrixWorld(true);
    const box = new THREE.Box3();
    for (const m of meshes) box.expandByObject(m);
    return box.distanceToPoint(marker.getWorldPosition(new THREE.Vector3())) / MM;
  };
  view.collision = () => (collision ? {
    bodies: collision.bodies.map((b) => ({ kind: b.kind, name: b.name })),
    point: inBase(marker),
    red: reddened.filter((r) => r.node.isMesh).length,
    ghost: ghost.visible,
    redLinkDistance: redLinkDistance(),
  } : null);
}
