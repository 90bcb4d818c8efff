#include "tools/lib/scenarios/scenario_suite.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sched.h>
#include <signal.h>
#include <sys/wait.h>
#include <tinyxml2.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "description/robot_model.hpp"
#include "tools/lib/scenarios/scenario.hpp"

namespace fs = std::filesystem;

namespace lcm_control::tools {

namespace {

nlohmann::json to_json(const ScenarioResult& r) {
  nlohmann::json checks = nlohmann::json::array();
  for (const auto& c : r.checks) checks.push_back({{"name", c.name}, {"where", c.where}, {"passed", c.passed}, {"detail", c.detail}});
  return {{"outcome", int(r.outcome)}, {"name", r.name}, {"file", r.file}, {"why", r.why}, {"checks", checks},
          {"sim_s", r.sim_s}, {"wall_s", r.wall_s}, {"steps", r.steps}, {"messages", r.messages}};
}

ScenarioResult from_json(const nlohmann::json& j) {
  ScenarioResult r;
  r.outcome = ScenarioResult::Outcome(j.at("outcome").get<int>());
  r.name = j.at("name");
  r.file = j.at("file");
  r.why = j.at("why");
  for (const auto& c : j.at("checks")) r.checks.push_back({c.at("name"), c.at("where"), c.at("passed"), c.at("detail")});
  r.sim_s = j.at("sim_s");
  r.wall_s = j.at("wall_s");
  r.steps = j.at("steps");
  r.messages = j.at("messages");
  return r;
}

int cpus() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

// A scenario in a child process: the result comes back as JSON in a file; a child that dies or overruns is an Error.
struct Child {
  pid_t pid = -1;
  size_t index = 0;
  std::string result_file;
  std::chrono::steady_clock::time_point started;
};

ScenarioResult collect(const Child& c, const std::string& file, int status, bool timed_out, double timeout_s) {
  ScenarioResult r;
  r.file = file;
  r.name = scenario_name(file);
  std::ifstream in(c.result_file);
  std::stringstream text;
  text << in.rdbuf();
  std::error_code ec;
  fs::remove(c.result_file, ec);
  if (!timed_out && WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    try {
      return from_json(nlohmann::json::parse(text.str()));
    } catch (const std::exception& e) {
      r.why = std::string("its result could not be read: ") + e.what();
      return r;
    }
  }
  r.why = timed_out ? fmt::format("did not finish within {:g} s of wall time (stopped)", timeout_s)
          : WIFSIGNALED(status) ? fmt::format("its process died of signal {} ({})", WTERMSIG(status), strsignal(WTERMSIG(status)))
                                : fmt::format("its process exited {}", WEXITSTATUS(status));
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - c.started).count();
  return r;
}

std::vector<ScenarioResult> run_all(const std::vector<std::string>& files, const SuiteOptions& o) {
  ScenarioRunOptions ro;
  ro.package_path = o.package_path;
  ro.golden = o.golden;
  const size_t jobs = size_t(o.jobs > 0 ? o.jobs : cpus());
  std::vector<ScenarioResult> results(files.size());
  std::vector<Child> running;
  // The longest first (by sim time), so that no long one starts last while the other CPUs idle; results stay in the
  // files' order.
  std::vector<size_t> order(files.size());
  std::vector<double> sim_s(files.size(), 0);
  for (size_t k = 0; k < files.size(); ++k) {
    order[k] = k;
    try {
      sim_s[k] = YAML::LoadFile(files[k])["duration"].as<double>(0);
    } catch (const std::exception&) {
      // read again, and named, by its run
    }
  }
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return sim_s[a] > sim_s[b]; });
  size_t next = 0;
  std::fflush(stdout);
  std::fflush(stderr);
  while (next < files.size() || !running.empty()) {
    while (next < files.size() && running.size() < jobs) {
      Child c;
      c.index = order[next++];
      std::string pattern = (fs::temp_directory_path() / "lcm_control_scenario_XXXXXX").string();
      const int fd = mkstemp(pattern.data());
      if (fd < 0) {
        results[c.index].file = files[c.index];
        results[c.index].why = std::string("cannot make a file for its result: ") + std::strerror(errno);
        continue;
      }
      close(fd);
      c.result_file = pattern;
      c.started = std::chrono::steady_clock::now();
      c.pid = fork();
      if (c.pid == 0) {
        int code = 1;
        try {
          const ScenarioResult r = run_scenario(files[c.index], ro);
          std::ofstream(c.result_file) << to_json(r).dump();
          code = 0;
        } catch (...) {
        }
        std::fflush(stdout);
        _exit(code);
      }
      if (c.pid < 0) {
        results[c.index].file = files[c.index];
        results[c.index].why = std::string("cannot start a process: ") + std::strerror(errno);
        std::error_code ec;
        fs::remove(c.result_file, ec);
        continue;
      }
      running.push_back(c);
    }
    // The children that ended, each reaped by its own pid; then those past their time, stopped and reaped.
    bool any = false;
    for (size_t k = 0; k < running.size();) {
      int status = 0;
      const pid_t pid = running[k].pid;
      const bool late = std::chrono::duration<double>(std::chrono::steady_clock::now() - running[k].started).count() >
                        o.timeout_s;
      pid_t done = waitpid(pid, &status, WNOHANG);
      if (done == 0 && late) {
        kill(pid, SIGKILL);
        done = waitpid(pid, &status, 0);
      }
      if (done != pid) {
        ++k;
        continue;
      }
      results[running[k].index] = collect(running[k], files[running[k].index], status, done == pid && late &&
                                          !(WIFEXITED(status) && WEXITSTATUS(status) == 0), o.timeout_s);
      running.erase(running.begin() + long(k));
      any = true;
    }
    if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return results;
}

}  // namespace

std::vector<std::string> scenario_files(const std::vector<std::string>& paths) {
  std::vector<std::string> out, problems;
  for (const auto& p : paths) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      std::vector<std::string> found;
      for (const auto& e : fs::recursive_directory_iterator(p, ec)) {
        const std::string name = e.path().filename().string();
        if (e.is_regular_file() && name.size() > 14 && name.compare(name.size() - 14, 14, ".scenario.yaml") == 0)
          found.push_back(e.path().string());
      }
      if (found.empty()) problems.push_back(fmt::format("{}: no *.scenario.yaml in this folder", p));
      std::sort(found.begin(), found.end());
      out.insert(out.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(p, ec)) {
      out.push_back(p);
    } else {
      problems.push_back(fmt::format("{}: no such scenario file or folder", p));
    }
  }
  if (!problems.empty()) throw ModelError(problems);
  return out;
}

std::string results_table(const std::vector<ScenarioResult>& results, bool verbose) {
  size_t width = 8;
  for (const auto& r : results) width = std::max(width, r.name.size());
  std::string out = fmt::format("{:<{}}  {:<7}  {:>7}  {:>7}  {:>6}\n", "scenario", width, "result", "sim s", "wall s", "checks");
  int counts[4] = {0, 0, 0, 0};
  double wall = 0;
  for (const auto& r : results) {
    ++counts[int(r.outcome)];
    wall += r.wall_s;
    const auto passed = std::count_if(r.checks.begin(), r.checks.end(), [](const CheckResult& c) { return c.passed; });
    out += fmt::format("{:<{}}  {:<7}  {:>7.3f}  {:>7.2f}  {:>6}\n", r.name, width, outcome_name(r.outcome), r.sim_s,
                       r.wall_s, fmt::format("{}/{}", passed, r.checks.size()));
    for (const auto& c : r.checks)
      if (!c.passed || verbose) out += fmt::format("    {} {} ({}): {}\n", c.passed ? "pass" : "FAIL", c.name, c.where, c.detail);
    if (!r.why.empty()) {
      std::istringstream lines(r.why);
      for (std::string line; std::getline(lines, line);)
        out += fmt::format("    {} {}\n", r.outcome == ScenarioResult::Outcome::Skipped ? "skipped:" : "error:", line);
    }
  }
  out += fmt::format("{} scenario(s): {} passed, {} failed, {} error(s), {} skipped ({:.2f} s of wall time summed "
                     "over them)\n",
                     results.size(), counts[0], counts[1], counts[3], counts[2], wall);
  return out;
}

std::string junit_xml(const std::vector<ScenarioResult>& results) {
  tinyxml2::XMLPrinter p;
  p.PushHeader(false, true);
  int failures = 0, errors = 0, skipped = 0;
  double time = 0;
  for (const auto& r : results) {
    failures += r.outcome == ScenarioResult::Outcome::Failed;
    errors += r.outcome == ScenarioResult::Outcome::Error;
    skipped += r.outcome == ScenarioResult::Outcome::Skipped;
    time += r.wall_s;
  }
  p.OpenElement("testsuites");
  p.OpenElement("testsuite");
  p.PushAttribute("name", "scenarios");
  p.PushAttribute("tests", int(results.size()));
  p.PushAttribute("failures", failures);
  p.PushAttribute("errors", errors);
  p.PushAttribute("skipped", skipped);
  p.PushAttribute("time", fmt::format("{:.3f}", time).c_str());
  for (const auto& r : results) {
    p.OpenElement("testcase");
    p.PushAttribute("classname", "scenarios");
    p.PushAttribute("name", r.name.c_str());
    p.PushAttribute("file", r.file.c_str());
    p.PushAttribute("time", fmt::format("{:.3f}", r.wall_s).c_str());
    std::string all;
    for (const auto& c : r.checks) all += fmt::format("{} {} ({}): {}\n", c.passed ? "pass" : "FAIL", c.name, c.where, c.detail);
    if (r.outcome == ScenarioResult::Outcome::Failed) {
      for (const auto& c : r.checks)
        if (!c.passed) {
          p.OpenElement("failure");
          p.PushAttribute("message", fmt::format("{}: {}", c.name, c.detail).c_str());
          p.PushAttribute("type", "check");
          p.PushText(c.where.c_str());
          p.CloseElement();
        }
    } else if (r.outcome == ScenarioResult::Outcome::Error) {
      p.OpenElement("error");
      p.PushAttribute("message", r.why.substr(0, r.why.find('\n')).c_str());
      p.PushText(r.why.c_str());
      p.CloseElement();
    } else if (r.outcome == ScenarioResult::Outcome::Skipped) {
      p.OpenElement("skipped");
      p.PushAttribute("message", r.why.c_str());
      p.CloseElement();
    }
    p.OpenElement("system-out");
    p.PushText(all.c_str());
    p.CloseElement();
    p.CloseElement();
  }
  p.CloseElement();
  p.CloseElement();
  return p.CStr();
}

int run_scenarios(const SuiteOptions& o) {
  const std::vector<std::string> files = scenario_files(o.paths);
  const std::vector<ScenarioResult> results = run_all(files, o);
  std::fputs(results_table(results, o.verbose).c_str(), stdout);
  if (!o.junit.empty()) {
    std::ofstream out(o.junit);
    out << junit_xml(results);
    if (!out) throw std::runtime_error(fmt::format("cannot write the JUnit XML to {}", o.junit));
  }
  int code = std::all_of(results.begin(), results.end(),
                         [](const ScenarioResult& r) { return r.outcome == ScenarioResult::Outcome::Skipped; })
                 ? o.skipped_exit
                 : 0;
  for (const auto& r : results) {
    if (r.outcome == ScenarioResult::Outcome::Error) code = 2;
    if (r.outcome == ScenarioResult::Outcome::Failed && code == 0) code = 1;
  }
  return code;
}

int record_scenario(const std::string& file, const std::string& log, const std::vector<std::string>& package_path) {
  ScenarioRunOptions ro;
  ro.package_path = package_path;
  ro.record_log = log;
  const ScenarioResult r = run_scenario(file, ro);
  std::fputs(results_table({r}, true).c_str(), stdout);
  if (r.outcome == ScenarioResult::Outcome::Passed)
    std::printf("recorded %lld messages to %s: `scenario run` replays it when the scenario names it (golden: %s)\n",
                static_cast<long long>(r.messages), log.c_str(), fs::path(log).filename().c_str());
  else
    std::printf("not a golden log: the scenario did not pass (%s)\n", log.c_str());
  return r.outcome == ScenarioResult::Outcome::Passed ? 0 : r.outcome == ScenarioResult::Outcome::Error ? 2 : 1;
}

}  // namespace lcm_control::tools
