import { options, shown } from './dom.js';
import { fieldsOfType } from './fields.js';

// PID gains of a joint while it runs (rqt_reconfigure, the tune tool): read from the owner, edit, apply; the owner
// (sim_server for gazebo_ros_control/pid_gains, or a controller with its own PID) confirms on <owner>/gains.
// The inputs are pid_gains_t's numbers (its doubles) and switches (its booleans but the request's own `query` and
// `ok`), as the schema lists them.
const REQUEST_FLAGS = ['query', 'ok'];

export class Gains {
  constructor(conn, el) {
    this.conn = conn;
    this.el = el;
    this.owners = {}; // owner -> joints
    this.waiting = null;
    el.innerHTML = `
      <div class="gains-row"><select id="gains-owner"></select><select id="gains-joint"></select>
      <button id="gains-read">Read</button><button id="gains-apply">Apply</button></div>
      <div class="gains-fields"></div>
      <div id="gains-message" class="message"></div>`;
    this.numbers = [];
    this.switches = [];
    this.owner = el.querySelector('#gains-owner');
    this.joint = el.querySelector('#gains-joint');
    this.message = el.querySelector('#gains-message');
    this.owner.onchange = () => this.fillJoints();
    this.joint.onchange = () => this.fillJoints();
    el.querySelector('#gains-read').onclick = () => this.ask(true);
    el.querySelector('#gains-apply').onclick = () => this.ask(false);
  }

  setSchema(schema) {
    this.numbers = fieldsOfType(schema, 'pid_gains_t', ['double']);
    this.switches = fieldsOfType(schema, 'pid_gains_t', ['boolean']).filter((f) => !REQUEST_FLAGS.includes(f));
    this.el.querySelector('.gains-fields').innerHTML =
      this.numbers.map((f) => `<label>${f} <input id="gains-${f}" type="number" step="any"></label>`).join('') +
      this.switches.map((f) => `<label>${f} <input id="gains-${f}" type="checkbox"></label>`).join('');
    this.shown = null; // read the gains again into the new inputs
    this.fillJoints();
  }

  // Owners: sim_server with every joint, and each running controller that commands joints (its answer says when it
  // has no PID of its own, as a forwarding controller does not).
  update(controllers, joints) {
    const owners = { sim_server: Object.keys(joints) };
    for (const c of controllers) if (c.state === 'running' && c.interface && c.joints.length) owners[c.name] = c.joints;
    const key = JSON.stringify(owners);
    if (key === this.key) return;
    this.key = key;
    this.owners = owners;
    const keep = this.owner.value;
    options(this.owner, Object.keys(owners));
    if (keep in owners) this.owner.value = keep;
    this.fillJoints();
  }

  fillJoints() {
    const keep = this.joint.value;
    const joints = this.owners[this.owner.value] || [];
    options(this.joint, joints);
    if (joints.includes(keep)) this.joint.value = keep;
    const shown = `${this.owner.value}/${this.joint.value}`;
    if (this.joint.value && shown !== this.shown) {
      this.shown = shown;
      this.ask(true);  // the gains in force, without a click
    }
  }

  ask(query) {
    const owner = this.owner.value;
    const joint = this.joint.value;
    if (!owner || !joint) return;
    const msg = { request_id: Math.floor(Math.random() * 1e9), owner, joint, query: query ? 1 : 0 };
    if (!query) {
      for (const f of this.numbers) msg[f] = Number(this.el.querySelector(`#gains-${f}`).value);
      for (const f of this.switches) msg[f] = this.el.querySelector(`#gains-${f}`).checked ? 1 : 0;
    }
    this.waiting = { id: msg.request_id, channel: `${owner}/gains`, since: performance.now() };
    this.message.textContent = shown(`asking ${owner} ...`);
    this.message.className = 'message';
    this.conn.publish(`${owner}/gains/set`, 'pid_gains_t', msg).then((r) => {
      if (!r.ok) this.show(false, r.message);
    });
    setTimeout(() => {
      if (this.waiting && this.waiting.id === msg.request_id) {
        this.show(false, `no answer from ${owner} on ${owner}/gains: it has no PID for ${joint}, or is not running`);
        this.waiting = null;
      }
    }, 3000);
  }

  onMessage(channel, msg) {
    if (!this.waiting || channel !== this.waiting.channel || msg.request_id !== this.waiting.id) return;
    this.waiting = null;
    for (const f of this.numbers) this.el.querySelector(`#gains-${f}`).value = msg[f];
    for (const f of this.switches) this.el.querySelector(`#gains-${f}`).checked = !!msg[f];
    this.show(msg.ok, msg.message || (msg.ok ? 'gains in force' : 'refused'));
  }

  show(ok, text) {
    this.message.textContent = shown(text);
    this.message.className = ok ? 'message' : 'message error';
  }
}
