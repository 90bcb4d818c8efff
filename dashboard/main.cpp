// dashboard: the robot in a browser. Serves a page (the robot in 3D from its URDF, live plots of any field,
// sliders and expressions for command channels, PID gains, the controllers and their switches, e-stop, loop
// statistics) and streams the bus to it over a WebSocket, each channel's newest message at the display rate.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <thread>

#include "cli/cli.hpp"
#include "control/expression.hpp"
#include "description/packages.hpp"
#include "description/robot_file.hpp"
#include "rt/scheduling.hpp"
#include "dashboard/requests.hpp"
#include "dashboard/throttle.hpp"
#include "dashboard/web_server.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "tools/lib/cm_client.hpp"
#include "tools/lib/message_json.hpp"
#include "tools/lib/message_text.hpp"
#include "tools/lib/support.hpp"
#include "tools/lib/time_base.hpp"

namespace lcm_control::dashboard {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using tools::CmClient;

std::string dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }
std::string dump(const nlohmann::ordered_json& j) {
  return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

// What the server's threads hand the bus thread: browsers that came or went, and what they sent.
class Inbox {
 public:
  void push(int conn, std::string text) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (items_.size() < kMax) items_.emplace_back(conn, std::move(text));
  }
  std::deque<std::pair<int, std::string>> take() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(items_, {});
  }

 private:
  static constexpr size_t kMax = 10000;
  std::mutex mutex_;
  std::deque<std::pair<int, std::string>> items_;
};

json controller_list_json(const cm_response_t& r) {
  json list = json::array();
  for (const auto& c : r.controllers)
    list.push_back({{"name", c.name}, {"type", c.type}, {"state", c.state}, {"interface", c.hardware_interface},
                    {"joints", c.joints}, {"command_type", c.command_type}, {"command_channel", c.command_channel},
                    {"command_width", c.command_width}, {"command_quantity", c.command_quantity},
                    {"publishes", c.publishes}});
  return {{"kind", "controllers"}, {"ok", true}, {"controllers", list}, {"hardware", r.hardware},
          {"hardware_age_us", r.hardware_age_us}};
}

// The controller manager's services on a thread and an LCM instance of their own, so that a manager that does not
// answer never holds up the stream: the list every second while a browser looks, and the calls browsers make.
class CmWorker {
 public:
  CmWorker(const BusFlags& flags, WebServer& web, double timeout_s)
      : bus_(flags.lcm_url, flags.ns), web_(web), timeout_s_(timeout_s), thread_([this] { run(); }) {}
  ~CmWorker() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  void call(int conn, int64_t id, CmCall c) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (jobs_.size() < 100) jobs_.push_back(Job{conn, id, std::move(c)});
    }
    cv_.notify_all();
  }
  std::string last_list() {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_list_;
  }

 private:
  struct Job {
    int conn;
    int64_t id;
    CmCall call;
  };
  void run() {
    CmClient cm(bus_, "dashboard");
    int64_t next_list = 0;
    while (true) {
      std::optional<Job> job;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        cv_.wait_for(lock, std::chrono::milliseconds(std::max<int64_t>(0, (next_list - monotonic_us()) / 1000)),
                     [&] { return done_ || !jobs_.empty() || monotonic_us() >= next_list; });
        if (done_) return;
        if (!jobs_.empty()) {
          job = std::move(jobs_.front());
          jobs_.pop_front();
        }
      }
      if (job) {
        serve(cm, *job);
        next_list = 0;  // show the result at once
        continue;
      }
      next_list = monotonic_us() + 1000000;
      if (web_.connections() > 0) publish_list(cm);  // nobody looking: no request on the robot's bus
    }
  }
  void publish_list(CmClient& cm) {
    json frame;
    try {
      frame = controller_list_json(cm.list(1.0));
    } catch (const std::exception& e) {
      frame = {{"kind", "controllers"}, {"ok", false}, {"message", e.what()}};
    }
    const std::string text = dump(frame);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      last_list_ = text;
    }
    web_.broadcast(text);
  }
  void serve(CmClient& cm, const Job& job) {
    const CmCall& c = job.call;
    cm_response_t r{};
    try {
      if (c.call == "list") r = cm.list(timeout_s_);
      else if (c.call == "load") r = cm.load(c.names, timeout_s_);
      else if (c.call == "unload") r = cm.unload(c.names, timeout_s_);
      else if (c.call == "switch") r = cm.switch_controllers(c.start, c.stop, c.strict, timeout_s_);
      else r = cm.reload(false, timeout_s_);
    } catch (const std::exception& e) {
      web_.send(job.conn, reply_json(job.id, false, e.what()));
      return;
    }
    web_.send(job.conn, reply_json(job.id, r.ok, r.message.empty() ? (r.ok ? "done" : "refused") : r.message));
  }

  Bus bus_;
  WebServer& web_;
  double timeout_s_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<Job> jobs_;
  std::string last_list_;
  bool done_ = false;
  std::thread thread_;  // last: starts once the rest is built
};

// A command channel fed by expressions in i and t at a rate (turret-cmd's job), until stopped, replaced, taken over
// by a publish on the same channel, or its browser goes.
struct ExprStream {
  int conn = 0;
  std::unique_ptr<Expressions> expressions;
  int64_t period_us = 0, next_us = 0, start_us = 0, i = 0;
  std::vector<double> values;
};

// "NS/name" -> "name" for the robot's own channels; other channels keep their full name.
std::string relative(const std::string& channel, const std::string& prefix) {
  return !prefix.empty() && channel.rfind(prefix, 0) == 0 ? channel.substr(prefix.size()) : channel;
}

struct Options {
  BusFlags bus;
  std::string bind = "127.0.0.1", web_root, urdf;
  std::vector<std::string> package_path, xacro_args;
  int port = 8080, nice = 10;
  double rate_hz = 30, duration_s = 0, timeout_s = 5;
  bool read_only = false;
};

// The name the page asks for: the file's own, or for a .xacro the URDF it expands to (robot.urdf.xacro -> robot.urdf).
std::string served_urdf_name(const std::string& urdf) {
  const std::string name = fs::path(urdf).filename().string();
  if (!is_xacro_file(urdf)) return name;
  std::string stem = name;
  for (const char* ext : {".urdf.xacro", ".xacro.urdf", ".xacro"})
    if (stem.size() > std::strlen(ext) && stem.compare(stem.size() - std::strlen(ext), std::string::npos, ext) == 0) {
      stem.resize(stem.size() - std::strlen(ext));
      break;
    }
  return stem + ".urdf";
}

// A .xacro robot file expanded once into a private folder of its own, served in place of the file; removed on exit.
class ExpandedUrdf {
 public:
  ExpandedUrdf(const std::string& urdf, const LoadOptions& options) {
    std::string dir = (fs::temp_directory_path() / "lcm_control_dashboard_XXXXXX").string();
    if (!::mkdtemp(dir.data())) throw std::runtime_error(fmt::format("cannot make a folder in {}", dir));
    dir_ = dir;
    path_ = (fs::path(dir_) / served_urdf_name(urdf)).string();
    std::FILE* f = std::fopen(path_.c_str(), "w");
    const std::string xml = read_robot_file(urdf, options);
    if (!f || std::fwrite(xml.data(), 1, xml.size(), f) != xml.size() || std::fclose(f) != 0)
      throw std::runtime_error(fmt::format("cannot write the expanded URDF {}", path_));
  }
  ~ExpandedUrdf() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  ExpandedUrdf(const ExpandedUrdf&) = delete;
  ExpandedUrdf& operator=(const ExpandedUrdf&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string dir_, path_;
};

class Dashboard {
 public:
  // opened, sent, closed: filled by the web server's threads, which touch nothing else of the dashboard.
  Dashboard(const Options& o, Bus& bus, WebServer& web, Inbox& opened, Inbox& sent, Inbox& closed)
      : o_(o), bus_(bus), web_(web), opened_(opened), inbox_(sent), closed_(closed),
        period_us_(int64_t(1e6 / o.rate_hz)), throttle_(period_us_), clock_(bus, 0.0) {
    prefix_ = bus.channel("");
    own_.insert(bus.channel(channels::kCmRequest));
    const std::string pattern = prefix_.empty() ? ".*" : tools::regex_escape(prefix_) + ".*";
    bus_.lcm().subscribe(pattern, &Dashboard::on_any, this)->setQueueCapacity(10000);
  }

  // What a browser gets first: the bus it looks at, its URDF, the messages' schema (lcmtypes/), and the controllers
  // as last listed.
  void hello(int conn) {
    json h = {{"kind", "hello"}, {"namespace", bus_.ns()}, {"lcm_url", bus_.url()}, {"read_only", o_.read_only},
              {"rate_hz", o_.rate_hz}, {"urdf", nullptr}, {"schema", tools::schema_json()}};
    if (!o_.urdf.empty()) h["urdf"] = "/robot/" + served_urdf_name(o_.urdf);
    web_.send(conn, dump(h));
    const std::string list = cm_ ? cm_->last_list() : "";
    if (!list.empty()) web_.send(conn, list);
  }
  void set_cm(CmWorker* cm) { cm_ = cm; }

  // One pass of the bus thread: it sleeps until the next display period or expression tick, then takes everything
  // the bus queued meanwhile in one go (one wake-up per period instead of one per message: the loop it watches
  // keeps its CPU), then browsers' requests, due messages, expression streams, the status each second.
  void run_once() {
    int64_t until = next_flush_;
    for (const auto& [channel, s] : streams_) until = std::min(until, s.next_us);
    tools::sleep_until_us(until);
    for (int n = 0; n < kMaxDrain && bus_.lcm().handleTimeout(0) > 0; ++n) {
    }
    for (auto& [conn, text] : opened_.take()) hello(conn);
    for (auto& [conn, text] : closed_.take()) stop_streams_of(conn);
    for (auto& [conn, text] : inbox_.take()) serve(conn, text);
    tick_streams();
    const int64_t t = monotonic_us();
    if (t >= next_flush_) {
      flush(t);
      next_flush_ = std::max(next_flush_ + period_us_, t + period_us_ / 2);
    }
    if (t >= next_status_) {
      status(t);
      next_status_ = t + 1000000;
    }
  }

 private:
  void on_any(const lcm::ReceiveBuffer* rb, const std::string& channel) {
    throttle_.offer(channel, rb->data, rb->data_size, monotonic_us(), own_.count(channel) == 0);
  }

  void flush(int64_t now) {
    if (web_.connections() == 0) {
      throttle_.take_due(now);  // nobody to send to: nothing to decode
      return;
    }
    for (auto& d : throttle_.take_due(now)) {
      nlohmann::ordered_json frame;
      frame["kind"] = "msg";
      frame["channel"] = relative(d.channel, prefix_);
      frame["received_s"] = double(wall_us() - (now - d.received_us)) * 1e-6;
      frame["skipped"] = d.skipped;
      try {
        frame["type"] = tools::short_type_name(tools::type_of_payload(d.bytes.data(), d.bytes.size()));
        frame["msg"] = tools::message_to_json(d.bytes.data(), d.bytes.size());
      } catch (const std::exception& e) {
        frame["type"] = "";
        frame["error"] = e.what();
      }
      web_.broadcast(dump(frame));
    }
  }

  void status(int64_t now) {
    json channels = json::array();
    for (const auto& r : throttle_.rates(now))
      channels.push_back({{"channel", relative(r.channel, prefix_)}, {"hz", r.hz}, {"total", r.total}});
    json streams = json::array();
    for (const auto& [channel, s] : streams_) streams.push_back(relative(channel, prefix_));
    const int64_t last = throttle_.last_message_us();
    web_.broadcast(dump(json{{"kind", "status"},
                             {"bus_silent_s", last < 0 ? -1.0 : double(now - last) * 1e-6},
                             {"channels", channels},
                             {"channels_ignored", throttle_.ignored()},
                             {"streams", streams},
                             {"browsers", web_.connections()},
                             {"sim_time", clock_.on_sim()}}));
  }

  void serve(int conn, const std::string& text) {
    const Parsed p = parse_request(text, o_.read_only);
    if (!p.ok()) {
      web_.send(conn, reply_json(p.request.id, false, p.error));
      return;
    }
    const int64_t id = p.request.id;
    std::visit(
        [&](const auto& r) {
          using R = std::decay_t<decltype(r)>;
          if constexpr (std::is_same_v<R, Publish>) {
            publish(conn, id, r);
          } else if constexpr (std::is_same_v<R, CmCall>) {
            if (cm_) cm_->call(conn, id, r);
          } else if constexpr (std::is_same_v<R, ExprStart>) {
            start_stream(conn, id, r);
          } else {
            const bool had = streams_.erase(bus_.channel(r.channel)) > 0;
            web_.send(conn, reply_json(id, true, had ? "stopped " + r.channel : r.channel + " had no stream"));
          }
        },
        p.request.what);
  }

  void publish(int conn, int64_t id, const Publish& r) {
    std::vector<uint8_t> bytes;
    try {
      bytes = tools::message_from_json(r.type, r.fields, clock_.now_us());
    } catch (const std::exception& e) {
      web_.send(conn, reply_json(id, false, e.what()));
      return;
    }
    const std::string channel = bus_.channel(r.channel);
    own_.insert(channel);
    const bool took_over = streams_.erase(channel) > 0;
    if (bus_.lcm().publish(channel, bytes.data(), unsigned(bytes.size())) != 0) {
      web_.send(conn, reply_json(id, false, fmt::format("LCM could not publish on {}", channel)));
      return;
    }
    if (id != 0 || took_over)
      web_.send(conn, reply_json(id, true, took_over ? "published; the expression on " + r.channel + " stopped"
                                                     : "published on " + r.channel));
  }

  void start_stream(int conn, int64_t id, const ExprStart& r) {
    ExprStream s;
    try {
      s.expressions = std::make_unique<Expressions>(r.expressions);
    } catch (const ExpressionError& e) {
      web_.send(conn, reply_json(id, false, e.what()));
      return;
    }
    if (streams_.size() >= kMaxStreams && !streams_.count(bus_.channel(r.channel))) {
      web_.send(conn, reply_json(id, false, fmt::format("at most {} expression streams run at once", kMaxStreams)));
      return;
    }
    s.conn = conn;
    s.period_us = int64_t(1e6 / r.rate_hz);
    s.start_us = s.next_us = monotonic_us();
    s.values.assign(r.expressions.size(), 0.0);
    own_.insert(bus_.channel(r.channel));
    streams_[bus_.channel(r.channel)] = std::move(s);
    web_.send(conn, reply_json(id, true,
                               fmt::format("{} at {} Hz: {}", r.channel, r.rate_hz, fmt::join(r.expressions, ", "))));
  }

  void tick_streams() {
    const int64_t now = monotonic_us();
    for (auto it = streams_.begin(); it != streams_.end();) {
      ExprStream& s = it->second;
      if (now < s.next_us) {
        ++it;
        continue;
      }
      const double t = double(now - s.start_us) * 1e-6;
      const int bad = s.expressions->eval(s.i, t, s.values.data());
      if (bad >= 0) {
        web_.send(s.conn, reply_json(0, false,
                                     fmt::format("the expression '{}' gave no finite number at i={}, t={:.3f}; "
                                                 "its stream on {} stopped",
                                                 s.expressions->texts()[size_t(bad)], s.i, t,
                                                 relative(it->first, prefix_))));
        it = streams_.erase(it);
        continue;
      }
      if (s.values.size() == 1) {
        float64_t m{};
        m.utime = clock_.now_us();
        m.data = s.values[0];
        bus_.lcm().publish(it->first, &m);
      } else {
        float64_array_t m{};
        m.utime = clock_.now_us();
        m.size = int32_t(s.values.size());
        m.data = s.values;
        bus_.lcm().publish(it->first, &m);
      }
      ++s.i;
      s.next_us += s.period_us;
      if (s.next_us < now) s.next_us = now + s.period_us;  // behind (a stall): skip, do not burst
      ++it;
    }
  }

  void stop_streams_of(int conn) {
    for (auto it = streams_.begin(); it != streams_.end();) it = it->second.conn == conn ? streams_.erase(it) : ++it;
  }

  static constexpr size_t kMaxStreams = 64;
  static constexpr int kMaxDrain = 100000;  // messages taken in one pass at most (a flood cannot hold the page up)
  const Options& o_;
  Bus& bus_;
  WebServer& web_;
  Inbox &opened_, &inbox_, &closed_;
  int64_t period_us_;
  Throttle throttle_;
  tools::CommandClock clock_;
  CmWorker* cm_ = nullptr;
  std::string prefix_;
  std::map<std::string, ExprStream> streams_;
  std::set<std::string> own_;  // channels this dashboard publishes on: its echo is not a sign of life
  int64_t next_flush_ = 0, next_status_ = 0;
};

std::string default_web_root() {
  const fs::path exe_dir = fs::read_symlink("/proc/self/exe").parent_path();
  return (exe_dir.parent_path() / "share" / "lcm_control" / "dashboard").string();
}

}  // namespace

int run(Options& o) {
  if (o.web_root.empty()) o.web_root = default_web_root();
  if (!fs::is_regular_file(fs::path(o.web_root) / "index.html"))
    throw std::runtime_error(fmt::format(
        "no page in {} (index.html is missing): build the dashboard page (cmake --build build --target "
        "dashboard_page, which needs npm) or give its folder with --web-root",
        o.web_root));
  std::string urdf_dir;
  if (!o.urdf.empty()) {
    if (!fs::is_regular_file(o.urdf))
      throw std::runtime_error(fmt::format("--urdf {}: no such file", o.urdf));
    urdf_dir = fs::absolute(o.urdf).parent_path().string();
  }
  if (!WebServer::loopback(o.bind))
    std::fprintf(stderr,
                 "dashboard: warning: serving on %s: the dashboard has no authentication, so anyone who can reach "
                 "this port can command the robot (--read-only refuses commands)\n",
                 o.bind.c_str());
  lower_priority(o.nice);  // before any thread: LCM's and civetweb's threads inherit it
  tools::install_stop_signals();
  Bus bus(o.bus.lcm_url, o.bus.ns);
  const auto package_path = package_path_for(o.urdf, o.package_path);
  std::unique_ptr<ExpandedUrdf> expanded;
  if (!o.urdf.empty() && is_xacro_file(o.urdf))
    expanded = std::make_unique<ExpandedUrdf>(o.urdf, load_options(o.package_path, o.bus, {}, o.xacro_args));
  Inbox opened, sent, closed;  // outlive the server, whose threads fill them
  WebServer web(o.bind, o.port, o.web_root,
                {[&](int id) { opened.push(id, ""); }, [&](int id, const std::string& text) { sent.push(id, text); },
                 [&](int id) { closed.push(id, ""); }});
  web.route("/robot/", [&](const std::string& rest) {
    return expanded && rest == served_urdf_name(o.urdf) ? expanded->path() : WebServer::file_under(urdf_dir, rest);
  });
  web.route("/package/", [&](const std::string& rest) {
    const size_t slash = rest.find('/');
    if (slash == std::string::npos) return std::string();
    return WebServer::file_under(find_package_dir(rest.substr(0, slash), package_path), rest.substr(slash + 1));
  });
  Dashboard d(o, bus, web, opened, sent, closed);
  CmWorker cm(o.bus, web, o.timeout_s);
  d.set_cm(&cm);
  std::printf("dashboard: http://%s:%d/ (bus %s%s%s)\n", WebServer::loopback(o.bind) ? "127.0.0.1" : o.bind.c_str(), web.port(),
              bus.url().c_str(), bus.ns().empty() ? "" : ", namespace ", bus.ns().c_str());
  std::fflush(stdout);
  const int64_t end = o.duration_s > 0 ? monotonic_us() + int64_t(o.duration_s * 1e6) : INT64_MAX;
  while (!tools::stop_requested() && monotonic_us() < end) d.run_once();
  return kExitOk;
}

}  // namespace lcm_control::dashboard

int main(int argc, char** argv) {
  using namespace lcm_control;
  CLI::App app(
      "Serve the robot's dashboard to a browser: the robot in 3D, live plots of any field, sliders and expressions "
      "for command channels, PID gains, controllers (load, start, stop, switch), e-stop and loop statistics.\n"
      "  dashboard --urdf config/turret_bot.urdf           # then open http://127.0.0.1:8080/\n"
      "  dashboard --namespace r1 --port 8081 --read-only",
      "dashboard");
  dashboard::Options o;
  add_bus_flags(app, o.bus);
  add_package_path_flag(app, o.package_path);
  app.add_option("--urdf", o.urdf,
                 "the robot's URDF or .urdf.xacro (with --xacro-arg), for the 3D view (meshes from package:// or "
                 "beside it)");
  add_xacro_arg_flag(app, o.xacro_args);
  app.add_option("--port", o.port, "TCP port of the page (0: one the system picks; the URL is printed)")
      ->check(CLI::Range(0, 65535));
  app.add_option("--bind", o.bind,
                 "address to serve on (default 127.0.0.1: this computer only; there is no authentication)");
  app.add_option("--rate", o.rate_hz, "messages per second per channel at most (latest wins)")
      ->check(CLI::Range(1.0, 1000.0));
  app.add_flag("--read-only", o.read_only, "show the robot, refuse every command from the page");
  app.add_option("--web-root", o.web_root, "folder of the built page (default: ../share/lcm_control/dashboard "
                                           "beside this program)");
  app.add_option("--nice", o.nice,
                 "run at this nice value (0 to 19; default 10), so that a busy page never takes the CPU of the loop "
                 "it shows")
      ->check(CLI::Range(0, 19));
  app.add_option("--timeout", o.timeout_s, "seconds to wait for the controller manager's answers")
      ->check(CLI::PositiveNumber);
  app.add_option("--duration", o.duration_s, "stop after S seconds (default: until Ctrl-C)")
      ->check(CLI::PositiveNumber);
  return run_program(app, argc, argv, [&] { return dashboard::run(o); });
}
