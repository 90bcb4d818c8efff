import { distinctLabels, el, nameEl, shown } from './dom.js';

// Command channels of the running controllers (rqt's message publisher): a slider per joint within its URDF limits,
// and an expression in i and t streamed by the server at a rate, like turret-cmd. What a controller takes is what its
// type declares (the controller manager's list): numbers, one (float64_t) or one per joint (float64_array_t), each a
// position, velocity or effort set point; or a gripper goal (gripper_command_t, a GripperActionController): a slider
// for its joint's position that sends one goal when released, with the goal's max_effort. The sliders follow what
// the controller is commanded, by this page or any other tool (turret-cmd, a script), as heard on its channel, and
// the set point a controller with a PID reports on <name>/state: before any command, and when it changes without one
// (the controller manager restarts its controllers from the measured state after the hardware was silent).

// The set point a controller's sliders give ("position", "velocity", "effort", or "value" when its type does not
// say; "gripper" for a gripper goal), or null when it does not take one number per joint.
export function commandKind(c) {
  if (c.command_type === 'gripper_command_t') return c.joints.length === 1 ? 'gripper' : null;
  const numbers = (c.command_type === 'float64_t' && c.command_width === 1 && c.joints.length === 1) ||
    (c.command_type === 'float64_array_t' && c.command_width === c.joints.length && c.joints.length > 0);
  return numbers ? c.command_quantity || 'value' : null;
}

// The controllers that get sliders.
export function commandable(controllers) {
  return controllers.filter((c) => c.state === 'running' && commandKind(c));
}

// The message a gripper slider sends: a goal with a fresh id (the result comes on <name>/result; the `gripper`
// tool waits for it).
export function gripperGoal(position, maxEffort, goalId) {
  return { goal_id: goalId, position, max_effort: maxEffort > 0 ? maxEffort : 0 };
}

// The values a message heard on controller c's command channel sets its sliders to (one per joint), or null when it
// is not a command c takes.
export function commandedValues(c, type, msg) {
  const kind = commandKind(c);
  if (!kind || type !== c.command_type || !msg) return null;
  const values = kind === 'gripper' ? [msg.position] : type === 'float64_t' ? [msg.data] : msg.data;
  return Array.isArray(values) && values.length === c.joints.length && values.every(Number.isFinite) ? values : null;
}

// The values a controller_state_t heard on <c.name>/state sets a single-joint controller's slider to (its set
// point), or null.
export function setPointValues(c, type, msg) {
  if (type !== 'controller_state_t' || !msg || c.joints.length !== 1 || msg.joint !== c.joints[0]) return null;
  return commandKind(c) && Number.isFinite(msg.set_point) ? [msg.set_point] : null;
}

// How long after the user last moved a controller's slider the page leaves it alone: the bus echoes the page's own
// commands late, and an older one would pull the slider back under the user's hand.
export const kHandsOffMs = 300;

// Whether a set point heard on <name>/state moves the sliders at nowMs: not while the user moves them, nor within
// kHandsOffMs of a command heard (the controller's state reports the set point it had before it).
export function setPointShown(touchedMs, commandHeardMs, nowMs) {
  return nowMs - touchedMs >= kHandsOffMs && nowMs - commandHeardMs >= kHandsOffMs;
}

function range(kind, j) {
  if (kind === 'position' || kind === 'gripper') {
    if (!j || j.type === 'continuous' || !(j.upper > j.lower)) return [-Math.PI, Math.PI];
    return [j.lower, j.upper];
  }
  const limit = kind === 'velocity' ? j?.velocity : kind === 'effort' ? j?.effort : 0;
  return limit > 0 ? [-limit, limit] : [-10, 10];
}

export class Commands {
  constructor(conn, el) {
    this.conn = conn;
    this.el = el;
    this.joints = {};
    this.key = '';
    this.values = {}; // controller -> values
    this.lastSend = {};
    this.sliders = {}; // "<controller>/<command channel>" -> {c, values, rows: [{slider, out, digits}], touched}
    this.states = {}; // "<controller>/state" -> the same
    this.heardAt = {}; // controller -> performance.now() of the last command heard on its channel
  }

  setJoints(joints) {
    this.joints = joints;
    this.key = '';
    if (this.controllers) this.update(this.controllers);
  }

  update(controllers) {
    this.controllers = controllers;
    const shown = commandable(controllers);
    const key = JSON.stringify(shown.map((c) => [c.name, c.type, c.joints, c.command_type, c.command_quantity])) +
      Object.keys(this.joints).join();
    if (key === this.key) return;
    this.key = key;
    this.el.replaceChildren(...(shown.length ? [] : [el('p', { class: 'hint' }, 'no running position, velocity or effort controller')]));
    this.sliders = {};
    this.states = {};
    for (const c of shown) this.el.appendChild(this.block(c));
  }

  block(c) {
    const kind = commandKind(c);
    const group = c.command_type === 'float64_array_t';
    const channel = `${c.name}/${c.command_channel || 'command'}`;
    const div = document.createElement('div');
    div.className = 'command';
    div.append(el('h3', { title: c.name }, c.name, ' ', el('small', {}, `${kind} → ${channel}`)));
    const values = (this.values[c.name] ||= c.joints.map(() => 0));
    const follow = (this.sliders[channel] = { c, values, rows: [], touched: -Infinity });
    this.states[`${c.name}/state`] = follow;
    if (kind === 'gripper') return this.gripperBlock(c, div, channel, values, follow);
    const labels = distinctLabels(c.joints);
    c.joints.forEach((joint, k) => {
      const [lo, hi] = range(kind, this.joints[joint]);
      const row = document.createElement('label');
      row.className = 'slider';
      const slider = document.createElement('input');
      slider.type = 'range';
      slider.id = `slider-${c.name}-${joint}`;
      slider.min = lo;
      slider.max = hi;
      slider.step = (hi - lo) / 1000;
      slider.value = Math.min(hi, Math.max(lo, values[k]));
      const out = document.createElement('output');
      out.textContent = Number(slider.value).toFixed(3);
      follow.rows.push({ slider, out, digits: 3 });
      slider.oninput = () => {
        follow.touched = performance.now();
        values[k] = Number(slider.value);
        out.textContent = values[k].toFixed(3);
        this.send(c.name, channel, group, values, false);
      };
      slider.onchange = () => this.send(c.name, channel, group, values, true);
      const label = el('span', { class: 'joint', title: joint }, labels[k]);
      row.append(label, slider, out);
      div.appendChild(row);
    });
    const expr = document.createElement('div');
    expr.className = 'expression';
    const text = document.createElement('input');
    text.placeholder = group ? c.joints.map(() => '0').join('; ') : '3.14*sin(i/100)';
    text.title = 'muparser expressions in i (tick) and t (seconds); several separated by ; for a group';
    text.id = `expr-${c.name}`;
    const rate = document.createElement('input');
    rate.type = 'number';
    rate.value = 60;
    rate.min = 1;
    rate.max = 1000;
    rate.title = 'Hz';
    const start = document.createElement('button');
    start.textContent = 'Run';
    const stop = document.createElement('button');
    stop.textContent = 'Stop';
    const msg = document.createElement('span');
    msg.className = 'message';
    start.onclick = async () => {
      const expressions = text.value.split(';').map((s) => s.trim()).filter(Boolean);
      const r = await this.conn.request({ op: 'expr', channel, expressions, rate: Number(rate.value) });
      msg.textContent = shown(r.message);
      msg.className = r.ok ? 'message' : 'message error';
    };
    stop.onclick = async () => {
      const r = await this.conn.request({ op: 'expr_stop', channel });
      msg.textContent = shown(r.message);
    };
    expr.append(text, ' at ', rate, ' Hz ', start, stop, msg);
    div.appendChild(expr);
    return div;
  }

  // One slider for the gripper joint: a goal when it is released (not while it moves: each goal preempts the last).
  gripperBlock(c, div, channel, values, follow) {
    const joint = c.joints[0];
    const [lo, hi] = range('gripper', this.joints[joint]);
    const row = document.createElement('label');
    row.className = 'slider';
    const slider = document.createElement('input');
    slider.type = 'range';
    slider.id = `slider-${c.name}-${joint}`;
    slider.min = lo;
    slider.max = hi;
    slider.step = (hi - lo) / 1000;
    slider.value = Math.min(hi, Math.max(lo, values[0]));
    const out = document.createElement('output');
    out.textContent = Number(slider.value).toFixed(4);
    const effort = document.createElement('input');
    effort.type = 'number';
    effort.min = 0;
    effort.value = 0;
    effort.id = `effort-${c.name}`;
    effort.title = "max_effort of the goal (0: the controller's max_effort, else the URDF's limit)";
    follow.rows.push({ slider, out, digits: 4 });
    slider.oninput = () => {
      follow.touched = performance.now();
      out.textContent = Number(slider.value).toFixed(4);
    };
    slider.onchange = () => {
      follow.touched = performance.now();
      values[0] = Number(slider.value);
      this.conn.send({ op: 'publish', channel, type: 'gripper_command_t',
        msg: gripperGoal(values[0], Number(effort.value), Date.now()) });
    };
    row.append(nameEl('span', 'joint', joint), slider, out, ' max effort ', effort);
    div.append(row, el('p', { class: 'hint' },
      `a goal on release; its result on ${c.name}/result (the gripper tool waits for it: gripper ${c.name} --position X)`));
    return div;
  }

  // A message on the bus: a command a controller with sliders takes moves them there (unless the user is moving
  // them), as does its set point (setPointShown()). The time it did so is the slider's data-followed-at (ms since
  // the epoch).
  message(channel, type, msg) {
    const command = this.sliders[channel];
    const follow = command || this.states[channel];
    if (!follow) return;
    const now = performance.now();
    if (command ? now - follow.touched < kHandsOffMs
      : !setPointShown(follow.touched, this.heardAt[follow.c.name] ?? -Infinity, now)) return;
    const values = command ? commandedValues(follow.c, type, msg) : setPointValues(follow.c, type, msg);
    if (!values) return;
    if (command) this.heardAt[follow.c.name] = now;
    const moved = command || values.some((v, k) => v !== follow.values[k]);
    follow.rows.forEach(({ slider, out, digits }, k) => {
      follow.values[k] = values[k];
      slider.value = values[k];
      out.textContent = values[k].toFixed(digits);
      if (moved) slider.dataset.followedAt = Date.now();
    });
  }

  // Slider moves at most 30 a second per controller; the final value (change) always goes.
  send(name, channel, group, values, final) {
    const now = performance.now();
    if (!final && now - (this.lastSend[name] || 0) < 33) {
      clearTimeout(this.timer?.[name]);
      (this.timer ||= {})[name] = setTimeout(() => this.send(name, channel, group, values, true), 40);
      return;
    }
    this.lastSend[name] = now;
    if (group) this.conn.send({ op: 'publish', channel, type: 'float64_array_t', msg: { data: values } });
    else this.conn.send({ op: 'publish', channel, type: 'float64_t', msg: { data: values[0] } });
  }
}
