// The 3D objects of one run: a tube per beam, built as the VTK tubes are (docs/output.md: at every node a
// ring r + R (cos phi g1 + sin phi g2) of the current, unnormalised directors), and the contact elements as
// thin cylinders from x_i to x_j. The buffers are made once per run and rewritten in place for each state.

import {
  BufferAttribute, BufferGeometry, Color, CylinderGeometry, DoubleSide, DynamicDrawUsage, InstancedMesh,
  Matrix4, Mesh, MeshStandardMaterial, Quaternion, Vector3,
} from 'three';

import { CONTACT_FIELD, CONTACT_RECORD, CONTACT_STATES } from './data.js';
import { CONTACT_STATE_COLORS, ColorScale, TOOL_COLOR, fibreColor } from './colors.js';

/// Tubes and contact elements of a run, updated by setState.
export class RunView {
  /// `run`: a RunData; `scene`: the three.js scene they are added to.
  constructor(run, scene) {
    this.run = run;
    this.scene = scene;
    // Fewer sides for large models keep the vertex count (and the per-state update) bounded.
    this.sides = run.nodeCount > 6000 ? 8 : 12;
    this.cos = new Float32Array(this.sides);
    this.sin = new Float32Array(this.sides);
    for (let j = 0; j < this.sides; j++) {
      this.cos[j] = Math.cos((2 * Math.PI * j) / this.sides);
      this.sin[j] = Math.sin((2 * Math.PI * j) / this.sides);
    }
    this.tubes = run.beams.map((beam, b) => this.makeTube(beam, b));
    this.maxContacts = Math.max(0, ...run.states.map((s) => s.contacts));
    this.contactMesh = this.maxContacts > 0 ? this.makeContacts() : null;
    this.colorBy = 'fibre';
    this.contactColorBy = 'normal_force';
    this.stateIndex = -1;
    this.current = null;
  }

  makeTube(beam, b) {
    const m = beam.count, S = this.sides;
    const geometry = new BufferGeometry();
    const position = new BufferAttribute(new Float32Array(3 * m * S), 3);
    const normal = new BufferAttribute(new Float32Array(3 * m * S), 3);
    const color = new BufferAttribute(new Float32Array(3 * m * S), 3);
    for (const a of [position, normal, color]) a.setUsage(DynamicDrawUsage);
    geometry.setAttribute('position', position);
    geometry.setAttribute('normal', normal);
    geometry.setAttribute('color', color);
    const index = [];
    for (let i = 0; i + 1 < m; i++) {
      for (let j = 0; j < S; j++) {
        const a = i * S + j, c = (i + 1) * S + j;
        const bb = i * S + ((j + 1) % S), d = (i + 1) * S + ((j + 1) % S);
        index.push(a, bb, d, a, d, c);  // outward normals for g1 x g2 along the axis
      }
    }
    geometry.setIndex(index);
    const material = new MeshStandardMaterial({
      vertexColors: true, side: DoubleSide, roughness: 0.55, metalness: 0.05,
      transparent: beam.tool, opacity: beam.tool ? 0.45 : 1, depthWrite: !beam.tool,
    });
    const mesh = new Mesh(geometry, material);
    mesh.frustumCulled = false;  // the bounding sphere would go stale as the nodes move
    mesh.userData = { kind: 'beam', beam: b };
    this.scene.add(mesh);
    return mesh;
  }

  makeContacts() {
    const radius = Math.min(...this.run.beams.filter((b) => !b.tool).map((b) => b.radius).concat([Infinity]));
    const R = Number.isFinite(radius) ? radius : this.run.beams[0].radius;
    this.contactRadius = 0.3 * R;
    this.contactReach = 0.5 * R;
    const geometry = new CylinderGeometry(1, 1, 1, 8, 1, false).translate(0, 0.5, 0);
    const material = new MeshStandardMaterial({ roughness: 0.4, metalness: 0.0 });
    const mesh = new InstancedMesh(geometry, material, this.maxContacts);
    mesh.instanceMatrix.setUsage(DynamicDrawUsage);
    mesh.setColorAt(0, new Color(0, 0, 0));
    mesh.instanceColor.setUsage(DynamicDrawUsage);
    mesh.count = 0;
    mesh.frustumCulled = false;
    mesh.userData = { kind: 'contact' };
    this.scene.add(mesh);
    return mesh;
  }

  dispose() {
    for (const mesh of [...this.tubes, this.contactMesh]) {
      if (!mesh) continue;
      this.scene.remove(mesh);
      mesh.geometry.dispose();
      mesh.material.dispose();
    }
  }

  /// The measure drawn ('fibre' or a measure name) and its colour scale (null for 'fibre').
  measureScale(name) {
    const m = this.run.measures.find((x) => x.name === name);
    if (!m) return null;
    return { measure: m, scale: new ColorScale(m.range[0], m.range[1]) };
  }

  contactScale() {
    const key = this.contactColorBy;
    if (key === 'state') return null;
    const range = this.run.contactRanges[key] || [0, 1];
    return new ColorScale(Math.min(0, range[0]), Math.max(range[1], 1e-12));
  }

  /// Draws state `index`.
  setState(index) {
    this.stateIndex = index;
    this.current = this.run.state(index);
    this.updateTubes();
    this.updateContacts();
  }

  updateTubes() {
    const st = this.current;
    if (!st) return;
    const S = this.sides;
    const scaled = this.measureScale(this.colorBy);
    const values = scaled ? st.measures[this.run.measures.indexOf(scaled.measure)] : null;
    this.run.beams.forEach((beam, b) => {
      const mesh = this.tubes[b];
      const pos = mesh.geometry.attributes.position.array;
      const nor = mesh.geometry.attributes.normal.array;
      const col = mesh.geometry.attributes.color.array;
      const R = beam.radius;
      const fixed = beam.tool ? TOOL_COLOR : fibreColor(b);
      for (let i = 0; i < beam.count; i++) {
        const n = beam.first + i;
        const cx = st.centre[3 * n], cy = st.centre[3 * n + 1], cz = st.centre[3 * n + 2];
        const ax = st.g1[3 * n], ay = st.g1[3 * n + 1], az = st.g1[3 * n + 2];
        const bx = st.g2[3 * n], by = st.g2[3 * n + 1], bz = st.g2[3 * n + 2];
        const rgb = values && !beam.tool ? scaled.scale.color(values[n]) : fixed;
        for (let j = 0; j < S; j++) {
          const k = 3 * (i * S + j);
          const dx = this.cos[j] * ax + this.sin[j] * bx;
          const dy = this.cos[j] * ay + this.sin[j] * by;
          const dz = this.cos[j] * az + this.sin[j] * bz;
          pos[k] = cx + R * dx;
          pos[k + 1] = cy + R * dy;
          pos[k + 2] = cz + R * dz;
          const len = Math.hypot(dx, dy, dz) || 1;
          nor[k] = dx / len;
          nor[k + 1] = dy / len;
          nor[k + 2] = dz / len;
          col[k] = rgb[0];
          col[k + 1] = rgb[1];
          col[k + 2] = rgb[2];
        }
      }
      mesh.geometry.attributes.position.needsUpdate = true;
      mesh.geometry.attributes.normal.needsUpdate = true;
      mesh.geometry.attributes.color.needsUpdate = true;
    });
  }

  updateContacts() {
    const mesh = this.contactMesh;
    if (!mesh || !this.current) return;
    const c = this.current.contacts;
    const count = c.length / CONTACT_RECORD;
    const scale = this.contactScale();
    const matrix = new Matrix4(), q = new Quaternion(), up = new Vector3(0, 1, 0);
    const a = new Vector3(), d = new Vector3(), s = new Vector3(), color = new Color();
    const n = new Vector3();
    const reach = this.contactReach;
    for (let e = 0; e < count; e++) {
      const r = e * CONTACT_RECORD;
      // The segment x_i -> x_j, lengthened by `reach` into each beam along the normal: the particles sit on
      // the two surfaces, often a few micrometres apart, and the bare segment would not show.
      n.set(c[r + CONTACT_FIELD.normal], c[r + CONTACT_FIELD.normal + 1], c[r + CONTACT_FIELD.normal + 2]);
      a.set(c[r + CONTACT_FIELD.xi], c[r + CONTACT_FIELD.xi + 1], c[r + CONTACT_FIELD.xi + 2]);
      d.set(c[r + CONTACT_FIELD.xj] - a.x, c[r + CONTACT_FIELD.xj + 1] - a.y, c[r + CONTACT_FIELD.xj + 2] - a.z);
      if (n.lengthSq() === 0) n.copy(d);
      if (n.lengthSq() === 0) n.set(0, 0, 1);
      n.normalize();
      const along = d.dot(n);  // the gap
      a.addScaledVector(n, -reach);
      const length = Math.max(along + 2 * reach, 1e-9);
      q.setFromUnitVectors(up, n);
      s.set(this.contactRadius, length, this.contactRadius);
      matrix.compose(a, q, s);
      mesh.setMatrixAt(e, matrix);
      // Elements of a state without contact forces (NaN forces, state -1) in the colour of `none`.
      const code = c[r + CONTACT_FIELD.state];
      const key = this.contactColorBy === 'normal_force' ? CONTACT_FIELD.normalForce : CONTACT_FIELD.tangentialForce;
      let rgb;
      if (code < 0) rgb = CONTACT_STATE_COLORS.none;
      else if (!scale) rgb = CONTACT_STATE_COLORS[CONTACT_STATES[code]];
      else rgb = scale.color(c[r + key]);
      mesh.setColorAt(e, color.setRGB(rgb[0], rgb[1], rgb[2]));
    }
    mesh.count = count;
    mesh.instanceMatrix.needsUpdate = true;
    mesh.instanceColor.needsUpdate = true;
  }

  /// Fibres drawn see-through, to show the contact elements between them.
  setSeeThrough(on) {
    this.run.beams.forEach((beam, b) => {
      const m = this.tubes[b].material;
      m.transparent = beam.tool || on;
      m.opacity = beam.tool ? 0.45 : on ? 0.35 : 1;
      m.depthWrite = !m.transparent;
      m.needsUpdate = true;
    });
  }

  setContactsVisible(visible) {
    if (this.contactMesh) this.contactMesh.visible = visible;
  }

  /// Values at a picked point: {kind: 'beam', ...} or {kind: 'contact', ...}, for the info panel.
  describeHit(hit) {
    const st = this.current;
    if (hit.object.userData.kind === 'beam') {
      const b = hit.object.userData.beam;
      const beam = this.run.beams[b];
      // The face's first vertex lies on ring i = vertex / sides: the nearer of that ring and the next.
      const v = hit.face ? hit.face.a : 0;
      let local = Math.floor(v / this.sides);
      const n0 = beam.first + local;
      if (local + 1 < beam.count) {
        const dist = (n) => Math.hypot(st.centre[3 * n] - hit.point.x, st.centre[3 * n + 1] - hit.point.y,
          st.centre[3 * n + 2] - hit.point.z);
        if (dist(n0 + 1) < dist(n0)) local += 1;
      }
      const node = beam.first + local;
      const values = {};
      this.run.measures.forEach((m, k) => { values[m.name] = st.measures[k][node]; });
      return {
        kind: 'beam', beam: beam.name, beamIndex: b, tool: beam.tool, node: local, globalNode: node,
        centre: [st.centre[3 * node], st.centre[3 * node + 1], st.centre[3 * node + 2]], values,
      };
    }
    const e = hit.instanceId;
    const r = e * CONTACT_RECORD;
    const c = st.contacts;
    const code = c[r + CONTACT_FIELD.state];
    return {
      kind: 'contact', element: e, zone: c[r + CONTACT_FIELD.zone],
      beamI: this.run.beams[c[r + CONTACT_FIELD.beamI]].name, beamJ: this.run.beams[c[r + CONTACT_FIELD.beamJ]].name,
      gap: c[r + CONTACT_FIELD.gap], normalForce: c[r + CONTACT_FIELD.normalForce],
      tangentialForce: c[r + CONTACT_FIELD.tangentialForce], state: code >= 0 ? CONTACT_STATES[code] : 'no forces',
    };
  }
}
