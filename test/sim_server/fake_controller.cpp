#include "test/sim_server/fake_controller.hpp"

#include "bus/bus.hpp"
#include "bus/messages.hpp"
#include "test/support/lcm_test.hpp"

namespace lcm_control::sim::testing {

FakeController::FakeController(lcm::LCM& lc, const std::string& ns)
    : lc_(lc), command_channel_((ns.empty() ? "" : ns + "/") + "hardware/command") {
  sub_ = lc_.subscribe((ns.empty() ? "" : ns + "/") + "hardware/state", &FakeController::on_state, this);
  sub_->setQueueCapacity(0);
}

FakeController::~FakeController() { lc_.unsubscribe(sub_); }

void FakeController::on_state(const lcm::ReceiveBuffer* rb, const std::string&, const hardware_state_t* s) {
  const bool repeat = !states.empty() && states.back().step == s->step && states.back().session == s->session;
  if (repeat)
    ++republished;
  else
    states.push_back(*s);
  if (!answering) return;
  if (repeat && have_last_ && last_.step == s->step) return publish_command(last_);
  hardware_command_t cmd{};
  resize(cmd, s->num_actuators);
  cmd.utime = s->utime;
  cmd.step = s->step;
  cmd.session = s->session;
  cmd.name = s->name;
  cmd.mode = s->mode;
  for (int i = 0; i < s->num_actuators; ++i) cmd.command[i] = s->position[i];
  if (policy) policy(*s, cmd);
  if (before_answer) before_answer(*s);
  last_ = cmd;
  have_last_ = true;
  if (wall_us() - rb->recv_utime > kLateAnswerUs) ++late_answers;  // recv_utime is on the wall clock
  publish_command(cmd);
}

void FakeController::publish_command(const hardware_command_t& cmd) { lc_.publish(command_channel_, &cmd); }

bool FakeController::run_until_step(int64_t step, double timeout_s) {
  return lcm_control::testing::pump_until(
      lc_, [&] { return !states.empty() && states.back().step >= step; }, timeout_s);
}

void FakeController::pump_for(double seconds) {
  lcm_control::testing::pump_until(lc_, [] { return false; }, seconds);
}

bool SimServerProcess::start(const std::vector<std::string>& flags, const std::string& urdf,
                             const std::string& config, std::string* why) {
  std::vector<std::string> argv{lcm_control::testing::bin("sim_server"), "--urdf", urdf, "--lcm-url", url};
  if (!config.empty()) {
    argv.push_back("--config");
    argv.push_back(config);
  }
  argv.insert(argv.end(), flags.begin(), flags.end());
  process = std::make_unique<lcm_control::testing::ChildProcess>(argv);
  const bool ready = process->wait_for_output("ready (", 10.0);
  if (!ready && why) *why = process->output();
  return ready;
}

}  // namespace lcm_control::sim::testing
