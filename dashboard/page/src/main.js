// The dashboard page: wires the server's stream to the panels.
import 'uplot/dist/uPlot.min.css';
import '../style.css';
import { Connection } from './connection.js';
import { RobotView } from './robot_view.js';
import { Plots } from './plots.js';
import { Channels } from './channels.js';
import { Controllers } from './controllers.js';
import { Commands } from './commands.js';
import { Gains } from './gains.js';
import { el, shown } from './dom.js';

const $ = (id) => document.getElementById(id);
const conn = new Connection(`${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/ws`);
const view = new RobotView($('view'), $('view-note'), $('view-fit'));
const plots = new Plots($('plot'), { window: $('plot-window'), pause: $('plot-pause'), clear: $('plot-clear'), series: $('plot-series') });
const channels = new Channels($('channels'), $('channel-filter'), plots);
const controllers = new Controllers(conn, $('controllers'), $('switch-selected'), $('cm-message'), $('load-name'), $('load-button'));
const commands = new Commands(conn, $('commands'));
const gains = new Gains(conn, $('gains'));

const state = { hello: null, status: null, controllersOk: null, cmMessage: '', estop: false, stats: {} };
window.dashboard = { conn, view, plots, channels, controllers, commands, gains, state };

view.onLoad.push((joints) => {
  header();
  commands.setJoints(joints);
  gains.update(controllers.list, joints);
});
controllers.onChange.push((list) => {
  commands.update(list);
  gains.update(list, view.joints);
});

conn.on('hello', (h) => {
  state.hello = h;
  channels.setSchema(h.schema);
  gains.setSchema(h.schema);
  header();
  document.body.classList.toggle('read-only', h.read_only);
  if (!view.robot) view.load(h.urdf);
  banner();
});
// The robot's name (from its URDF), its namespace, read-only; the bus in the tooltip.
function header() {
  const h = state.hello;
  if (!h) return;
  const name = view.robot?.robotName || (h.urdf ? '' : 'no URDF');
  $('robot-name').textContent = shown([name, h.namespace && `namespace ${h.namespace}`, h.read_only && 'read-only']
    .filter(Boolean).join(' · '));
  $('robot-name').title = shown(`bus ${h.lcm_url}`);
}

conn.on('msg', (f) => {
  if (!f.msg) return;
  channels.message(f.channel, f.type, f.msg);
  commands.message(f.channel, f.type, f.msg);
  plots.add(f.channel, f.msg, f.received_s);
  if (f.type === 'joint_state_t' && f.channel.endsWith('joint_states')) view.setJoints(f.msg.name, f.msg.position);
  if (f.type === 'odometry_t' && f.channel.endsWith('sim_server/base_pose')) view.setBase(f.msg.position, f.msg.orientation);
  if (f.type === 'loop_stats_t') {
    state.stats[f.msg.process || f.channel] = f.msg;
    if (f.msg.process === 'controller_manager') controllers.timing(f.msg);
    stats();
  }
  if (f.type === 'e_stop_t') {
    state.estop = !!f.msg.engaged;
    estopButton();
  }
  if (f.type === 'pid_gains_t') gains.onMessage(f.channel, f.msg);
});
conn.on('status', (s) => {
  state.status = s;
  channels.rates(s.channels);
  banner();
});
conn.on('controllers', (c) => {
  state.controllersOk = c.ok;
  state.cmMessage = c.message || '';
  controllers.update(c);
  banner();
});
conn.on('open', banner);
conn.on('close', banner);

function banner() {
  const b = $('banner');
  let text = '';
  if (!conn.open) text = 'No connection to the dashboard server: is `dashboard` still running? Reconnecting every second.';
  else if (state.status && (state.status.bus_silent_s < 0 || state.status.bus_silent_s > 2))
    text = `The bus is silent: nothing received ${state.status.bus_silent_s < 0 ? 'yet' : `for ${state.status.bus_silent_s.toFixed(0)} s`} on ${state.hello?.lcm_url}. Is sim_server running (./scripts/demo, launch)? Same --lcm-url and --namespace?`;
  else if (state.controllersOk === false) text = `The controller manager does not answer: ${state.cmMessage}`;
  b.textContent = text;
  b.hidden = !text;
}

function stats() {
  const parts = [];
  for (const [name, s] of Object.entries(state.stats)) {
    const f = (x, digits) => (Number.isFinite(x) ? x.toFixed(digits) : '–');
    const figures = `${s.real_time_factor ? `RTF ${f(s.real_time_factor, 2)} · ` : ''}period ${f(s.period_mean_us, 0)} µs · jitter ${f(s.period_jitter_us, 1)} µs${s.period_error_p99_us ? ` · error p99 ${f(s.period_error_p99_us, 0)} µs` : ''} · missed ${s.missed}`;
    parts.push(el('span', { title: name }, el('b', {}, name.replace(/\/statistics$/, '')), ' ', figures));
  }
  $('stats').replaceChildren(...parts);
}

function estopButton() {
  const b = $('estop');
  b.textContent = state.estop ? 'RELEASE E-STOP' : 'E-STOP';
  b.classList.toggle('engaged', state.estop);
}
$('estop').onclick = async () => {
  const engage = !state.estop;
  const msg = { engaged: engage ? 1 : 0, source: 'dashboard' };
  const r = await conn.publish('e_stop', 'e_stop_t', msg);
  // UDP may lose one datagram: the same state twice more, 100 ms apart (sim_server keeps it until told otherwise).
  for (const delay of [100, 200]) setTimeout(() => state.estop === engage && conn.send({ op: 'publish', channel: 'e_stop', type: 'e_stop_t', msg }), delay);
  if (r.ok) {
    state.estop = engage;
    estopButton();
  } else {
    $('cm-message').textContent = shown(r.message);
  }
};
