// Live plots of any numeric field, PlotJuggler-style: click a field to add it, a time window, pause and clear.
import uPlot from 'uplot';
import { valueAt } from './fields.js';

const COLORS = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf'];
const MAX_POINTS = 20000;

export class Plots {
  constructor(el, controls) {
    this.el = el;
    this.series = []; // {channel, path, label}
    this.xs = [];
    this.ys = [];
    this.windowS = Number(controls.window.value);
    this.paused = false;
    this.t0 = null;
    this.dirty = false;
    this.controls = controls;
    controls.window.onchange = () => {
      this.windowS = Number(controls.window.value);
      this.dirty = true;
    };
    controls.pause.onclick = () => {
      this.paused = !this.paused;
      controls.pause.textContent = this.paused ? 'Resume' : 'Pause';
    };
    controls.clear.onclick = () => {
      this.series = [];
      this.xs = [];
      this.ys = [];
      this.rebuild();
    };
    new ResizeObserver(() => this.resize()).observe(el);
    this.rebuild();
    const frame = () => {
      if (this.dirty && !this.paused) this.redraw();
      requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
  }

  has(channel, path) {
    return this.series.some((s) => s.channel === channel && s.path === path);
  }

  toggle(channel, path, label) {
    const k = this.series.findIndex((s) => s.channel === channel && s.path === path);
    if (k >= 0) {
      this.series.splice(k, 1);
      this.ys.splice(k, 1);
    } else {
      this.series.push({ channel, path, label: `${channel} ${label}` });
      this.ys.push(this.xs.map(() => null));
    }
    this.rebuild();
  }

  // One message: a point for every series of its channel (the other series get a gap).
  add(channel, msg, t) {
    if (!this.series.some((s) => s.channel === channel)) return;
    if (this.t0 === null) this.t0 = t;
    this.xs.push(t - this.t0);
    this.series.forEach((s, k) => this.ys[k].push(s.channel === channel ? valueAt(msg, s.path) ?? null : null));
    if (this.xs.length > MAX_POINTS) {
      this.xs.shift();
      this.ys.forEach((y) => y.shift());
    }
    this.dirty = true;
  }

  points() {
    return this.xs.length;
  }

  rebuild() {
    if (this.plot) this.plot.destroy();
    this.controls.series.textContent = this.series.length ? '' : 'no field yet: click a number under Channels';
    const size = this.size();
    this.plot = new uPlot(
      {
        width: size.width,
        height: size.height,
        scales: { x: { time: false } },
        axes: [{ label: 's' }, {}],
        legend: { live: true },
        series: [{ label: 't' }, ...this.series.map((s, k) => ({ label: s.label, stroke: COLORS[k % COLORS.length], width: 1.5, spanGaps: true }))],
      },
      [this.xs, ...this.ys],
      this.el,
    );
    this.dirty = true;
  }

  redraw() {
    this.dirty = false;
    const end = this.xs.length ? this.xs[this.xs.length - 1] : 0;
    this.plot.setData([this.xs, ...this.ys], false);
    this.plot.setScale('x', { min: Math.max(0, end - this.windowS), max: Math.max(this.windowS, end) });
  }

  size() {
    const r = this.el.getBoundingClientRect();
    return { width: Math.max(200, r.width - 10), height: Math.max(120, r.height - 70) };
  }

  resize() {
    if (this.plot) this.plot.setSize(this.size());
  }
}
