// tune: dynamic reconfigure for PID gains. Shows the gains in force for a
// joint, or sets some of them and confirms from the owner's answer.
#include <cmath>
#include <optional>
#include <set>

#include "cli/cli.hpp"
#include "lcm_control/pid_gains_t.hpp"
#include "tools/lib/support.hpp"

namespace lcm_control::tools {
namespace {

class GainsClient {
 public:
  GainsClient(Bus& bus, std::string owner) : bus_(bus), owner_(std::move(owner)) {
    subscribe_guarded<&GainsClient::on_answer>(bus_, bus_.channel(gains_channel(owner_)), this);
  }
  // Sends req and waits up to timeout_s for the owner's answer, sending it
  // again every second (a query or the same gains twice change nothing) in
  // case UDP lost the request or the answer.
  pid_gains_t call(pid_gains_t req, double timeout_s) {
    req.owner = owner_;
    ids_.clear();
    answered_ = false;
    const int64_t end = monotonic_us() + int64_t(timeout_s * 1e6);
    while (!answered_ && !stop_requested()) {
      const double left = double(end - monotonic_us()) / 1e6;
      if (left <= 0) break;
      req.utime = wall_us();
      req.request_id = new_request_id();
      ids_.insert(req.request_id);
      bus_.publish(gains_set_channel(owner_), req);
      pump_until(bus_, [&] { return answered_; }, std::min(1.0, left));
    }
    if (!answered_)
      throw BusError(fmt::format(
          "no answer from '{}' within {} (sent on '{}', nothing came back on '{}'): is {} running on {}{}?", owner_,
          seconds_text(timeout_s), bus_.channel(gains_set_channel(owner_)), bus_.channel(gains_channel(owner_)),
          owner_ == channels::kSimGainsOwner ? "sim_server" : "controller_manager with '" + owner_ + "' loaded",
          bus_.url(), bus_.ns().empty() ? "" : " with namespace '" + bus_.ns() + "'") +
          (owner_ == channels::kSimGainsOwner ? ""
                                               : " Only controllers with a PID of their own (effort_controllers/..., "
                                                 "velocity_controllers/JointPositionController) answer."));
    return answer_;
  }

 private:
  void on_answer(const lcm::ReceiveBuffer*, const std::string&, const pid_gains_t* m) {
    if (!answered_ && ids_.count(m->request_id)) {
      answer_ = *m;
      answered_ = true;
    }
  }
  Bus& bus_;
  std::string owner_;
  std::set<int64_t> ids_;
  bool answered_ = false;
  pid_gains_t answer_;
};

std::string describe(const pid_gains_t& g) {
  return fmt::format("p {:g}  i {:g}  d {:g}  i_clamp [{:g}, {:g}]  antiwindup {}", g.p, g.i, g.d, g.i_clamp_min,
                     g.i_clamp_max, g.antiwindup ? "true" : "false");
}

bool same(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(a)); }

}  // namespace
}  // namespace lcm_control::tools

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Show or set the PID gains of a joint while it runs (dynamic reconfigure). The owner is sim_server for "
      "gazebo_ros_control/pid_gains, or a controller with its own PID (e.g. effort_controllers/"
      "JointPositionController). Gains not given keep their value; the new gains are confirmed from the owner's echo.\n"
      "Examples:\n"
      "  tune j2                          # print the gains in force\n"
      "  tune j2 --p 150 --d 50           # set p and d of sim_server's j2 PID\n"
      "  tune j2 --owner j2_controller --p 10 --i 1 --i-clamp 2",
      "tune"};
  std::string joint, owner = channels::kSimGainsOwner;
  std::optional<double> p, i, d, i_clamp;
  std::optional<bool> antiwindup;
  double timeout = 3;
  BusFlags bus_flags;
  app.add_option("JOINT", joint, "joint name")->required();
  app.add_option("--owner", owner, "sim_server (default) or a controller name");
  app.add_option("--p", p, "proportional gain");
  app.add_option("--i", i, "integral gain");
  app.add_option("--d", d, "derivative gain");
  app.add_option("--i-clamp", i_clamp, "integral clamp: the integral term stays within [-X, X]")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--antiwindup", antiwindup, "true or false");
  app.add_option("--timeout", timeout, "seconds to wait for each answer")->check(CLI::PositiveNumber);
  add_bus_flags(app, bus_flags);
  return run_program(app, argc, argv, [&] {
    install_stop_signals();
    Bus bus(bus_flags.lcm_url, bus_flags.ns, "", HardwareReader::Direct);
    GainsClient client(bus, owner);
    pid_gains_t q{};
    q.joint = joint;
    q.query = true;
    const pid_gains_t now = client.call(q, timeout);
    if (!now.ok) throw std::runtime_error(fmt::format("{} refused the query for '{}': {}", owner, joint, now.message));
    const bool setting = p || i || d || i_clamp || antiwindup;
    if (!setting) {
      fmt::print("{} ({}): {}\n", joint, owner, describe(now));
      return int(kExitOk);
    }
    pid_gains_t set = now;
    set.query = false;
    set.ok = false;
    set.message.clear();
    set.joint = joint;
    if (p) set.p = *p;
    if (i) set.i = *i;
    if (d) set.d = *d;
    if (i_clamp) {
      set.i_clamp_min = -*i_clamp;
      set.i_clamp_max = *i_clamp;
    }
    if (antiwindup) set.antiwindup = *antiwindup;
    const pid_gains_t echo = client.call(set, timeout);
    if (!echo.ok) throw std::runtime_error(fmt::format("{} refused the gains for '{}': {}", owner, joint, echo.message));
    if (!same(echo.p, set.p) || !same(echo.i, set.i) || !same(echo.d, set.d) ||
        !same(echo.i_clamp_min, set.i_clamp_min) || !same(echo.i_clamp_max, set.i_clamp_max) ||
        echo.antiwindup != set.antiwindup)
      throw std::runtime_error(fmt::format("{} answered ok but the gains in force differ: asked {}, got {}", owner,
                                           describe(set), describe(echo)));
    fmt::print("{} ({}): {}  (was {})\n", joint, owner, describe(echo), describe(now));
    return int(kExitOk);
  });
}
