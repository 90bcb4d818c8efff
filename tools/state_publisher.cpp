// state-publisher: robot_state_publisher for LCM. Turns joint_states into the
// world pose of every URDF link (forward kinematics) on `link_poses`.
#include <map>

#include "cli/cli.hpp"
#include "bus/messages.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/link_poses_t.hpp"
#include "description/kinematics.hpp"
#include "tools/lib/clients/wait.hpp"
#include "description/load.hpp"

namespace lcm_control::tools {
namespace {

class StatePublisher {
 public:
  StatePublisher(Bus& bus, const RobotModel& model, double max_rate) : bus_(bus), model_(model) {
    min_period_us_ = max_rate > 0 ? int64_t(1e6 / max_rate) : 0;
    subscribe_guarded<&StatePublisher::on_joint_states>(bus, bus.channel(channels::kJointStates), this);
  }
  int64_t published() const { return published_; }
  int64_t dropped() const { return dropped_; }

 private:
  void on_joint_states(const lcm::ReceiveBuffer*, const std::string& channel, const joint_state_t* m) {
    const std::string problem = check(*m);
    if (!problem.empty() || !all_finite(m->position)) {
      if (dropped_++ == 0)
        fmt::print(stderr, "state-publisher: dropping a bad message on {}: {}\n", channel,
                   problem.empty() ? "position contains NaN or Inf" : problem);
      return;
    }
    const int64_t now = monotonic_us();
    if (min_period_us_ > 0 && published_ > 0 && now - last_us_ < min_period_us_) return;
    last_us_ = now;
    for (int k = 0; k < m->num_joints; ++k) q_[m->name[k]] = m->position[k];
    const auto poses = forward_kinematics(model_, q_);
    link_poses_t out;
    out.utime = m->utime;
    out.num_links = int32_t(poses.size());
    for (const auto& p : poses) {
      out.name.push_back(p.link);
      const Eigen::Vector3d t = p.pose.translation();
      const Eigen::Quaterniond r(p.pose.linear());
      out.position.push_back({t.x(), t.y(), t.z()});
      out.orientation.push_back({r.w(), r.x(), r.y(), r.z()});
    }
    bus_.publish(channels::kLinkPoses, out);
    ++published_;
  }

  Bus& bus_;
  const RobotModel& model_;
  std::map<std::string, double> q_;
  int64_t min_period_us_ = 0, last_us_ = 0, published_ = 0, dropped_ = 0;
};

}  // namespace
}  // namespace lcm_control::tools

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Publish the world pose of every URDF link on `link_poses` (lcm_control.link_poses_t: position x y z, "
      "quaternion w x y z), computed from `joint_states` (robot_state_publisher). Joints not in joint_states stay at "
      "0; the last value of each joint is kept.\n"
      "Example: state-publisher --urdf config/turret_bot.urdf",
      "state-publisher"};
  std::string urdf;
  std::vector<std::string> config;
  double max_rate = 0;
  std::vector<std::string> package_path;
  BusFlags bus_flags;
  app.add_option("--urdf", urdf, "the robot's URDF (or .urdf.xacro, with --xacro-arg)")->required();
  add_config_flag(app, config, "ros_control YAML, checked together with the URDF (optional)");
  app.add_option("--max-rate", max_rate, "publish at most this many times per second (default: every joint_states)")
      ->check(CLI::NonNegativeNumber);
  add_package_path_flag(app, package_path);
  std::vector<std::string> args;
  add_arg_flag(app, args);
  std::vector<std::string> xacro_args;
  add_xacro_arg_flag(app, xacro_args);
  std::vector<std::string> simulate_hardware;
  add_simulate_hardware_flag(app, simulate_hardware);
  add_bus_flags(app, bus_flags);
  return run_program(app, argc, argv, [&] {
    const RobotModel model = load_robot_model(urdf, config, load_options(package_path, bus_flags, args, xacro_args, simulate_hardware));
    install_stop_signals();
    Bus bus(bus_flags.lcm_url, model.ns, "", HardwareReader::Direct);
    StatePublisher pub(bus, model, max_rate);
    fmt::print(stderr, "state-publisher: ready: {} links of '{}', {} -> {}\n", model.links.size(), model.name,
               bus.channel(channels::kJointStates), bus.channel(channels::kLinkPoses));
    while (!stop_requested())
      handle_bus(bus, 100);
    fmt::print(stderr, "state-publisher: published {} link_poses{}\n", pub.published(),
               pub.dropped() ? fmt::format(", dropped {} bad joint_states", pub.dropped()) : "");
    return int(kExitOk);
  });
}
