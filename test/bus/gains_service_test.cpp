// common/gains_service: the answer to a pid_gains_t request, as sim_server and every controller with PIDs give it.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "bus/gains_service.hpp"

using namespace lcm_control;

namespace {
bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

struct Pids {
  std::map<std::string, PidGains> gains;
  PidLookup lookup(bool explain = false) {
    PidLookup l;
    l.joints = [this] {
      std::vector<std::string> v;
      for (const auto& [j, g] : gains) v.push_back(j);
      return v;
    };
    l.get = [this](const std::string& j) { return gains.at(j); };
    l.set = [this](const std::string& j, const PidGains& g) { gains[j] = g; };
    if (explain) l.why_none = [](const std::string& j) { return "joint '" + j + "' runs effort: add pid_gains"; };
    return l;
  }
};

pid_gains_t request(const std::string& joint, double p, bool query = false) {
  pid_gains_t r{};
  r.request_id = 42;
  r.joint = joint;
  r.p = p;
  r.i_clamp_min = -1;
  r.i_clamp_max = 1;
  r.query = query;
  return r;
}
}  // namespace

TEST(GainsService, SetsCheckedGainsAndAnswersWithTheGainsInForce) {
  Pids pids;
  pids.gains["j1"] = PidGains{150, 0, 50, 0, 0, false};
  pid_gains_t a = answer_gains("sim_server", pids.lookup(), request("j1", 160), 7, " from step 9");
  EXPECT_TRUE(a.ok) << a.message;
  EXPECT_EQ(a.request_id, 42);
  EXPECT_EQ(a.utime, 7);
  EXPECT_EQ(a.owner, "sim_server");
  EXPECT_EQ(a.p, 160);
  EXPECT_EQ(pids.gains["j1"].p, 160);
  EXPECT_TRUE(has(a.message, "set gains of 'sim_server' joint 'j1': p 160") && has(a.message, " from step 9"))
      << a.message;

  a = answer_gains("sim_server", pids.lookup(), request("j1", NAN), 8);
  EXPECT_FALSE(a.ok);
  EXPECT_TRUE(has(a.message, "p is not a finite number") && has(a.message, "gains unchanged")) << a.message;
  EXPECT_EQ(a.p, 160);  // the gains in force
  EXPECT_EQ(pids.gains["j1"].p, 160);

  a = answer_gains("sim_server", pids.lookup(), request("", 0, true), 9);  // one PID: no joint needed
  EXPECT_TRUE(a.ok) << a.message;
  EXPECT_EQ(a.joint, "j1");
  EXPECT_EQ(a.p, 160);
}

TEST(GainsService, RefusalsNameTheJointsAndTheOwner) {
  Pids pids;
  pids.gains["a"] = PidGains{1, 0, 0, 0, 0, false};
  pids.gains["b"] = PidGains{2, 0, 0, 0, 0, false};
  pid_gains_t a = answer_gains("arm", pids.lookup(), request("", 5), 0);
  EXPECT_FALSE(a.ok);
  EXPECT_TRUE(has(a.message, "'arm' has PIDs for several joints (a, b); say which in `joint`")) << a.message;

  a = answer_gains("arm", pids.lookup(), request("c", 5), 0);
  EXPECT_FALSE(a.ok);
  EXPECT_TRUE(has(a.message, "'arm' has no PID for joint 'c' (its PIDs: a, b)")) << a.message;
  a = answer_gains("arm", pids.lookup(true), request("c", 5), 0);
  EXPECT_EQ(a.message, "joint 'c' runs effort: add pid_gains");  // the owner's own reason

  pid_gains_t other = request("a", 5);
  other.owner = "leg";
  a = answer_gains("arm", pids.lookup(), other, 0);
  EXPECT_FALSE(a.ok);
  EXPECT_TRUE(has(a.message, "request owner 'leg' does not match 'arm'")) << a.message;
  EXPECT_EQ(pids.gains["a"].p, 1);
}
