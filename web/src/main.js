// `nodus view`'s page: a run (and its branches) in 3D, with a step slider, play, colouring by fibre, by a
// node measure or by contact force, and picking. Everything it needs is in the page: the data (data.js)
// and this script, bundled with three.js by esbuild (web/build.mjs).

import {
  AmbientLight, Box3, Color, DirectionalLight, HemisphereLight, PerspectiveCamera, Raycaster, Scene, Vector2,
  Vector3, WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

import { CONTACT_RECORD, readPageData, runsOf } from './data.js';
import { RunView } from './scene.js';
import { buildUi } from './ui.js';

const BACKGROUND = 0xf4f5f7;

/// Whether WebGL runs on the CPU here.
function softwareRenderer() {
  try {
    const gl = document.createElement('canvas').getContext('webgl2');
    const info = gl && gl.getExtension('WEBGL_debug_renderer_info');
    const name = info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : '';
    gl?.getExtension('WEBGL_lose_context')?.loseContext();
    return /swiftshader|llvmpipe|software/i.test(name);
  } catch (e) {
    return false;
  }
}

function main() {
  const page = readPageData();
  const runs = runsOf(page);
  const ui = buildUi(document.body, page, runs);

  // On a software renderer (SwiftShader, llvmpipe: no GPU) antialiasing would make every frame several times
  // slower: it is left off there.
  const software = softwareRenderer();
  const renderer = new WebGLRenderer({ antialias: !software, preserveDrawingBuffer: true });
  renderer.setPixelRatio(software ? 1 : window.devicePixelRatio || 1);
  renderer.setClearColor(new Color(BACKGROUND));
  ui.viewport.appendChild(renderer.domElement);
  const scene = new Scene();
  const camera = new PerspectiveCamera(35, 1, 1e-3, 1e5);
  scene.add(new HemisphereLight(0xffffff, 0x8090a0, 1.4));
  scene.add(new AmbientLight(0xffffff, 0.25));
  const headlight = new DirectionalLight(0xffffff, 1.6);
  headlight.position.set(0.3, 0.6, 1);
  camera.add(headlight);
  scene.add(camera);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.enableDamping = false;

  let view = null;
  let run = null;
  let frameRequested = false;
  const render = () => {
    frameRequested = false;
    renderer.render(scene, camera);
  };
  const requestRender = () => {
    if (!frameRequested) {
      frameRequested = true;
      requestAnimationFrame(render);
    }
  };
  controls.addEventListener('change', requestRender);

  const resize = () => {
    const w = ui.viewport.clientWidth || 1, h = ui.viewport.clientHeight || 1;
    renderer.setSize(w, h, true);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    requestRender();
  };
  window.addEventListener('resize', resize);

  /// Frames `box`, looking across its longest side from a little above.
  const frameBox = (box) => {
    const centre = box.getCenter(new Vector3());
    const radius = Math.max(box.getSize(new Vector3()).length() / 2, 1e-6);
    const distance = radius / Math.sin((camera.fov * Math.PI) / 360) * 1.05;
    camera.near = distance / 1000;
    camera.far = distance * 100;
    const size = box.getSize(new Vector3()).toArray();
    const longest = size.indexOf(Math.max(...size));
    const direction = new Vector3(0.55, 0.6, 1).toArray();
    direction[longest] = 0.2;
    camera.position.copy(centre).add(new Vector3(...direction).normalize().multiplyScalar(distance));
    camera.updateProjectionMatrix();
    controls.target.copy(centre);
    controls.update();
  };
  /// The box of all the run's states (the quantisation ranges of the centres).
  const frame = () => frameBox(new Box3(
    new Vector3(...[0, 1, 2].map((c) => run.quant[c][0])),
    new Vector3(...[0, 1, 2].map((c) => run.quant[c][0] + 65535 * run.quant[c][1]))));
  /// The box of the drawn state's fibres (tools left out), the camera's direction kept.
  const frameState = () => {
    const box = new Box3();
    const p = new Vector3();
    const st = view.current;
    for (const beam of run.beams) {
      if (beam.tool) continue;
      for (let n = beam.first; n < beam.first + beam.count; n++) {
        box.expandByPoint(p.set(st.centre[3 * n], st.centre[3 * n + 1], st.centre[3 * n + 2]));
      }
    }
    if (box.isEmpty()) return;
    const centre = box.getCenter(new Vector3());
    const radius = Math.max(box.getSize(new Vector3()).length() / 2, 1e-6);
    const distance = radius / Math.sin((camera.fov * Math.PI) / 360) * 1.05;
    const direction = camera.position.clone().sub(controls.target).normalize();
    camera.position.copy(centre).addScaledVector(direction, distance);
    camera.near = distance / 1000;
    camera.far = distance * 100;
    camera.updateProjectionMatrix();
    controls.target.copy(centre);
    controls.update();
    requestRender();
  };

  const setState = (index) => {
    index = Math.max(0, Math.min(run.stateCount - 1, index | 0));
    view.setState(index);
    ui.showState(run, index);
    requestRender();
  };

  const setRun = (r) => {
    if (view) view.dispose();
    run = runs[r];
    view = new RunView(run, scene);
    ui.showRun(run);  // keeps the measure chosen where this run has it
    view.colorBy = ui.colorSelect.value;
    view.contactColorBy = ui.contactSelect.value;
    view.setSeeThrough(ui.seeThrough.checked);
    view.setContactsVisible(ui.contactToggle.checked);
    ui.showLegend(view);
    frame();
    setState(run.stateCount - 1);
  };

  // Play: one state per animation frame at most, about 20 states a second.
  let playing = null;
  const stop = () => {
    if (playing !== null) cancelAnimationFrame(playing);
    playing = null;
    ui.playButton.textContent = '\u25B6';
  };
  const play = () => {
    if (view.stateIndex >= run.stateCount - 1) setState(0);
    ui.playButton.textContent = '\u275A\u275A';
    let last = 0;
    const tick = (t) => {
      if (t - last >= 50) {
        last = t;
        if (view.stateIndex >= run.stateCount - 1) return stop();
        setState(view.stateIndex + 1);
      }
      playing = requestAnimationFrame(tick);
    };
    playing = requestAnimationFrame(tick);
  };

  ui.slider.addEventListener('input', () => setState(Number(ui.slider.value)));
  ui.playButton.addEventListener('click', () => (playing === null ? play() : stop()));
  ui.frameButton.addEventListener('click', frameState);
  ui.runSelect.addEventListener('change', () => {
    stop();
    setRun(Number(ui.runSelect.value));
  });
  ui.colorSelect.addEventListener('change', () => {
    view.colorBy = ui.colorSelect.value;
    view.updateTubes();
    ui.showLegend(view);
    requestRender();
  });
  ui.contactSelect.addEventListener('change', () => {
    view.contactColorBy = ui.contactSelect.value;
    view.updateContacts();
    ui.showLegend(view);
    requestRender();
  });
  ui.contactToggle.addEventListener('change', () => {
    view.setContactsVisible(ui.contactToggle.checked);
    ui.showLegend(view);
    requestRender();
  });
  ui.seeThrough.addEventListener('change', () => {
    view.setSeeThrough(ui.seeThrough.checked);
    requestRender();
  });

  // Picking: a click (a press and release without dragging) reads the fibre node or contact element under it.
  const raycaster = new Raycaster();
  const PICK_PIXELS = 8;
  const nearestContactOnScreen = (x, y, rect) => {
    const c = view.current.contacts;
    const count = view.contactMesh.count;
    const v = new Vector3();
    let best = null;
    let bestDistance = PICK_PIXELS;
    for (let e = 0; e < count; e++) {
      const r = e * CONTACT_RECORD;
      v.set((c[r] + c[r + 3]) / 2, (c[r + 1] + c[r + 4]) / 2, (c[r + 2] + c[r + 5]) / 2).project(camera);
      if (v.z > 1) continue;  // behind the camera
      const d = Math.hypot(((v.x + 1) / 2) * rect.width - x, ((1 - v.y) / 2) * rect.height - y);
      if (d < bestDistance) {
        bestDistance = d;
        best = { object: view.contactMesh, instanceId: e, distance: 0 };
      }
    }
    return best;
  };
  const pickAt = (clientX, clientY) => {
    const rect = renderer.domElement.getBoundingClientRect();
    const p = new Vector2(((clientX - rect.left) / rect.width) * 2 - 1, -((clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(p, camera);
    const targets = [...view.tubes];
    if (view.contactMesh && view.contactMesh.visible) targets.push(view.contactMesh);
    const hits = raycaster.intersectObjects(targets, false);
    // A contact element lies between the surfaces, mostly inside the tubes: it is taken when the ray meets
    // it within a fibre diameter behind the first surface it meets, or anywhere with see-through fibres.
    const reach = 2 * Math.max(...run.beams.map((b) => b.radius));
    let contact = hits.find((h) => h.object === view.contactMesh);
    // A contact element a few pixels across is hard to hit: with see-through fibres, the element whose middle
    // is drawn nearest the click, within PICK_PIXELS, is taken when the ray meets none.
    if (!contact && ui.seeThrough.checked && view.contactMesh && view.contactMesh.visible) {
      contact = nearestContactOnScreen(clientX - rect.left, clientY - rect.top, rect);
    }
    const hit = contact && (ui.seeThrough.checked || contact.distance <= hits[0].distance + reach) ? contact : hits[0];
    const info = hit ? view.describeHit(hit) : null;
    ui.showPick(info);
    return info;
  };
  let down = null;
  renderer.domElement.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
  renderer.domElement.addEventListener('pointerup', (e) => {
    if (down && Math.hypot(e.clientX - down[0], e.clientY - down[1]) < 4) pickAt(e.clientX, e.clientY);
    down = null;
  });
  window.addEventListener('keydown', (e) => {
    if (e.target && e.target.tagName === 'SELECT') return;
    if (e.key === ' ' && e.target === document.body) {
      e.preventDefault();
      ui.playButton.click();
    }
    if (e.key === 'f' && !e.ctrlKey && !e.metaKey) frameState();
  });

  setRun(0);
  resize();
  render();

  // For scripts and tests (tests/view/browser_test.mjs): the state of the page and a few of its actions.
  window.nodusView = {
    get runCount() { return runs.length; },
    get stateCount() { return run.stateCount; },
    get stateIndex() { return view.stateIndex; },
    get contactCount() { return view.contactMesh ? view.contactMesh.count : 0; },
    setState: (i) => { setState(i); render(); },
    setRun: (r) => { ui.runSelect.value = String(r); setRun(r); render(); },
    pickAt,
    frameState: () => { frameState(); render(); },
    camera,
    controls,
    render,
    /// Milliseconds to draw `count` states from the first, the drawing finished (gl.finish): the slider's pace.
    timeStates: (count) => {
      const gl = renderer.getContext();
      const shown = view.stateIndex;
      const start = performance.now();
      for (let i = 0; i < count; i++) {
        setState(i % run.stateCount);
        render();
        gl.finish();
      }
      const ms = (performance.now() - start) / count;
      setState(shown);
      render();
      return ms;
    },
    /// A screen point on node `node` of beam `beam` in the drawn state, for a test click.
    screenPointOfNode: (beam, node) => {
      const st = view.current;
      const n = run.beams[beam].first + node;
      const v = new Vector3(st.centre[3 * n], st.centre[3 * n + 1], st.centre[3 * n + 2]).project(camera);
      const rect = renderer.domElement.getBoundingClientRect();
      return [rect.left + ((v.x + 1) / 2) * rect.width, rect.top + ((1 - v.y) / 2) * rect.height];
    },
    /// A screen point on the middle of contact element `e` in the drawn state.
    screenPointOfContact: (e) => {
      const c = view.current.contacts;
      const r = e * CONTACT_RECORD;
      const v = new Vector3((c[r] + c[r + 3]) / 2, (c[r + 1] + c[r + 4]) / 2, (c[r + 2] + c[r + 5]) / 2).project(camera);
      const rect = renderer.domElement.getBoundingClientRect();
      return [rect.left + ((v.x + 1) / 2) * rect.width, rect.top + ((1 - v.y) / 2) * rect.height];
    },
    ready: true,
  };
  document.body.dataset.ready = 'true';
}

try {
  main();
} catch (error) {
  const p = document.createElement('pre');
  p.className = 'nodus-error';
  p.textContent = `nodus view: ${error && error.message ? error.message : error}`;
  document.body.appendChild(p);
  console.error(error);
}
