// The controller manager's controllers (rqt_controller_manager): state, claimed joints, start/stop, a switch.
import { kTitleChars, shown } from './dom.js';

export class Controllers {
  constructor(conn, table, switchButton, message, loadName, loadButton) {
    this.conn = conn;
    this.body = table.querySelector('tbody');
    this.message = message;
    this.list = [];
    this.ok = null;
    this.onChange = [];
    loadButton.onclick = () => {
      const name = loadName.value.trim();
      if (name) this.call({ call: 'load', names: [name] });
    };
    switchButton.onclick = () => {
      const checked = [...this.body.querySelectorAll('input[type=checkbox]:checked')].map((c) => c.dataset.name);
      const running = new Set(this.list.filter((c) => c.state === 'running').map((c) => c.name));
      const stop = checked.filter((n) => running.has(n));
      const start = checked.filter((n) => !running.has(n));
      if (start.length || stop.length) this.call({ call: 'switch', start, stop, strict: true });
    };
  }

  async call(body) {
    this.message.textContent = shown(`${body.call} ${[...(body.start || []), ...(body.stop || []), ...(body.names || [])].join(', ')} ...`);
    const r = await this.conn.request({ op: 'cm', ...body });
    this.message.textContent = shown(r.message);
    this.message.className = r.ok ? 'message' : 'message error';
  }

  update(frame) {
    this.ok = frame.ok;
    if (!frame.ok) return;
    const key = JSON.stringify(frame.controllers);
    if (key === this.key) return;
    this.key = key;
    this.list = frame.controllers;
    this.body.innerHTML = '';
    for (const c of this.list) {
      const tr = document.createElement('tr');
      tr.dataset.controller = c.name;
      tr.className = c.state;
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.dataset.name = c.name;
      const action = document.createElement('button');
      const running = c.state === 'running';
      action.textContent = running ? 'Stop' : 'Start';
      action.className = running ? 'stop' : 'start';
      action.onclick = () => this.call(running ? { call: 'switch', stop: [c.name] } : { call: 'switch', start: [c.name] });
      const actions = document.createElement('span');
      actions.append(action);
      if (!running) {
        const unload = document.createElement('button');
        unload.textContent = '✕';
        unload.title = shown(`unload ${c.name}`);
        unload.onclick = () => this.call({ call: 'unload', names: [c.name] });
        actions.append(unload);
      }
      const type = document.createElement('span');
      type.textContent = shown(c.type.split('/').pop());
      const timing = document.createElement('span');
      timing.className = 'timing';
      const cells = [box, c.name, type, c.state, c.joints.join(' '), timing, actions];
      for (const cell of cells) {
        const td = document.createElement('td');
        if (typeof cell === 'string') td.textContent = shown(cell);
        else td.appendChild(cell);
        td.title = shown(cell === type ? c.type : typeof cell === 'string' ? cell : td.textContent, kTitleChars);
        tr.appendChild(td);
      }
      this.body.appendChild(tr);
    }
    for (const fn of this.onChange) fn(this.list);
    if (this.stats) this.timing(this.stats);
  }

  // controller_manager/statistics: each running controller's execution time (p99) and period (mean), in µs.
  timing(stats) {
    this.stats = stats;
    const f = (x) => (Number.isFinite(x) && x > 0 ? x.toFixed(x < 10 ? 1 : 0) : '–');
    for (let k = 0; k < (stats.item || []).length; ++k) {
      const row = [...this.body.children].find((tr) => tr.dataset.controller === stats.item[k]);
      const cell = row?.querySelector('.timing');
      if (!cell) continue;
      const updates = stats.item_count ? stats.item_count[k] : 0;
      cell.textContent = updates ? `${f(stats.item_exec_p99_us[k])} / ${f(stats.item_period_mean_us[k])}` : '';
      cell.title = updates
        ? `${updates} updates: execution ${f(stats.item_exec_mean_us[k])} mean, ${f(stats.item_exec_p99_us[k])} p99, ${f(stats.item_exec_max_us[k])} max; period ${f(stats.item_period_mean_us[k])} mean, ${f(stats.item_period_p99_us[k])} p99, ${f(stats.item_period_max_us[k])} max (µs)`
        : '';
    }
  }
}
