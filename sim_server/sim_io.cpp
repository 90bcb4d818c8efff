#include "sim_server/sim_io.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "bus/gains_service.hpp"
#include "bus/hardware_wire.hpp"
#include "bus/messages.hpp"

namespace lcm_control::sim {

namespace {
constexpr int kMaxMessagesPastDeadline = 100;
constexpr int kMessagesPerWake = 64;
constexpr size_t kMaxQueuedRequests = 16;

int64_t random_session() {
  std::random_device rd;
  const int64_t s = (int64_t(rd()) << 31) ^ int64_t(rd());
  return s == 0 ? 1 : s;
}

}  // namespace

SimIo::SimIo(Bus& bus, Simulation& sim, bool lockstep, int clock_every)
    : bus_(bus),
      sim_(sim),
      lockstep_(lockstep),
      clock_every_(std::max(1, clock_every)),
      session_(random_session()),
      state_channel_(bus.channel(channels::kHardwareState)),
      endpoints_(bus, Endpoints::On::Shared),
      hw_endpoints_(bus, Endpoints::On::Hardware),
      state_pub_(hw_endpoints_.publisher<hardware_state_t>(state_channel_)),
      clock_pub_(endpoints_.publisher<sim_clock_t>(bus.channel(channels::kClock))),
      base_pub_(endpoints_.publisher<odometry_t>(bus.channel(channels::kBasePose))),
      stats_pub_(endpoints_.publisher<loop_stats_t>(bus.channel(channels::kSimStatistics))),
      response_pub_(endpoints_.publisher<sim_response_t>(bus.channel(channels::kSimResponse))) {
  if (ShmLink* shm = bus.hardware_shm()) shm->yield_first(lockstep);
  const PlayedHardware& act = sim.hardware();
  const int n = act.size();
  resize(state_, n);
  for (int i = 0; i < n; ++i) {
    state_.name[i] = act.name(i);
    state_.mode[i] = act.wire_mode(i);
  }
  if (const SensorBank* sensors = sim.sensors()) {
    state_.sensor_interface = sensors->names();
    state_.sensor_value = sensors->values();
  }
  // Then the <gpio> state interfaces, under their "<gpio>/<interface>" names.
  state_.sensor_interface.insert(state_.sensor_interface.end(), sim.gpio().names().begin(), sim.gpio().names().end());
  state_.sensor_value.insert(state_.sensor_value.end(), sim.gpio().values().begin(), sim.gpio().values().end());
  state_.num_sensor_values = int32_t(state_.sensor_value.size());
  state_.session = session_;
  state_.lockstep = lockstep;
  state_.period_us = int32_t(std::llround(sim.control_period() * 1e6));
  floating_base_ = sim.floating_base();
  if (floating_base_) {
    base_ = odometry_t{};
    base_.frame_id = "world";
    base_.child_frame_id = sim.multibody().root_link();
  }
  resize(cmd_, n);
  sim.components().bind(state_.name);
  rejected_warned_.assign(n, hardware_command_t::MODE_NONE);
  pending_mode_.assign(n, hardware_command_t::MODE_NONE);
  pending_value_.assign(n, 0.0);
  pending_damping_.assign(n, 0.0);

  auto on = [this](Endpoints& e, const std::string& channel, void (SimIo::*handler)(const lcm::ReceiveBuffer&)) {
    e.subscribe_raw(channel, [this, handler](const lcm::ReceiveBuffer& rb) { (this->*handler)(rb); });
  };
  on(hw_endpoints_, bus.channel(channels::kHardwareCommand), &SimIo::on_command);
  on(hw_endpoints_, state_channel_, &SimIo::on_state);
  on(endpoints_, bus.channel(channels::kEStop), &SimIo::on_e_stop);
  serve_gains(endpoints_, bus, channels::kSimGainsOwner, pid_lookup(),
              {[this] { return sim_.time_us(); }, [this] { return fmt::format(" from step {}", sim_.step_count()); },
               [this](const std::string& message) { log_.info(message); }, [this](const std::string& why) { drop(why); }});
  on(endpoints_, bus.channel(channels::kSimRequest), &SimIo::on_request);
}

void SimIo::publish_state(double real_time_factor, bool clock_again) {
  const PlayedHardware& act = sim_.hardware();
  state_.utime = sim_.time_us();
  state_.step = sim_.step_count();
  state_.e_stop = act.e_stop();
  state_.real_time_factor = real_time_factor;
  for (int i = 0; i < act.size(); ++i) {
    state_.mode[i] = act.wire_mode(i);
    state_.position[i] = act.position(i);
    state_.velocity[i] = act.velocity(i);
    state_.effort[i] = act.effort(i);
  }
  size_t v = 0;
  if (const SensorBank* sensors = sim_.sensors()) {  // the same sensors after a reset
    std::copy(sensors->values().begin(), sensors->values().end(), state_.sensor_value.begin());
    v = sensors->values().size();
  }
  std::copy(sim_.gpio().values().begin(), sim_.gpio().values().end(), state_.sensor_value.begin() + long(v));
  sim_.components().report(state_);
  state_pub_.publish(state_);
  const bool due = clock_step_ < 0 || (state_.step != clock_step_ && state_.step % clock_every_ == 0);
  if (!due && !clock_again) return;
  clock_step_ = state_.step;
  clock_.utime = state_.utime;
  clock_.step = state_.step;
  clock_.real_time_factor = real_time_factor;
  clock_pub_.publish(clock_);
  if (floating_base_) publish_base_pose();
}

void SimIo::publish_base_pose() {
  const Multibody& mb = sim_.multibody();
  const Eigen::Isometry3d pose = mb.base_pose();
  const Eigen::Quaterniond q(pose.linear());
  const Eigen::Vector3d v = pose.linear().transpose() * mb.base_linear_velocity();
  const Eigen::Vector3d w = pose.linear().transpose() * mb.base_angular_velocity();
  base_.utime = state_.utime;
  base_.position = {pose.translation().x(), pose.translation().y(), pose.translation().z()};
  base_.orientation = {q.w(), q.x(), q.y(), q.z()};
  base_.linear = {v.x(), v.y(), v.z()};
  base_.angular = {w.x(), w.y(), w.z()};
  base_.yaw = std::atan2(pose.linear()(1, 0), pose.linear()(0, 0));
  base_pub_.publish(base_);
}

void SimIo::publish_statistics(const loop_stats_t& stats) { stats_pub_.publish(stats); }

bool SimIo::poll_until(int64_t deadline_us, bool until_command, bool until_request, int64_t answering_step) {
  auto done = [&] {
    return (until_command && has_pending_ && last_step_ >= answering_step) || (until_request && has_request());
  };
  for (int late = 0, pass = 0; late < kMaxMessagesPastDeadline; ++pass) {
    if (pass > 0 && monotonic_us() >= deadline_us) ++late;  // the first pass reads no clock: the wait needs none
    const int ready = bus_.wait_until_us(deadline_us);
    if (ready < 0) return false;
    if (ready == 0) return true;  // the time ran out, or a signal came
    // One message at a time, so that what was sent after the awaited command waits for the next step.
    for (const int source : {Bus::kSharedReady, Bus::kHardwareReady}) {
      if (!(ready & source)) continue;
      for (int k = 0; k < kMessagesPerWake; ++k) {
        const int n = source == Bus::kSharedReady ? bus_.handle_shared(1) : bus_.handle_hardware(1);
        if (n < 0) return false;
        if (done()) return true;
        if (n == 0) break;
      }
    }
    if (done()) return true;
  }
  return true;
}

bool SimIo::take_command() {
  if (!has_pending_) return false;
  PlayedHardware& act = sim_.hardware();
  const ComponentStates& components = sim_.components();
  for (int i = 0; i < act.size(); ++i) {
    const int8_t mode = components.holds(i) ? hardware_command_t::MODE_NONE : pending_mode_[i];
    if (!act.set_command(i, mode, pending_value_[i], pending_damping_[i])) reject_mode(i, mode);
  }
  sim_.gpio().commit();
  has_pending_ = false;
  return true;
}

void SimIo::reject_mode(int i, int8_t mode) {
  ++rejected_modes_;
  if (rejected_warned_[i] == mode) return;
  rejected_warned_[i] = mode;
  const PlayedHardware& act = sim_.hardware();
  std::vector<std::string> offered;
  for (int8_t w = hardware_command_t::MODE_POSITION; w <= hardware_command_t::MODE_EFFORT; ++w)
    if (act.offers(i, w)) offered.push_back(wire_mode_name(w));
  spdlog::warn("actuator '{}' (joint '{}') got a {} command at step {}, but its joint offers only {}: it holds while "
               "such commands come (said once; counted). Claim the joint with a controller of an offered interface, "
               "or add <command_interface name=\"{}\"/> to the joint in the URDF's <ros2_control> block",
               act.name(i), act.joint(i), wire_mode_name(mode), sim_.step_count(), fmt::join(offered, ", "),
               wire_mode_name(mode));
}

std::string SimIo::why_rejected() {
  std::string problem = check(cmd_);
  if (!problem.empty()) return problem;
  const PlayedHardware& act = sim_.hardware();
  if (cmd_.session != session_)
    return fmt::format("session {} is not this sim_server's session {} (answer the latest hardware/state)",
                       cmd_.session, session_);
  if (cmd_.num_actuators != act.size())
    return fmt::format("{} actuators, but this robot has {}", cmd_.num_actuators, act.size());
  if (cmd_.name != bound_names_) {  // a new sender or a new order: match by name, then use the indices
    const ActuatorBinding b = bind_actuators(state_.name, cmd_.name);
    if (const std::string p = b.problem(false); !p.empty())
      return fmt::format("its actuators are not this robot's: {} (this robot's: '{}')", p,
                         fmt::join(state_.name, "', '"));
    bound_names_ = cmd_.name;
    slot_ = b.slot;
  }
  return "";
}

void SimIo::drop(const std::string& why) {
  ++dropped_;
  const int64_t now = monotonic_us();
  if (dropped_logged_ == 0 || now - last_drop_log_us_ > 1000000) {
    spdlog::warn("dropped a hardware/command ({} so far): {}", dropped_, why);
    dropped_logged_ = dropped_;
    last_drop_log_us_ = now;
  }
}

void SimIo::on_command(const lcm::ReceiveBuffer& rb) {
  if (const std::string why =
          check_hardware_command_bytes(rb.data, rb.data_size, sim_.hardware().size(),
                                       std::max(sim_.gpio().commands(), int(sim_.components().components().size())));
      !why.empty())
    return drop(why);
  if (!decode_walked(cmd_, rb.data, rb.data_size))
    return drop("not a hardware_command_t (wrong fingerprint, truncated or undecodable)");
  const std::string why = why_rejected();
  if (!why.empty()) return drop(why);
  // A command answers a state already published: a later step is forged or corrupt, and remembering it would make
  // every genuine command after it look stale.
  if (cmd_.step > sim_.step_count() && cmd_.step <= pre_reset_step_) {
    ++stale_;
    return;
  }
  if (cmd_.step > sim_.step_count())
    return drop(fmt::format("step {} is ahead of the hardware's step {}: it answers no published state", cmd_.step,
                            sim_.step_count()));
  const bool too_old = max_age_ > 0 && cmd_.step < sim_.step_count() - max_age_;
  if (lockstep_ ? cmd_.step != expected_step_ : cmd_.step < last_step_ || too_old) {
    ++stale_;
    return;
  }
  for (int i = 0; i < cmd_.num_actuators; ++i) {
    pending_mode_[i] = cmd_.mode[slot_[i]];
    pending_value_[i] = cmd_.command[slot_[i]];
    pending_damping_[i] = cmd_.damping[slot_[i]];
  }
  if (cmd_.num_components > 0 || components_listed_) {  // the lifecycle changes between steps, said when it does
    for (const std::string& line : sim_.components().take(cmd_, sim_.gpio())) spdlog::info("{}", line);
    components_listed_ = cmd_.num_components > 0;
  }
  sim_.gpio().stage(cmd_);
  has_pending_ = true;
  last_step_ = cmd_.step;
  pre_reset_step_ = -1;
  last_command_us_ = monotonic_us();
}

// hardware/state comes back to us (every socket on the port receives it anyway); one with another session is a second
// simulator on this namespace. Only the fingerprint and the session (bytes 24-31) are read.
void SimIo::on_state(const lcm::ReceiveBuffer& rb) {
  if (rb.data_size < 32) return;
  const int64_t session = read_int64_be(static_cast<const uint8_t*>(rb.data) + 24);
  if (payload_fingerprint(rb.data) != hardware_state_t::getHash() || session == session_) return;
  ++foreign_states_;
  log_.warn(fmt::format("another simulator publishes {} (session {:x}; this one is {:x}): the controller manager "
                        "follows one of them and the other is not controlled. Stop one, or give each robot its own "
                        "--namespace",
                        state_channel_, session, session_));
}

void SimIo::on_e_stop(const lcm::ReceiveBuffer& rb) {
  if (!decode_guarded(e_stop_msg_, rb.data, rb.data_size)) return drop("e_stop: not an e_stop_t");
  PlayedHardware& act = sim_.hardware();
  if (e_stop_msg_.engaged != act.e_stop()) {
    const std::string who = e_stop_msg_.source.empty() ? "" : fmt::format(" by '{}'", clip(e_stop_msg_.source));
    if (e_stop_msg_.engaged)
      log_.warn(fmt::format(
          "e-stop engaged{} at step {}: position actuators hold where they are, velocity and effort get 0", who,
          sim_.step_count()));
    else
      log_.info(fmt::format("e-stop released{} at step {}: commands resume", who, sim_.step_count()));
  }
  act.set_e_stop(e_stop_msg_.engaged);
}

// The actuators' PIDs (position and velocity actuators with pid_gains), looked up through the simulation at each
// request: a reset rebuilds the actuators.
PidLookup SimIo::pid_lookup() {
  PidLookup l;
  l.joints = [this] {
    const PlayedHardware& act = sim_.hardware();
    std::vector<std::string> joints;
    for (int k = 0; k < act.size(); ++k)
      if (act.has_pid(k)) joints.push_back(act.joint(k));
    return joints;
  };
  l.get = [this](const std::string& joint) { return sim_.hardware().gains(sim_.hardware().find_joint(joint)); };
  l.set = [this](const std::string& joint, const PidGains& g) {
    sim_.hardware().set_gains(sim_.hardware().find_joint(joint), g);
  };
  l.why_none = [this, joints = l.joints](const std::string& joint) {
    const PlayedHardware& act = sim_.hardware();
    const int i = act.find_joint(joint);
    if (i < 0) {
      const std::vector<std::string> with = joints();
      return fmt::format("no actuated joint '{}'; joints with pid_gains: {}", joint,
                         with.empty() ? "none" : fmt::format("{}", fmt::join(with, ", ")));
    }
    if (sim_.backend() == Backend::Mock)
      return fmt::format("joint '{}' runs on mock hardware, which has no PID (its state follows the command); run "
                         "sim_server without --mock-hardware, on a description naming a simulator, for pid_gains",
                         joint);
    return fmt::format("joint '{}' runs {} (no pid_gains); add gazebo_ros_control/pid_gains/{} to the YAML for a PID",
                       joint, act.mode_name(i), joint);
  };
  return l;
}

void SimIo::on_request(const lcm::ReceiveBuffer& rb) {
  sim_request_t req;
  if (!decode_guarded(req, rb.data, rb.data_size)) return drop("sim_server/request: not a sim_request_t");
  const sim_response_t* given = nullptr;
  switch (ledger_.seen(req.request_id, &given)) {
    case AnswerLedger<sim_response_t>::Seen::Answered: return answer(*given);
    case AnswerLedger<sim_response_t>::Seen::Working: return;  // queued, or a STEP under way: answered when done
    case AnswerLedger<sim_response_t>::Seen::New: break;
  }
  if (requests_.size() >= kMaxQueuedRequests) {
    sim_response_t busy{};
    busy.utime = sim_.time_us();
    busy.request_id = req.request_id;
    busy.op = req.op;
    busy.message = fmt::format("{} requests are already waiting; try again", requests_.size());
    busy.lockstep = lockstep_;
    busy.step = sim_.step_count();
    busy.period_us = int32_t(std::llround(sim_.control_period() * 1e6));
    return answer(busy);
  }
  ledger_.working(req.request_id);
  requests_.push_back(std::move(req));
}

sim_request_t SimIo::take_request() {
  sim_request_t r = std::move(requests_.front());
  requests_.pop_front();
  return r;
}

void SimIo::answer(const sim_response_t& a) {
  response_pub_.publish(a);
  ledger_.answered(a);
}

void SimIo::after_reset(int64_t previous_step) {
  has_pending_ = false;
  std::fill(rejected_warned_.begin(), rejected_warned_.end(), hardware_command_t::MODE_NONE);
  last_step_ = -1;
  clock_step_ = -1;
  expected_step_ = 0;
  pre_reset_step_ = previous_step;
}

}  // namespace lcm_control::sim
