// The live page of `tmlab realtime --serve` (docs/realtime.md). Protocol: realtime/live_protocol.hpp.
// The server sends a hello (surface triangles, probe, bounds) and then binary frames (node
// positions, probe centre, force on the probe); the page sends the probe target while the user drags
// the probe. window.tmlab exposes the state to the headless browser test (tests/browser_test.mjs).

const state = (window.tmlab = {
  connected: false, hello: null, frames: 0, fps: 0, force: [0, 0, 0], probe: [0, 0, 0], t: 0,
  rendered: 0, error: null, moves: 0, target: null,
  probeScreen: null, worldToScreen: null, viewDirection: null,
});
const panel = document.getElementById('panel');

function fail(html, err) {
  const m = document.getElementById('message');
  m.innerHTML = html;
  m.style.display = 'block';
  state.error = m.textContent;
  panel.textContent = 'not running';
  if (err) console.error(err);
}

let THREE, OrbitControls;
try {
  THREE = await import('three');
  ({ OrbitControls } = await import('three/addons/controls/OrbitControls.js'));
} catch (e) {
  fail(`<b>three.js is not installed</b>, so this page cannot draw the liver.<br><br>
    On the machine running tmlab, install it (npm is needed: <code>sudo apt-get install npm</code>):<br>
    <code>./tmlab build</code> (the set-up runs npm for you), or by hand from the tmlab directory:<br>
    <code>mkdir -p build/npm &amp;&amp; cp realtime/web/package.json realtime/web/package-lock.json build/npm/ &amp;&amp;
    npm ci --prefix build/npm</code><br><br>then reload this page (the run keeps going).`, e);
  throw e;
}

// ---------------------------------------------------------------- scene
const view = document.getElementById('view');
let renderer;
try {
  renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
} catch (e) {
  fail('<b>WebGL is not available in this browser</b>: the page cannot draw the liver.', e);
  throw e;
}
renderer.setPixelRatio(window.devicePixelRatio);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1d2024);
const camera = new THREE.PerspectiveCamera(35, 1, 0.001, 100);
camera.up.set(0, 0, 1);  // the mesh frame has z up
scene.add(new THREE.HemisphereLight(0xffffff, 0x303040, 1.4));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
scene.add(sun);
const controls = new OrbitControls(camera, renderer.domElement);
controls.enableDamping = false;

let geometry = null, positions = null, probeMesh = null, ghost = null, arrow = null, center = null, extent = 1;
let probeStart = null, target = null;  // the probe's start and the target last asked for (mesh frame)

function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / Math.max(1, h);
  camera.updateProjectionMatrix();
  resizePlot();
}
window.addEventListener('resize', resize);

function onHello(h) {
  state.hello = h;
  const lo = new THREE.Vector3(...h.bounds.min), hi = new THREE.Vector3(...h.bounds.max);
  center = lo.clone().add(hi).multiplyScalar(0.5);
  extent = hi.clone().sub(lo).length();
  geometry = new THREE.BufferGeometry();
  positions = new THREE.BufferAttribute(new Float32Array(3 * h.nodes), 3);
  positions.setUsage(THREE.DynamicDrawUsage);
  geometry.setAttribute('position', positions);
  geometry.setIndex(h.triangles);
  const liver = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({
    color: 0xa8473d, roughness: 0.55, metalness: 0.0, side: THREE.DoubleSide }));
  scene.add(liver);
  const wire = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({
    color: 0x000000, wireframe: true, transparent: true, opacity: 0.12 }));
  scene.add(wire);
  const r = h.probe_radius;
  probeMesh = new THREE.Mesh(new THREE.SphereGeometry(r, 32, 16),
    new THREE.MeshStandardMaterial({ color: 0xb8c0cc, roughness: 0.3, metalness: 0.3, transparent: true, opacity: 0.85 }));
  probeMesh.position.set(...h.probe);
  scene.add(probeMesh);
  ghost = new THREE.Mesh(new THREE.SphereGeometry(r, 16, 8),
    new THREE.MeshBasicMaterial({ color: 0x66ccff, wireframe: true, transparent: true, opacity: 0.35 }));
  ghost.visible = false;
  scene.add(ghost);
  arrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), probeMesh.position, 0.01, 0xffd23f);
  arrow.traverse((o) => { if (o.material) { o.material.depthTest = false; o.renderOrder = 10; } });  // seen through the probe
  scene.add(arrow);
  probeStart = new THREE.Vector3(...h.probe);
  target = probeStart.clone();
  state.target = target.toArray();
  // The view of the PNG frames (frame_renderer.hpp): looking along (0.35, 1, -0.6).
  const look = new THREE.Vector3(0.35, 1.0, -0.6).normalize();
  camera.position.copy(center).addScaledVector(look, -1.6 * extent);
  camera.near = extent / 100;
  camera.far = extent * 20;
  controls.target.copy(center);
  controls.update();
  sun.position.copy(camera.position).add(new THREE.Vector3(0, 0, extent));
  resize();
}

// ---------------------------------------------------------------- force plot
const plot = document.getElementById('plot');
const ctx = plot.getContext('2d');
const history = [];  // [t, |F|, Fx, Fy, Fz]
const windowS = 10;
function resizePlot() {
  plot.width = plot.clientWidth * window.devicePixelRatio;
  plot.height = plot.clientHeight * window.devicePixelRatio;
}
function drawPlot() {
  const W = plot.width, H = plot.height, s = window.devicePixelRatio;
  ctx.clearRect(0, 0, W, H);
  if (history.length < 2) return;
  const t1 = history[history.length - 1][0], t0 = t1 - windowS;
  let fmax = 0.1;
  for (const h of history) fmax = Math.max(fmax, h[1]);
  fmax *= 1.1;
  const L = 50 * s, R = W - 10 * s, T = 12 * s, B = H - 22 * s;
  const x = (t) => L + (R - L) * (t - t0) / windowS;
  const y = (f) => B - (B - T) * (f + fmax) / (2 * fmax);
  ctx.strokeStyle = '#333a44'; ctx.lineWidth = s;
  ctx.beginPath(); ctx.moveTo(L, y(0)); ctx.lineTo(R, y(0)); ctx.stroke();
  ctx.fillStyle = '#99a'; ctx.font = `${11 * s}px ui-monospace, monospace`;
  ctx.fillText(`${fmax.toFixed(2)} N`, 4 * s, T + 4 * s);
  ctx.fillText(`${(-fmax).toFixed(2)} N`, 4 * s, B);
  ctx.fillText(`force on the probe, last ${windowS} s`, L, H - 6 * s);
  const series = [[2, '#e06c75', 1], [3, '#98c379', 1], [4, '#61afef', 1], [1, '#ffd23f', 2]];
  for (const [k, colour, w] of series) {
    ctx.strokeStyle = colour; ctx.lineWidth = w * s;
    ctx.beginPath();
    history.forEach((h, i) => (i ? ctx.lineTo(x(h[0]), y(h[k])) : ctx.moveTo(x(h[0]), y(h[k]))));
    ctx.stroke();
  }
  const lx = R - 190 * s;
  [['|F|', '#ffd23f'], ['Fx', '#e06c75'], ['Fy', '#98c379'], ['Fz', '#61afef']].forEach(([n, c], i) => {
    ctx.fillStyle = c; ctx.fillText(n, lx + i * 48 * s, T + 4 * s);
  });
}

// ---------------------------------------------------------------- frames
const frameTimes = [];
function onFrame(buf) {
  const dv = new DataView(buf);
  if (dv.getUint32(0, true) !== 0x464c4d54) return;
  const n = dv.getUint32(8, true);
  if (!positions || n * 3 !== positions.array.length) return;
  const t = dv.getFloat64(16, true);
  const f = [dv.getFloat32(24, true), dv.getFloat32(28, true), dv.getFloat32(32, true)];
  const p = [dv.getFloat32(36, true), dv.getFloat32(40, true), dv.getFloat32(44, true)];
  positions.array.set(new Float32Array(buf, 48, 3 * n));
  positions.needsUpdate = true;
  geometry.computeVertexNormals();
  geometry.computeBoundingSphere();
  probeMesh.position.set(...p);
  if (!dragging && ghost.visible && probeMesh.position.distanceTo(target) < 0.02 * state.hello.probe_radius)
    ghost.visible = false;
  const fv = new THREE.Vector3(...f), fn = fv.length();
  arrow.position.copy(probeMesh.position);
  if (fn > 1e-6) {
    arrow.visible = true;
    arrow.setDirection(fv.clone().normalize());
    // From the centre: the probe's radius, then 0.25 mesh extents per newton.
    const len = state.hello.probe_radius + Math.min(0.5 * extent, 0.25 * extent * fn);
    arrow.setLength(len, Math.min(0.3 * len, 0.03 * extent), Math.min(0.2 * len, 0.015 * extent));
  } else {
    arrow.visible = false;
  }
  state.frames++;
  state.force = f;
  state.probe = p;
  state.t = t;
  const now = performance.now();
  frameTimes.push(now);
  while (frameTimes.length && frameTimes[0] < now - 2000) frameTimes.shift();
  state.fps = frameTimes.length > 1 ? (1000 * (frameTimes.length - 1)) / (frameTimes[frameTimes.length - 1] - frameTimes[0]) : 0;
  history.push([t, fn, f[0], f[1], f[2]]);
  while (history.length && history[0][0] < t - windowS) history.shift();
  panel.textContent =
    `${state.hello.case}  ·  ${state.fps.toFixed(1)} frames/s  ·  frame ${state.frames}\n` +
    `|F| = ${fn.toFixed(3)} N   F = (${f.map((v) => v.toFixed(3)).join(', ')}) N\n` +
    `probe (${p.map((v) => (1000 * v).toFixed(1)).join(', ')}) mm`;
  needsDraw = true;
}

// ---------------------------------------------------------------- drag the probe
const raycaster = new THREE.Raycaster();
const pointer = new THREE.Vector2();
let dragging = false, dragPlane = new THREE.Plane(), dragOffset = new THREE.Vector3();
let ws = null, lastSent = 0, pendingTarget = null;

function ndc(ev) {
  const r = renderer.domElement.getBoundingClientRect();
  pointer.set(((ev.clientX - r.left) / r.width) * 2 - 1, -((ev.clientY - r.top) / r.height) * 2 + 1);
  raycaster.setFromCamera(pointer, camera);
}
function sendProbe(x) {
  // The server clamps targets into the probe box; so does the page, so that a target pushed past
  // it comes back with the first notch or drag the other way.
  const box = state.hello.probe_box;
  x.clamp(new THREE.Vector3(...box.min), new THREE.Vector3(...box.max));
  target = x.clone();
  state.target = target.toArray();
  pendingTarget = x;
  const now = performance.now();
  if (now - lastSent < 8 || !ws || ws.readyState !== 1) return;  // at most ~120 messages/s
  ws.send(JSON.stringify({ type: 'probe', x: [x.x, x.y, x.z] }));
  lastSent = now;
  pendingTarget = null;
  state.moves++;
}
renderer.domElement.addEventListener('pointerdown', (ev) => {
  if (!probeMesh || ev.button !== 0) return;
  ndc(ev);
  if (raycaster.intersectObject(probeMesh).length === 0) return;
  dragging = true;
  controls.enabled = false;
  const normal = new THREE.Vector3();
  camera.getWorldDirection(normal);
  dragPlane.setFromNormalAndCoplanarPoint(normal, probeMesh.position);
  const hit = new THREE.Vector3();
  raycaster.ray.intersectPlane(dragPlane, hit);
  dragOffset.copy(probeMesh.position).sub(hit);
  ghost.position.copy(probeMesh.position);
  ghost.visible = true;
  renderer.domElement.setPointerCapture(ev.pointerId);
  ev.preventDefault();
  ev.stopImmediatePropagation();
}, { capture: true });
renderer.domElement.addEventListener('pointermove', (ev) => {
  if (!dragging) return;
  ndc(ev);
  const hit = new THREE.Vector3();
  if (!raycaster.ray.intersectPlane(dragPlane, hit)) return;
  hit.add(dragOffset);
  sendProbe(hit);
  ghost.position.copy(target);
  needsDraw = true;
});
function endDrag(ev) {
  if (!dragging) return;
  dragging = false;
  controls.enabled = true;
  ghost.visible = false;
  if (pendingTarget) { lastSent = 0; sendProbe(pendingTarget); }
  try { renderer.domElement.releasePointerCapture(ev.pointerId); } catch (_) { /* already released */ }
}
renderer.domElement.addEventListener('pointerup', endDrag);
renderer.domElement.addEventListener('pointercancel', endDrag);
window.addEventListener('keydown', (ev) => {
  if ((ev.key === 'r' || ev.key === 'R') && probeStart) {
    lastSent = 0;
    sendProbe(probeStart.clone());
    if (!dragging) ghost.visible = false;
  }
});

// Depth: the wheel while dragging the probe, or Shift+wheel at any time, moves the probe target
// along the view direction, a tenth of the probe radius per wheel notch: forward (away from you)
// presses it into what the camera looks at, backward pulls it out. The drag plane follows.
function wheelNotches(ev) {
  // Chromium turns Shift+wheel into a horizontal scroll on some systems: take whichever axis moved.
  const d = Math.abs(ev.deltaY) >= Math.abs(ev.deltaX) ? ev.deltaY : ev.deltaX;
  if (ev.deltaMode === 1) return d / 3;   // lines
  if (ev.deltaMode === 2) return d * 10;  // pages
  return d / 100;                         // pixels: 100 per notch
}
function pushProbe(notches) {
  const dir = new THREE.Vector3();
  camera.getWorldDirection(dir);
  const from = dragging ? ghost.position.clone() : target.clone();  // the ghost is the target in a drag
  const x = from.addScaledVector(dir, notches * 0.1 * state.hello.probe_radius);
  lastSent = 0;
  sendProbe(x);
  if (dragging) dragPlane.setFromNormalAndCoplanarPoint(dir, target);
  ghost.position.copy(target);
  ghost.visible = true;
  needsDraw = true;
}
renderer.domElement.addEventListener('wheel', (ev) => {
  if (!probeMesh || !target || !(dragging || ev.shiftKey)) return;  // otherwise: zoom (OrbitControls)
  ev.preventDefault();
  ev.stopImmediatePropagation();
  const n = wheelNotches(ev);
  if (n !== 0) pushProbe(-n);  // wheel forward (deltaY < 0): away from the camera
}, { capture: true, passive: false });
controls.addEventListener('change', () => (needsDraw = true));

// For the browser test: where a point of the mesh frame is on the page (CSS pixels).
state.worldToScreen = (x, y, z) => {
  const v = new THREE.Vector3(x, y, z).project(camera);
  const r = renderer.domElement.getBoundingClientRect();
  return { x: r.left + ((v.x + 1) / 2) * r.width, y: r.top + ((1 - v.y) / 2) * r.height };
};
state.probeScreen = () => (probeMesh ? state.worldToScreen(...probeMesh.position.toArray()) : null);
state.viewDirection = () => camera.getWorldDirection(new THREE.Vector3()).toArray();

// ---------------------------------------------------------------- connection and drawing
let needsDraw = true;
function connect() {
  ws = new WebSocket(`ws://${location.host}/ws`);
  ws.binaryType = 'arraybuffer';
  ws.onopen = () => { state.connected = true; };
  ws.onmessage = (m) => {
    if (typeof m.data === 'string') {
      const h = JSON.parse(m.data);
      if (h.type === 'hello' && !state.hello) onHello(h);
    } else {
      onFrame(m.data);
    }
  };
  ws.onclose = () => {
    state.connected = false;
    panel.textContent = 'disconnected: the tmlab run has ended (start it again and reload)';
  };
}
function draw() {
  requestAnimationFrame(draw);
  if (pendingTarget && performance.now() - lastSent >= 8) sendProbe(pendingTarget);
  if (!needsDraw || !geometry) return;
  needsDraw = false;
  renderer.render(scene, camera);
  drawPlot();
  state.rendered++;
}
connect();
draw();
