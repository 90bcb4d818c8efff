// Every channel on the bus with its type, rate and newest numbers (lcm-spy in the page); a click on a number plots it.
import { numericFields } from './fields.js';
import { el, nameEl } from './dom.js';

export class Channels {
  constructor(el, filter, plots) {
    this.el = el;
    this.filter = filter;
    this.plots = plots;
    this.rows = new Map(); // channel -> {div, head, body, open, type, hz}
    this.schema = null; // the messages' fields, from the server's hello
    filter.oninput = () => this.applyFilter();
    setInterval(() => this.refreshOpen(), 200);
  }

  // LCM's own self-test channel says nothing about the robot.
  static hidden(channel) {
    return channel.startsWith('LCM_SELF_TEST');
  }

  row(channel) {
    let r = this.rows.get(channel);
    if (r) return r;
    const div = document.createElement('div');
    div.className = 'channel';
    div.dataset.channel = channel;
    const head = document.createElement('div');
    head.className = 'channel-head';
    const body = document.createElement('div');
    body.className = 'channel-fields';
    body.hidden = true;
    div.append(head, body);
    r = { div, head, body, open: false, type: '', hz: 0, msg: null };
    head.onclick = () => {
      r.open = !r.open;
      body.hidden = !r.open;
      this.renderFields(channel, r);
    };
    this.rows.set(channel, r);
    const sorted = [...this.rows.keys()].sort();
    const next = sorted[sorted.indexOf(channel) + 1];
    this.el.insertBefore(div, next ? this.rows.get(next).div : null);
    this.applyFilter();
    this.renderHead(channel, r);
    return r;
  }

  renderHead(channel, r) {
    r.head.replaceChildren(nameEl('span', 'name', channel), nameEl('span', 'type', r.type),
      el('span', { class: 'hz' }, `${r.hz.toFixed(1)} Hz`));
  }

  message(channel, type, msg) {
    if (Channels.hidden(channel)) return;
    const r = this.row(channel);
    if (r.type !== type) {
      r.type = type;
      this.renderHead(channel, r);
    }
    r.msg = msg;
    r.changed = true;
  }

  rates(list) {
    for (const c of list) {
      if (Channels.hidden(c.channel)) continue;
      const r = this.row(c.channel);
      r.hz = c.hz;
      this.renderHead(c.channel, r);
    }
  }

  refreshOpen() {
    for (const [channel, r] of this.rows) if (r.open && r.changed) this.renderFields(channel, r);
  }

  setSchema(schema) {
    this.schema = schema;
    for (const r of this.rows.values()) {
      r.body.innerHTML = '';
      r.changed = true;
    }
  }

  renderFields(channel, r) {
    r.changed = false;
    if (!r.open || !r.msg) return;
    const fields = numericFields(r.msg, this.schema, r.type);
    if (r.body.childElementCount !== fields.length) {
      r.body.innerHTML = '';
      for (const f of fields) {
        const line = document.createElement('div');
        line.className = 'field';
        line.dataset.path = f.path;
        line.append(nameEl('span', 'label', f.label), el('span', { class: 'value' }));
        line.onclick = () => {
          this.plots.toggle(channel, f.path, f.label);
          line.classList.toggle('plotted', this.plots.has(channel, f.path));
        };
        r.body.appendChild(line);
      }
    }
    fields.forEach((f, k) => {
      const line = r.body.children[k];
      line.querySelector('.value').textContent = Number.isInteger(f.value) ? String(f.value) : f.value.toFixed(4);
      line.classList.toggle('plotted', this.plots.has(channel, f.path));
    });
  }

  applyFilter() {
    const q = this.filter.value.trim();
    for (const [channel, r] of this.rows) r.div.hidden = q !== '' && !channel.includes(q);
  }
}
