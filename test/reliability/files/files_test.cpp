// Mutated and hostile input files (issue 18): seeded mutations of our own
// robots' URDFs and YAMLs (byte flips, deleted, duplicated and swapped lines,
// numbers made 1e308 / nan / inf / -0 / 1e-320 / negative, truncation, binary
// garbage, deep YAML nesting, an empty file) and paths that are not files (a
// folder, a FIFO, an unreadable file, a 50 MB file). Each must either load and
// then run finite in Bullet, or be refused with a message naming the file; no
// crash, no hang. In-process through the loader every program uses (and the
// controller check doctor runs), then a sample through the real doctor,
// sim_server and controller_manager, each run bounded and killed by pid.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "controller_manager/manager.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "sim_server/simulation.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lt = lcm_control::testing;
using namespace lcm_control;

namespace {

struct Robot {
  std::string urdf, yaml;
};

std::vector<Robot> robots() {
  return {{"config/turret_bot.urdf", "config/turret_bot.yaml"},
          {"test/robots/ur_like.urdf", "test/robots/ur_like.yaml"},
          {"test/robots/ns_bot.urdf", "test/robots/ns_bot.yaml"},
          {"test/robots/multi_trans_arm.urdf", "test/robots/multi_trans_arm.yaml"},
          {"test/controller_manager/data/test_bot.urdf", "test/controller_manager/data/test_bot.yaml"}};
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

std::string join_lines(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& l : v) s += l + "\n";
  return s;
}

// One seeded mutation of a text file; `what` says which.
class Mutator {
 public:
  explicit Mutator(uint64_t seed) : rng_(seed) {}
  std::string mutate(const std::string& text, std::string& what) {
    auto lines = lines_of(text);
    switch (pick(10)) {
      case 0: {
        std::string s = text;
        for (uint64_t k = 0, n = 1 + pick(6); k < n && !s.empty(); ++k) s[pick(s.size())] ^= char(1u << pick(8));
        what = "bit flips";
        return s;
      }
      case 1:
        if (!lines.empty()) lines.erase(lines.begin() + long(pick(lines.size())));
        what = "a line deleted";
        return join_lines(lines);
      case 2:
        if (lines.size() > 1) std::swap(lines[pick(lines.size())], lines[pick(lines.size())]);
        what = "two lines swapped";
        return join_lines(lines);
      case 3:
        if (!lines.empty()) {
          const size_t k = pick(lines.size());
          lines.insert(lines.begin() + long(k), lines[k]);
        }
        what = "a line duplicated";
        return join_lines(lines);
      case 4:
      case 5:
      case 6: {
        what = "a number replaced";
        return replace_number(text);
      }
      case 7:
        what = "truncated";
        return text.substr(0, pick(text.size() + 1));
      case 8: {
        std::string s = text;
        const size_t at = pick(s.size() + 1);
        std::string junk(1 + pick(64), '\0');
        for (auto& c : junk) c = char(rng_());
        s.insert(at, junk);
        what = "binary garbage inserted";
        return s;
      }
      default:
        what = "emptied";
        return pick(2) ? "" : "\n\n";
    }
  }
  uint64_t pick(uint64_t n) { return n == 0 ? 0 : rng_() % n; }

 private:
  std::string replace_number(const std::string& s) {
    std::vector<std::pair<size_t, size_t>> numbers;  // (start, length)
    for (size_t k = 0; k < s.size();) {
      if (std::isdigit(static_cast<unsigned char>(s[k])) &&
          (k == 0 || !std::isalpha(static_cast<unsigned char>(s[k - 1])))) {
        size_t e = k;
        while (e < s.size() && (std::isdigit(static_cast<unsigned char>(s[e])) || s[e] == '.' || s[e] == 'e'))
          ++e;
        numbers.emplace_back(k, e - k);
        k = e;
      } else {
        ++k;
      }
    }
    if (numbers.empty()) return s;
    static const char* values[] = {"1e308", "-1e308", "nan", "inf", "-0", "1e-320", "-5", "0", "1e9", "-1"};
    const auto [at, len] = numbers[pick(numbers.size())];
    std::string out = s;
    out.replace(at, len, values[pick(10)]);
    return out;
  }
  std::mt19937_64 rng_;
};

std::string write(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string p = dir + "/" + name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

enum class Outcome { RanFinite, Refused, NotNamed, NonFinite, OtherError };

// What every program does with the pair first: load and check it; then what sim_server does: 200 steps of Bullet.
Outcome load_and_run(const std::string& urdf, const std::string& yaml, std::string& why) {
  try {
    RobotModel model = load_robot_model(urdf, yaml);
    sim::Simulation sim(model, {});
    for (int k = 0; k < 200; ++k) sim.step();
    const auto& a = sim.actuators();
    for (int k = 0; k < a.size(); ++k)
      if (!std::isfinite(a.position(k)) || !std::isfinite(a.velocity(k)) || !std::isfinite(a.effort(k))) {
        why = "non-finite state after 200 steps";
        return Outcome::NonFinite;
      }
    return Outcome::RanFinite;
  } catch (const ModelError& e) {
    why = e.what();
  } catch (const std::exception& e) {
    why = e.what();
    if (why.find(urdf) == std::string::npos && why.find(yaml) == std::string::npos) return Outcome::OtherError;
  }
  return why.find(urdf) != std::string::npos || why.find(yaml) != std::string::npos ? Outcome::Refused
                                                                                   : Outcome::NotNamed;
}

int mutations() {
  const char* v = std::getenv("LCM_CONTROL_FILE_MUTATIONS");
  return v && *v ? std::atoi(v) : 1200;
}

}  // namespace

TEST(MutatedFiles, EveryMutationLoadsAndRunsFiniteOrIsRefusedNamingTheFile) {
  const std::string dir = lt::temp_dir("mutated_files");
  Mutator m(18);
  const auto all = robots();
  int ran = 0, refused = 0, hangs = 0;
  std::vector<std::string> failures;
  const int n = mutations();
  for (int k = 0; k < n; ++k) {
    const Robot& r = all[size_t(k) % all.size()];
    std::string urdf = slurp(lt::source(r.urdf)), yaml = slurp(lt::source(r.yaml)), what;
    const bool urdf_side = m.pick(3) != 0;
    (urdf_side ? urdf : yaml) = m.mutate(urdf_side ? urdf : yaml, what);
    const std::string u = write(dir, "m" + std::to_string(k) + ".urdf", urdf);
    const std::string y = write(dir, "m" + std::to_string(k) + ".yaml", yaml);
    std::string why;
    const auto t0 = std::chrono::steady_clock::now();
    const Outcome o = load_and_run(u, y, why);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (s > 10) ++hangs;
    if (o == Outcome::RanFinite) ++ran;
    if (o == Outcome::Refused) ++refused;
    if (o != Outcome::RanFinite && o != Outcome::Refused) {
      failures.push_back(fmt::format("{} ({} of {} in {}): {}", u, what, urdf_side ? "the URDF" : "the YAML",
                                     r.urdf, why.substr(0, 300)));
    } else {
      std::remove(u.c_str());
      std::remove(y.c_str());
    }
  }
  std::printf("RELIABILITY|files|loader + 200 Bullet steps (in-process, what every program loads)|tried=%d|ok=%d|"
              "crashes=0|hangs=%d|loaded and ran finite %d, refused naming the file %d, other %zu\n",
              n, ran + refused, hangs, ran, refused, failures.size());
  for (const auto& f : failures) ADD_FAILURE() << f;
  EXPECT_EQ(hangs, 0);
}

TEST(MutatedFiles, PathsThatAreNotReadableFilesAreRefusedAtOnce) {
  const std::string dir = lt::temp_dir("hostile_paths");
  const std::string yaml = lt::source("config/turret_bot.yaml");
  const std::string fifo = dir + "/fifo.urdf";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string unreadable = write(dir, "unreadable.urdf", slurp(lt::source("config/turret_bot.urdf")));
  chmod(unreadable.c_str(), 0);
  std::string big(50u << 20, ' ');
  big.replace(0, 6, "<robot");
  const std::string huge = write(dir, "huge.urdf", big);
  const std::string deep = write(dir, "deep.yaml", std::string(100000, '[') + std::string(100000, ']'));
  const std::string deep_map = write(dir, "deep_map.yaml", [] {
    std::string s;
    for (int k = 0; k < 20000; ++k) s += std::string(size_t(k % 200), ' ') + "a:\n";
    return s;
  }());
  struct Case {
    std::string urdf, yaml;
    bool valid_yaml = false;  // deeply indented but valid: the servers may run it (no controllers in it)
  };
  int ok = 0;
  std::vector<Case> cases{{dir, yaml},
                          {fifo, yaml},
                          {huge, yaml},
                          {lt::source("config/turret_bot.urdf"), deep},
                          {lt::source("config/turret_bot.urdf"), deep_map, true},
                          {lt::source("config/turret_bot.urdf"), dir + "/missing.yaml"}};
  if (geteuid() != 0) cases.push_back({unreadable, yaml});  // root reads it anyway
  for (const auto& c : cases) {
    for (const std::string prog : {"doctor", "sim_server", "controller_manager"}) {
      const std::string url = lt::unique_lcm_url();
      std::vector<std::string> argv{lt::bin(prog), "--urdf", c.urdf, "--config", c.yaml};
      if (prog != "doctor") argv.insert(argv.end(), {"--lcm-url", url});
      lt::ChildProcess p(argv);
      int rc = p.wait(5);
      const bool ran = rc == -1 && c.valid_yaml && prog != "doctor";
      if (rc == -1) rc = p.stop(5);
      const bool named = p.output().find(c.urdf == lt::source("config/turret_bot.urdf") ? c.yaml : c.urdf) !=
                         std::string::npos;
      if ((rc > 0 && rc < 128 && named) || (ran && rc == 0)) {
        ++ok;
      } else {
        ADD_FAILURE() << prog << " " << c.urdf << " " << c.yaml << ": exit " << rc << "\n" << p.output().substr(0, 600);
      }
    }
  }
  std::printf("RELIABILITY|files|a folder, a FIFO, a 50 MB file, 100,000-deep YAML, 20,000 nested keys, a missing "
              "file%s|tried=%zu|ok=%d|crashes=0|hangs=0|through doctor, sim_server and controller_manager\n",
              geteuid() != 0 ? ", an unreadable file" : "", cases.size() * 3, ok);
  chmod(unreadable.c_str(), 0600);
}

// A sample of the mutations through the real programs: doctor (exit 0 or a message naming the file), sim_server for
// 0.2 s of real time (hardware/state finite) and controller_manager until ready (then SIGINT: exit 0).
TEST(MutatedFiles, ASampleThroughDoctorSimServerAndControllerManager) {
  const char* v = std::getenv("LCM_CONTROL_FILE_PROCESS_SAMPLE");
  const int n = v && *v ? std::atoi(v) : 40;
  const std::string dir = lt::temp_dir("mutated_processes");
  Mutator m(1118);
  const auto all = robots();
  int tried = 0, ok = 0, hangs = 0, crashes = 0;
  for (int k = 0; k < n; ++k) {
    const Robot& r = all[size_t(k) % all.size()];
    std::string urdf = slurp(lt::source(r.urdf)), yaml = slurp(lt::source(r.yaml)), what;
    const bool urdf_side = m.pick(3) != 0;
    (urdf_side ? urdf : yaml) = m.mutate(urdf_side ? urdf : yaml, what);
    const std::string u = write(dir, "p" + std::to_string(k) + ".urdf", urdf);
    const std::string y = write(dir, "p" + std::to_string(k) + ".yaml", yaml);
    const std::string url = lt::unique_lcm_url();
    auto named = [&](const std::string& out) {
      return out.find(u) != std::string::npos || out.find(y) != std::string::npos;
    };
    auto judge = [&](const char* prog, int rc, bool finite, const std::string& out) {
      ++tried;
      if (rc == -1) ++hangs;
      if (rc >= 128) ++crashes;
      const bool good = (rc == 0 && finite) || (rc > 0 && rc < 128 && named(out));
      if (good)
        ++ok;
      else
        ADD_FAILURE() << prog << " on " << u << " / " << y << " (" << what << "): exit " << rc
                      << (finite ? "" : ", non-finite hardware/state") << "\n"
                      << out.substr(0, 600);
    };
    {
      lt::ChildProcess doctor({lt::bin("doctor"), "--urdf", u, "--config", y});
      const int rc = doctor.wait(20);
      judge("doctor", rc, true, doctor.output());
    }
    {
      lcm::LCM lc(url);
      lt::Recorder<hardware_state_t> states(lc, "hardware/state");
      lt::ChildProcess sim({lt::bin("sim_server"), "--urdf", u, "--config", y, "--duration", "0.2", "--lcm-url", url});
      int rc = -1;
      for (int w = 0; w < 200 && rc == -1; ++w) {
        lt::pump_until(lc, [] { return false; }, 0.05);
        rc = sim.wait(0.0);
      }
      if (rc == -1) sim.stop(2);
      bool finite = true;
      for (const auto& s : states.messages)
        for (size_t j = 0; j < s.position.size(); ++j)
          finite = finite && std::isfinite(s.position[j]) && std::isfinite(s.velocity[j]) && std::isfinite(s.effort[j]);
      judge("sim_server", rc, finite, sim.output());
    }
    {
      lt::ChildProcess cm({lt::bin("controller_manager"), "--urdf", u, "--config", y, "--lcm-url", url});
      int rc = -1;
      if (cm.wait_for_output("ready (", 10))
        rc = cm.stop(5);
      else
        rc = cm.wait(1);
      judge("controller_manager", rc, true, cm.output());
    }
  }
  std::printf("RELIABILITY|files|mutated files through doctor, sim_server, controller_manager (processes)|tried=%d|ok=%d|"
              "crashes=%d|hangs=%d|%d files, each program bounded and killed by pid\n",
              tried, ok, crashes, hangs, n);
}
