// Colours: one per fibre, and the colour scales of the measures and contact forces.

// Viridis (perceptually uniform, for magnitudes) at 9 stops; matplotlib's values.
const VIRIDIS = [
  [0.267, 0.005, 0.329], [0.283, 0.141, 0.458], [0.254, 0.265, 0.530], [0.207, 0.372, 0.553],
  [0.164, 0.471, 0.558], [0.128, 0.567, 0.551], [0.135, 0.659, 0.518], [0.267, 0.749, 0.441],
  [0.478, 0.821, 0.318], [0.741, 0.873, 0.150], [0.993, 0.906, 0.144],
];
// Blue - white - red (for signed values: strain, stress), Moreland's cool-warm end points.
const COOLWARM = [[0.230, 0.299, 0.754], [0.865, 0.865, 0.865], [0.706, 0.016, 0.150]];

function interpolate(stops, t) {
  const x = Math.min(1, Math.max(0, Number.isFinite(t) ? t : 0)) * (stops.length - 1);
  const i = Math.min(stops.length - 2, Math.floor(x));
  const f = x - i;
  const a = stops[i], b = stops[i + 1];
  return [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f];
}

/// A colour scale over [lo, hi]: diverging (centred on 0) when the range holds both signs, else viridis.
export class ColorScale {
  constructor(lo, hi) {
    if (!(hi > lo)) hi = lo + 1e-12;
    this.diverging = lo < 0 && hi > 0;
    if (this.diverging) {
      const m = Math.max(-lo, hi);
      lo = -m;
      hi = m;
    }
    this.lo = lo;
    this.hi = hi;
  }
  /// [r, g, b] in 0..1 of value `v`.
  color(v) {
    const t = (v - this.lo) / (this.hi - this.lo);
    return interpolate(this.diverging ? COOLWARM : VIRIDIS, t);
  }
  /// A CSS linear-gradient of the scale, left (lo) to right (hi).
  cssGradient() {
    const stops = [];
    for (let i = 0; i <= 10; i++) {
      const [r, g, b] = interpolate(this.diverging ? COOLWARM : VIRIDIS, i / 10);
      stops.push(`rgb(${Math.round(r * 255)},${Math.round(g * 255)},${Math.round(b * 255)}) ${i * 10}%`);
    }
    return `linear-gradient(to right, ${stops.join(', ')})`;
  }
}

/// The colour of fibre `index` of `count`: hues spread by the golden angle, so neighbours differ.
export function fibreColor(index) {
  const h = (index * 0.618033988749895) % 1;
  return hslToRgb(h, 0.65, 0.55);
}

export const TOOL_COLOR = [0.62, 0.62, 0.62];
export const CONTACT_STATE_COLORS = {
  open: [0.75, 0.75, 0.75],
  stick: [0.15, 0.45, 0.95],
  slip: [0.98, 0.55, 0.05],
  none: [0.85, 0.2, 0.75],
};

function hslToRgb(h, s, l) {
  const f = (n) => {
    const k = (n + h * 12) % 12;
    const a = s * Math.min(l, 1 - l);
    return l - a * Math.max(-1, Math.min(k - 3, 9 - k, 1));
  };
  return [f(0), f(8), f(4)];
}

/// A number for the legend and the pick panel: 4 significant digits.
export function formatNumber(v) {
  if (!Number.isFinite(v)) return String(v);
  if (v === 0) return '0';
  const a = Math.abs(v);
  if (a >= 1e-3 && a < 1e5) return String(Number(v.toPrecision(4)));
  return v.toExponential(3);
}
