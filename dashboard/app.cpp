// The dashboard application: the bus thread that streams each channel's newest message to the browsers at the
// display rate and serves their requests, wired to the web server and the controller-manager worker.
#include "dashboard/app.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <set>

#include "control/expression.hpp"
#include "description/packages.hpp"
#include "description/robot_file.hpp"
#include "dashboard/cm_worker.hpp"
#include "dashboard/requests.hpp"
#include "dashboard/served_urdf.hpp"
#include "dashboard/throttle.hpp"
#include "dashboard/web_server.hpp"
#include "rt/scheduling.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "tools/lib/messages/message_json.hpp"
#include "tools/lib/messages/message_text.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"
#include "tools/lib/clients/time_base.hpp"

namespace lcm_control::dashboard {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

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

class Dashboard {
 public:
  // opened, sent, closed: filled by the web server's threads, which touch nothing else of the dashboard.
  Dashboard(const Options& o, Bus& bus, WebServer& web, Inbox& opened, Inbox& sent, Inbox& closed)
      : o_(o), bus_(bus), web_(web), opened_(opened), inbox_(sent), closed_(closed),
        period_us_(int64_t(1e6 / o.rate_hz)), throttle_(period_us_), clock_(bus, 0.0) {
    prefix_ = bus.channel("");
    own_.insert(bus.channel(channels::kCmRequest));
    const std::string pattern = prefix_.empty() ? ".*" : tools::regex_escape(prefix_) + ".*";
    bus_.subscribe(pattern, &Dashboard::on_any, this, Bus::On::Shared, 10000);
  }

  // What a browser gets first: the bus it looks at, its URDF, the messages' schema (lcmtypes/, each type's fields in
  // their order: the page lists pid_gains_t's p, i, d before the clamps), and the controllers as last listed.
  void hello(int conn) {
    nlohmann::ordered_json h = {{"kind", "hello"}, {"namespace", bus_.ns()}, {"lcm_url", bus_.url()}, {"read_only", o_.read_only},
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
    bus_.handle_shared(kMaxDrain);
    for (auto& [conn, text] : opened_.take()) hello(conn);
    for (auto& [conn, text] : closed_.take()) {
      stop_streams_of(conn);
      told_.erase(conn);
    }
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
      if (told_.insert(conn).second)
        std::fprintf(stderr, "dashboard: browser %d sent a request that was refused: %s (its next ones are answered "
                     "the same way, without a line here)\n", conn, p.error.c_str());
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
  std::set<int> told_;          // browsers whose refused request the log has named
  int64_t next_flush_ = 0, next_status_ = 0;
};

// build/bin/dashboard: build/share/lcm_control/dashboard; installed, PREFIX/libexec/lcm_control/dashboard:
// PREFIX/share/lcm_control/dashboard.
std::string default_web_root() {
  const fs::path exe_dir = fs::read_symlink("/proc/self/exe").parent_path();
  const fs::path page = fs::path("share") / "lcm_control" / "dashboard";
  std::error_code ec;
  if (fs::is_directory(exe_dir.parent_path() / page, ec)) return (exe_dir.parent_path() / page).string();
  return (exe_dir.parent_path().parent_path() / page).string();
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
  lower_priority(o.nice);  // before any thread: LCM's and the web server's threads inherit it
  install_stop_signals();
  Bus bus(o.bus.lcm_url, o.bus.ns, "", HardwareReader::Direct);
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
  // file:// mesh URIs (xacro's force_abs_paths: UR's descriptions), as /file/<absolute path>: only inside a package
  // that the package path finds (what /package/ serves) or the URDF's folder, so that the page cannot read any
  // other file of the user's.
  web.route("/file/", [&](const std::string& rest) {
    const fs::path wanted = fs::path("/" + rest).lexically_normal();
    auto under = [&](const fs::path& root) {
      const fs::path inside = wanted.lexically_relative(root);
      return inside.empty() || *inside.begin() == ".." ? std::string() : WebServer::file_under(root, inside.string());
    };
    if (!urdf_dir.empty())
      if (const std::string f = under(fs::absolute(urdf_dir).lexically_normal()); !f.empty()) return f;
    std::vector<fs::path> roots;  // the path's own folders are not packages, even when one is named as its package
    for (const std::string& p : package_path) roots.push_back(fs::absolute(p).lexically_normal());
    fs::path prefix = "/";
    for (const fs::path& part : wanted.relative_path()) {
      prefix /= part;
      const std::string dir = find_package_dir(part.string(), package_path);
      if (!dir.empty() && fs::absolute(dir).lexically_normal() == prefix &&
          std::find(roots.begin(), roots.end(), prefix) == roots.end())
        return under(prefix);
    }
    return std::string();
  });
  Dashboard d(o, bus, web, opened, sent, closed);
  CmWorker cm(o.bus, web, o.timeout_s);
  d.set_cm(&cm);
  std::printf("dashboard: http://%s:%d/ (bus %s%s%s)\n", WebServer::loopback(o.bind) ? "127.0.0.1" : o.bind.c_str(), web.port(),
              bus.url().c_str(), bus.ns().empty() ? "" : ", namespace ", bus.ns().c_str());
  std::fflush(stdout);
  const int64_t end = o.duration_s > 0 ? monotonic_us() + int64_t(o.duration_s * 1e6) : INT64_MAX;
  while (!stop_requested() && monotonic_us() < end) d.run_once();
  return kExitOk;
}

}  // namespace lcm_control::dashboard
