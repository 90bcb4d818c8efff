import { kTitleChars, options, shown } from './dom.js';
import { fieldsOfType } from './fields.js';

// PID gains of a joint while it runs (rqt_reconfigure, the tune tool): read from the owner, edit, apply; the owner
// (sim_server for gazebo_ros_control/pid_gains, or a controller with its own PID) confirms on <owner>/gains.
// The inputs are pid_gains_t's numbers (its doubles: p, i, d, then the clamps) and switches (its booleans but the
// request's own `query` and `ok`), in the schema's order. The panel opens on the first joint whose owner answers
// with gains (sim_server's position joints, else the first controller with a PID of its own): only the owner knows.
const REQUEST_FLAGS = ['query', 'ok'];
const ANSWER_MS = 3000; // the owner's answer to a click
const PROBE_MS = 1000; // an owner's answer while looking for a joint with gains (none from a controller without PID)
const MAX_PROBES = 64;

// The (owner, joint) pairs to ask, in order, when looking for a joint with gains.
export function gainsCandidates(owners) {
  return Object.entries(owners).flatMap(([owner, joints]) => joints.map((joint) => [owner, joint])).slice(0, MAX_PROBES);
}

export class Gains {
  constructor(conn, el) {
    this.conn = conn;
    this.el = el;
    this.owners = {}; // owner -> joints
    this.pending = new Map(); // request_id -> {channel, resolve}
    this.chosen = null; // {owner, joint}: the joint shown, found with gains or picked by the user
    this.probing = 0; // a new probe, or the user's pick, ends the one before
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
    this.owner.onchange = () => this.pick();
    this.joint.onchange = () => this.pick();
    el.querySelector('#gains-read').onclick = () => this.ask(true);
    el.querySelector('#gains-apply').onclick = () => this.ask(false);
  }

  setSchema(schema) {
    this.numbers = fieldsOfType(schema, 'pid_gains_t', ['double']);
    this.switches = fieldsOfType(schema, 'pid_gains_t', ['boolean']).filter((f) => !REQUEST_FLAGS.includes(f));
    this.el.querySelector('.gains-fields').innerHTML =
      this.numbers.map((f) => `<label>${f} <input id="gains-${f}" type="number" step="any"></label>`).join('') +
      this.switches.map((f) => `<label>${f} <input id="gains-${f}" type="checkbox"></label>`).join('');
    if (this.chosen) this.ask(true); // the gains again, into the new inputs
    else this.probe();
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
    options(this.owner, Object.keys(owners));
    if (this.chosen && owners[this.chosen.owner]?.includes(this.chosen.joint)) this.select(this.chosen.owner, this.chosen.joint);
    else {
      this.chosen = null;
      this.probe();
    }
  }

  select(owner, joint) {
    this.owner.value = owner;
    options(this.joint, this.owners[owner] || []);
    this.joint.value = joint;
    this.owner.title = shown(owner, kTitleChars); // a narrow select cuts the name
    this.joint.title = shown(joint, kTitleChars);
  }

  // The user picked an owner or a joint: its gains in force, without a click.
  pick() {
    const keep = this.joint.value;
    const joints = this.owners[this.owner.value] || [];
    this.select(this.owner.value, joints.includes(keep) ? keep : joints[0] || '');
    this.chosen = this.joint.value ? { owner: this.owner.value, joint: this.joint.value } : null;
    if (this.chosen) this.ask(true);
  }

  // Asks each candidate in turn until one answers with its gains, and shows them.
  async probe() {
    const run = ++this.probing;
    const pairs = gainsCandidates(this.owners);
    if (!pairs.length || !this.numbers.length) return; // the joints, the controllers and the schema come in any order
    for (const [owner, joint] of pairs) {
      this.select(owner, joint);
      this.show(true, `asking ${owner} for ${joint}'s gains ...`);
      const a = await this.request({ owner, joint, query: 1 }, PROBE_MS);
      if (run !== this.probing) return;
      if (a.refused) return this.show(false, a.refused);
      if (a.answer?.ok) {
        this.chosen = { owner, joint };
        return this.fill(a.answer);
      }
    }
    this.select(...pairs[0]);
    this.show(true, `no PID gains on this robot's controllers or joints: asked ${[...new Set(pairs.map(([o]) => o))].join(', ')} ` +
      '(a position joint gets them from gazebo_ros_control/pid_gains, a controller from its pid)');
  }

  async ask(query) {
    this.probing++;
    const owner = this.owner.value;
    const joint = this.joint.value;
    if (!owner || !joint) return;
    const msg = { owner, joint, query: query ? 1 : 0 };
    if (!query) {
      for (const f of this.numbers) msg[f] = Number(this.el.querySelector(`#gains-${f}`).value);
      for (const f of this.switches) msg[f] = this.el.querySelector(`#gains-${f}`).checked ? 1 : 0;
    }
    this.show(true, `asking ${owner} ...`);
    const a = await this.request(msg, ANSWER_MS);
    if (a.refused) this.show(false, a.refused);
    else if (a.answer) this.fill(a.answer);
    else this.show(false, `no answer from ${owner} on ${owner}/gains: it has no PID for ${joint}, or is not running`);
  }

  // One request on <owner>/gains/set: {answer} (null after `ms` without one) or {refused} (the server's reason).
  async request(msg, ms) {
    const id = Math.floor(Math.random() * 1e9);
    const answered = new Promise((resolve) => {
      this.pending.set(id, { channel: `${msg.owner}/gains`, resolve });
      setTimeout(() => this.pending.delete(id) && resolve(null), ms);
    });
    const r = await this.conn.publish(`${msg.owner}/gains/set`, 'pid_gains_t', { ...msg, request_id: id });
    if (!r.ok) {
      this.pending.delete(id);
      return { refused: r.message };
    }
    return { answer: await answered };
  }

  onMessage(channel, msg) {
    const p = this.pending.get(msg.request_id);
    if (!p || p.channel !== channel) return;
    this.pending.delete(msg.request_id);
    p.resolve(msg);
  }

  fill(msg) {
    for (const f of this.numbers) this.el.querySelector(`#gains-${f}`).value = msg[f];
    for (const f of this.switches) this.el.querySelector(`#gains-${f}`).checked = !!msg[f];
    this.show(msg.ok, msg.message || (msg.ok ? 'gains in force' : 'refused'));
  }

  show(ok, text) {
    this.message.textContent = shown(text);
    this.message.className = ok ? 'message' : 'message error';
  }
}
