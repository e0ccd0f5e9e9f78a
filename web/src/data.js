// The run data embedded in the page by `nodus view` (src/nodus/output/view_page.cpp writes it; docs/view.md
// describes it): JSON in <script id="nodus-data">, with each state's nodes and contact elements as base64
// strings decoded here on demand, so that a page of hundreds of states keeps only the drawn one in memory.

/// Bytes of a base64 string.
export function decodeBase64(text) {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

/// The JSON document of the page.
export function readPageData(doc = document) {
  const element = doc.getElementById('nodus-data');
  if (!element) throw new Error('this page holds no nodus data (no <script id="nodus-data">)');
  return JSON.parse(element.textContent);
}

/// Values of contact-element record fields (Float32, `CONTACT_RECORD` per element; view_page.cpp).
export const CONTACT_RECORD = 16;
export const CONTACT_FIELD = {
  xi: 0, xj: 3, normal: 6, gap: 9, normalForce: 10, tangentialForce: 11, state: 12, beamI: 13, beamJ: 14, zone: 15,
};
export const CONTACT_STATES = ['open', 'stick', 'slip'];  // state codes 0, 1, 2; -1: no forces computed

/// One run (the main run or a branch) of the page, with accessors for its states.
export class RunData {
  constructor(json) {
    this.json = json;
    this.name = json.name;
    this.beams = json.beams;
    this.stages = json.stages;
    this.states = json.states;
    this.totalStates = json.state_count;  // before decimation to the page's size budget
    this.measures = json.measures;  // [{name, label, unit, channel}], channel into the node record
    this.quant = json.quant;        // per channel [lo, step]: value = lo + q * step
    this.nodeCount = json.node_count;
    this.channels = json.quant.length;
    this.contactRanges = json.contact_ranges;  // {normal_force: [lo, hi], tangential_force: [lo, hi]}
    this.cache = new Map();  // a few decoded states, for play and slider moves back and forth
  }

  get stateCount() {
    return this.states.length;
  }

  /// State `index` decoded: {centre, g1, g2: Float32Array(3 n), measures: [Float32Array(n)], contacts:
  /// Float32Array(CONTACT_RECORD m)}.
  state(index) {
    const cached = this.cache.get(index);
    if (cached) return cached;
    const n = this.nodeCount;
    const q = new Uint16Array(decodeBase64(this.json.nodes[index]).buffer);
    if (q.length !== n * this.channels) throw new Error(`state ${index}: ${q.length} values, expected ${n * this.channels}`);
    const channel = (c) => {
      const [lo, step] = this.quant[c];
      const out = new Float32Array(n);
      const base = c * n;
      for (let i = 0; i < n; i++) out[i] = lo + q[base + i] * step;
      return out;
    };
    const vector = (c0) => {
      const x = channel(c0), y = channel(c0 + 1), z = channel(c0 + 2);
      const out = new Float32Array(3 * n);
      for (let i = 0; i < n; i++) {
        out[3 * i] = x[i];
        out[3 * i + 1] = y[i];
        out[3 * i + 2] = z[i];
      }
      return out;
    };
    const decoded = {
      centre: vector(0),
      g1: vector(3),
      g2: vector(6),
      measures: this.measures.map((m) => channel(m.channel)),
      contacts: new Float32Array(decodeBase64(this.json.contacts[index]).buffer),
    };
    if (this.cache.size >= 8) this.cache.delete(this.cache.keys().next().value);
    this.cache.set(index, decoded);
    return decoded;
  }

  /// The beam that global node `node` belongs to, and its local index.
  beamOfNode(node) {
    for (let b = 0; b < this.beams.length; b++) {
      const beam = this.beams[b];
      if (node >= beam.first && node < beam.first + beam.count) return { beam: b, local: node - beam.first };
    }
    return null;
  }
}

/// The runs of the page: the main run, then its branches (a branch of a branch named "a/b").
export function runsOf(page) {
  return page.runs.map((r) => new RunData(r));
}
