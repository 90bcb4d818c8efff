#include "tools/lib/clients/tune.hpp"

#include <cmath>
#include <optional>
#include <set>

#include "lcm_control/pid_gains_t.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"

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

void add_tune_flags(CLI::App& app, TuneFlags& f) {
  app.add_option("JOINT", f.joint, "joint name")->required();
  app.add_option("--owner", f.owner, "sim_server (default) or a controller name");
  app.add_option("--p", f.p, "proportional gain");
  app.add_option("--i", f.i, "integral gain");
  app.add_option("--d", f.d, "derivative gain");
  app.add_option("--i-clamp", f.i_clamp, "integral clamp: the integral term stays within [-X, X]")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--antiwindup", f.antiwindup, "true or false");
  app.add_option("--timeout", f.timeout, "seconds to wait for each answer")->check(CLI::PositiveNumber);
  add_bus_flags(app, f.bus);
}

int run_tune(const TuneFlags& f) {
  install_stop_signals();
  Bus bus(f.bus.lcm_url, f.bus.ns, "", HardwareReader::Direct);
  GainsClient client(bus, f.owner);
  pid_gains_t q{};
  q.joint = f.joint;
  q.query = true;
  const pid_gains_t now = client.call(q, f.timeout);
  if (!now.ok) throw std::runtime_error(fmt::format("{} refused the query for '{}': {}", f.owner, f.joint, now.message));
  const bool setting = f.p || f.i || f.d || f.i_clamp || f.antiwindup;
  if (!setting) {
    fmt::print("{} ({}): {}\n", f.joint, f.owner, describe(now));
    return int(kExitOk);
  }
  pid_gains_t set = now;
  set.query = false;
  set.ok = false;
  set.message.clear();
  set.joint = f.joint;
  if (f.p) set.p = *f.p;
  if (f.i) set.i = *f.i;
  if (f.d) set.d = *f.d;
  if (f.i_clamp) {
    set.i_clamp_min = -*f.i_clamp;
    set.i_clamp_max = *f.i_clamp;
  }
  if (f.antiwindup) set.antiwindup = *f.antiwindup;
  const pid_gains_t echo = client.call(set, f.timeout);
  if (!echo.ok) throw std::runtime_error(fmt::format("{} refused the gains for '{}': {}", f.owner, f.joint, echo.message));
  if (!same(echo.p, set.p) || !same(echo.i, set.i) || !same(echo.d, set.d) ||
      !same(echo.i_clamp_min, set.i_clamp_min) || !same(echo.i_clamp_max, set.i_clamp_max) ||
      echo.antiwindup != set.antiwindup)
    throw std::runtime_error(fmt::format("{} answered ok but the gains in force differ: asked {}, got {}", f.owner,
                                         describe(set), describe(echo)));
  fmt::print("{} ({}): {}  (was {})\n", f.joint, f.owner, describe(echo), describe(now));
  return int(kExitOk);
}

}  // namespace lcm_control::tools
