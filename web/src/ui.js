// The page's controls around the 3D view: run (branch) selector, colour selectors, legend, step slider with
// the stages marked, play button, and the panel of the picked fibre node or contact element.

import { CONTACT_STATE_COLORS, formatNumber } from './colors.js';

const CSS = `
html, body { margin: 0; height: 100%; overflow: hidden; font: 13px/1.35 system-ui, sans-serif; color: #1d2330; }
#nodus-viewport { position: absolute; inset: 0 0 64px 0; }
#nodus-viewport canvas { display: block; width: 100%; height: 100%; }
.nodus-panel { position: absolute; background: rgba(255,255,255,0.92); border: 1px solid #d0d4dc;
  border-radius: 6px; padding: 8px 10px; box-shadow: 0 1px 4px rgba(0,0,0,0.08); }
#nodus-controls { top: 8px; left: 8px; width: 290px; }
#nodus-controls h1 { font-size: 14px; margin: 0 0 6px 0; overflow-wrap: anywhere; }
#nodus-controls label { display: block; margin: 4px 0; }
#nodus-controls select { width: 100%; }
#nodus-legend { margin-top: 6px; }
#nodus-note { margin-top: 6px; color: #6a7385; }
.nodus-bar { height: 12px; border: 1px solid #bbb; }
.nodus-ticks { display: flex; justify-content: space-between; font-variant-numeric: tabular-nums; }
.nodus-swatch { display: inline-block; width: 10px; height: 10px; margin: 0 4px 0 8px; border: 1px solid #888; }
#nodus-pick { top: 8px; right: 8px; width: 320px; display: none; font-variant-numeric: tabular-nums; }
#nodus-pick table { border-collapse: collapse; width: 100%; }
#nodus-pick td { padding: 0 4px; vertical-align: top; }
#nodus-pick td:last-child { text-align: right; white-space: nowrap; }
#nodus-timeline { position: absolute; left: 0; right: 0; bottom: 0; height: 64px; background: #fff;
  border-top: 1px solid #d0d4dc; display: flex; align-items: flex-start; gap: 10px; padding: 6px 10px;
  box-sizing: border-box; }
#nodus-play, #nodus-frame { width: 36px; height: 28px; font-size: 14px; cursor: pointer; }
#nodus-track { position: relative; flex: 1; }
#nodus-slider { width: 100%; margin: 6px 0 0 0; }
#nodus-stages { position: relative; height: 22px; }
.nodus-stage { position: absolute; top: 0; border-left: 1px solid #6a7385; padding-left: 3px; font-size: 11px;
  color: #4a5365; white-space: nowrap; overflow: hidden; }
.nodus-stage-end { border-left: none; border-right: 1px solid #6a7385; padding: 0 3px 0 0; }
#nodus-step { width: 250px; font-variant-numeric: tabular-nums; padding-top: 6px; }
.nodus-error { position: absolute; top: 40%; left: 10%; right: 10%; color: #a00; font-size: 15px; }
`;

const fibreCount = (run) => {
  const n = run.beams.filter((b) => !b.tool).length;
  return n === 1 ? '1 fibre' : `${n} fibres`;
};

function element(tag, attributes = {}, parent = null) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes)) {
    if (k === 'text') e.textContent = v;
    else e.setAttribute(k, v);
  }
  if (parent) parent.appendChild(e);
  return e;
}

/// Builds the page's controls in `body`; returns them and the functions that fill them.
export function buildUi(body, page, runs) {
  element('style', { text: CSS }, document.head);
  document.title = `nodus view: ${page.title}`;
  const viewport = element('div', { id: 'nodus-viewport' }, body);

  const controls = element('div', { id: 'nodus-controls', class: 'nodus-panel' }, body);
  element('h1', { text: page.title }, controls);
  const runLabel = element('label', { text: 'Run ' }, controls);
  const runSelect = element('select', { id: 'nodus-run' }, runLabel);
  runs.forEach((r, i) => element('option', { value: String(i), text: r.name }, runSelect));
  if (runs.length < 2) runLabel.style.display = 'none';
  const colorLabel = element('label', { text: 'Fibres coloured by ' }, controls);
  const colorSelect = element('select', { id: 'nodus-color' }, colorLabel);
  const contactLabel = element('label', {}, controls);
  const contactToggle = element('input', { type: 'checkbox', id: 'nodus-contacts-on', checked: '' }, contactLabel);
  contactLabel.appendChild(document.createTextNode(' contact elements coloured by '));
  const contactSelect = element('select', { id: 'nodus-contact-color' }, contactLabel);
  for (const [value, text] of [['normal_force', 'normal force R_N [N]'], ['tangential_force', 'friction force |T| [N]'],
    ['state', 'stick / slip / open']]) {
    element('option', { value, text }, contactSelect);
  }
  const seeLabel = element('label', {}, controls);
  const seeThrough = element('input', { type: 'checkbox', id: 'nodus-see-through' }, seeLabel);
  seeLabel.appendChild(document.createTextNode(' see-through fibres'));
  const legend = element('div', { id: 'nodus-legend' }, controls);
  const note = element('div', { id: 'nodus-note' }, controls);

  const pick = element('div', { id: 'nodus-pick', class: 'nodus-panel' }, body);

  const timeline = element('div', { id: 'nodus-timeline' }, body);
  const playButton = element('button', { id: 'nodus-play', title: 'play / pause (space)', text: '\u25B6' }, timeline);
  const frameButton = element('button', { id: 'nodus-frame', title: 'frame the fibres of this state (f)', text: '\u2922' }, timeline);
  const track = element('div', { id: 'nodus-track' }, timeline);
  const slider = element('input', { id: 'nodus-slider', type: 'range', min: '0', max: '0', step: '1', value: '0' }, track);
  const stageMarks = element('div', { id: 'nodus-stages' }, track);
  const stepLabel = element('div', { id: 'nodus-step' }, timeline);

  const showRun = (run) => {
    const chosen = colorSelect.value;
    colorSelect.replaceChildren();
    element('option', { value: 'fibre', text: 'fibre' }, colorSelect);
    for (const m of run.measures) element('option', { value: m.name, text: `${m.label} [${m.unit}]` }, colorSelect);
    if (run.measures.some((m) => m.name === chosen)) colorSelect.value = chosen;
    const hasContacts = run.states.some((s) => s.contacts > 0);
    contactLabel.style.display = hasContacts ? '' : 'none';
    note.textContent = run.stateCount < run.totalStates
      ? `${run.stateCount} of the run's ${run.totalStates} states, evenly spread (the page's size budget)` : '';
    slider.max = String(run.stateCount - 1);
    // A mark where each stage's first state is, named after the stage.
    stageMarks.replaceChildren();
    const last = Math.max(1, run.stateCount - 1);
    let previous = null;
    run.states.forEach((s, i) => {
      if (s.stage === previous) return;
      previous = s.stage;
      const mark = element('div', { class: 'nodus-stage', text: s.stage, title: `stage ${s.stage} from state ${i}` }, stageMarks);
      mark.style.left = `${(100 * i) / last}%`;
    });
    // Each mark as wide as the room up to the next one; a stage that begins near the end is named to the
    // left of its mark.
    const marks = [...stageMarks.children];
    marks.forEach((m, k) => {
      const left = parseFloat(m.style.left);
      const right = k + 1 < marks.length ? parseFloat(marks[k + 1].style.left) : 100;
      if (right - left < 12 && k + 1 === marks.length) {
        m.classList.add('nodus-stage-end');
        m.style.left = '';
        m.style.right = `${100 - left}%`;
      } else {
        m.style.maxWidth = `calc(${right - left}% - 4px)`;
      }
    });
    pick.style.display = 'none';
  };

  const showState = (run, index) => {
    slider.value = String(index);
    const s = run.states[index];
    stepLabel.textContent = `state ${index + 1}/${run.stateCount}: step ${s.step}, t = ${formatNumber(s.time)} s, ` +
      `stage ${s.stage}` + (s.contacts ? `, ${s.contacts} contact elements` : '');
  };

  const legendBar = (title, scale) => {
    const box = element('div', {}, legend);
    element('div', { text: title }, box);
    const bar = element('div', { class: 'nodus-bar' }, box);
    bar.style.background = scale.cssGradient();
    const ticks = element('div', { class: 'nodus-ticks' }, box);
    for (const v of [scale.lo, (scale.lo + scale.hi) / 2, scale.hi]) element('span', { text: formatNumber(v) }, ticks);
  };

  const showLegend = (view) => {
    legend.replaceChildren();
    const scaled = view.measureScale(view.colorBy);
    if (scaled) legendBar(`${scaled.measure.label} [${scaled.measure.unit}]`, scaled.scale);
    else element('div', { text: `${fibreCount(view.run)}, one colour each` +
      (view.run.beams.some((b) => b.tool) ? '; tools grey' : '') }, legend);
    if (view.contactMesh && contactToggle.checked) {
      const scale = view.contactScale();
      if (scale) {
        legendBar(view.contactColorBy === 'normal_force' ? 'contact normal force R_N [N]' : 'contact friction force |T| [N]', scale);
      } else {
        const box = element('div', {}, legend);
        for (const k of ['stick', 'slip', 'open']) {
          const sw = element('span', { class: 'nodus-swatch' }, box);
          const [r, g, b] = CONTACT_STATE_COLORS[k];
          sw.style.background = `rgb(${r * 255},${g * 255},${b * 255})`;
          box.appendChild(document.createTextNode(k));
        }
      }
    }
  };

  const showPick = (info) => {
    if (!info) {
      pick.style.display = 'none';
      return;
    }
    pick.style.display = 'block';
    pick.replaceChildren();
    const table = element('table', {}, pick);
    const row = (k, v) => {
      const tr = element('tr', {}, table);
      element('td', { text: k }, tr);
      element('td', { text: typeof v === 'number' ? formatNumber(v) : v }, tr);
    };
    if (info.kind === 'beam') {
      row(info.tool ? 'tool' : 'fibre', info.beam);
      row('node', `${info.node} (global ${info.globalNode})`);
      row('x, y, z [mm]', info.centre.map(formatNumber).join(', '));
      const run = runs[Number(runSelect.value)];
      for (const m of run.measures) row(`${m.label} [${m.unit}]`, info.values[m.name]);
    } else {
      row('contact element', String(info.element));
      row('zone', String(info.zone));
      row('beams', `${info.beamI} / ${info.beamJ}`);
      row('gap [mm]', info.gap);
      row('normal force R_N [N]', info.normalForce);
      row('friction force |T| [N]', info.tangentialForce);
      row('state', info.state);
    }
    pick.dataset.kind = info.kind;
  };

  return {
    viewport, runSelect, colorSelect, contactSelect, contactToggle, seeThrough, playButton, frameButton, slider, showRun, showState,
    showLegend, showPick,
  };
}
