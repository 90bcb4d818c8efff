#include "tools/lib/logs/plotter.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>

#include "tools/lib/messages/fields.hpp"
#include "tools/lib/process/process.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"
#include "tools/lib/logs/log_file.hpp"
#include "tools/lib/clients/time_base.hpp"

namespace lcm_control::tools {

namespace {

// "joint_states.position[1]" or "joint_states/position[1]" names a field of channel "joint_states".
bool under_channel(const std::string& path, const std::string& channel) {
  return path.size() > channel.size() + 1 && path.compare(0, channel.size(), channel) == 0 &&
         (path[channel.size()] == '.' || path[channel.size()] == '/');
}

// One requested path: channel + field, found when the first message of a
// channel that can hold it arrives.
struct Series {
  std::string path;                 // as the user typed it
  std::string channel, field;       // resolved
  std::string unit;                 // from the schema ("" when it gives none)
  bool text = false;                // the field is a string: an error to report, nothing to plot
  std::vector<std::pair<int64_t, double>> points;  // (time us, value)
};

bool any_text(const std::vector<Series>& series) {
  return std::any_of(series.begin(), series.end(), [](const Series& s) { return s.text; });
}

// "joint_states.velocity[1]" matches channel "joint_states", field "velocity[1]" (or its dashboard label
// "velocity[j2]"); ROS-style "/joint_states/velocity[1]" too; a bare channel whose message has one number besides
// utime ("/j2_controller/command") means that number. The field's path, or nothing.
std::optional<std::string> match(std::string path, const std::string& channel, const std::vector<Field>& fields) {
  while (!path.empty() && path[0] == '/') path.erase(0, 1);
  if (path == channel) {
    std::vector<std::string> numbers;
    for (const auto& f : fields)
      if (!f.is_text) numbers.push_back(f.path);
    if (numbers.size() == 2 && numbers[0] == "utime") return numbers[1];
    return std::nullopt;
  }
  if (!under_channel(path, channel)) return std::nullopt;
  const std::vector<const Field*> picked = select_fields(fields, path.substr(channel.size() + 1));
  const std::string field = path.substr(channel.size() + 1);
  if (picked.size() == 1 && (picked[0]->path == field || picked[0]->label == field)) return picked[0]->path;
  return std::nullopt;
}

class Collector {
 public:
  Collector(std::vector<Series>& series, bool use_utime) : series_(series), use_utime_(use_utime) {}

  void add(const std::string& channel, int64_t receive_us, const void* data, size_t size) {
    Decoded* d = nullptr;
    Decoded decoded;
    for (auto& s : series_) {
      if (!s.channel.empty() && s.channel != channel) continue;
      if (!d) {
        decoded = decode_fields(data, size);
        if (!decoded.ok()) return;
        d = &decoded;
        if (fields_seen_.size() < kMaxChannels) fields_seen_.emplace(channel, d->fields);
      }
      if (s.channel.empty()) {
        const auto f = match(s.path, channel, d->fields);
        if (!f) continue;
        s.channel = channel;
        s.field = *f;
        s.unit = field_unit(d->type, *f);
        s.text = std::any_of(d->fields.begin(), d->fields.end(),
                             [&](const Field& x) { return x.path == *f && x.is_text; });
      }
      if (s.text) continue;
      for (const auto& f : d->fields)
        if (f.path == s.field) {
          int64_t t = receive_us;
          if (use_utime_)
            for (const auto& u : d->fields)
              if (u.path == "utime") t = u.exact;
          s.points.emplace_back(t, f.value);
          break;
        }
    }
    if (channels_.size() < kMaxChannels) channels_.insert(channel);
  }
  // What the bus or log held, for an error that helps find the path `wanted`: the nearest field names (the
  // dashboard's labels too) of the channel it names, else of every channel heard.
  std::string hint(const std::string& wanted) const {
    const std::string path = wanted.substr(std::min(wanted.size(), wanted.find_first_not_of('/')));
    const bool named = std::any_of(fields_seen_.begin(), fields_seen_.end(),
                                   [&](const auto& c) { return under_channel(path, c.first); });
    std::string s;
    for (const auto& [ch, fields] : fields_seen_) {
      if (named && !under_channel(path, ch)) continue;
      std::vector<std::string> near = nearest_fields(fields, named ? path.substr(ch.size() + 1) : path, 6);
      const bool close = !near.empty();
      for (const auto& f : fields)
        if (!close && !f.is_text) near.push_back(f.name());
      for (auto& n : near) n = ch + "." + n;
      s += fmt::format("\n  {}: {}", ch, close ? "nearest: " + join(near) : join_some(near, 8));
    }
    std::string others;
    for (const auto& c : channels_)
      if (!fields_seen_.count(c)) others += " " + c;
    if (!others.empty()) s += "\n  channels of other types:" + others;
    return s.empty() ? "\n  (no messages at all)" : s;
  }

 private:
  std::vector<Series>& series_;
  bool use_utime_;
  static constexpr size_t kMaxChannels = 1000;  // names kept for the hint: anyone on the bus can invent more
  std::map<std::string, std::vector<Field>> fields_seen_;
  std::set<std::string> channels_;
};

void read_log(const std::string& path, Collector& c) {
  const auto log_file = open_log(path);
  lcm::LogFile& log = *log_file;
  for (const lcm::LogEvent* ev = log.readNextEvent(); ev; ev = log.readNextEvent())
    c.add(ev->channel, ev->timestamp, ev->data, size_t(ev->datalen));
}

class LiveListener {
 public:
  LiveListener(Bus& bus, Collector& c) : bus_(bus), c_(c) {
    bus.subscribe(".*", &LiveListener::on, this, Bus::On::Shared, 10000);
  }

 private:
  void on(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    const std::string prefix = bus_.channel("");
    if (channel.compare(0, prefix.size(), prefix) != 0) return;
    c_.add(channel.substr(prefix.size()), wall_us(), rbuf->data, size_t(rbuf->data_size));
  }
  Bus& bus_;
  Collector& c_;
};

// A gnuplot string literal: quotes doubled, and line breaks and other control characters made spaces, since a
// new line would end the command and start another (a title must never run `system(...)`).
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "''";
    else
      out += static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? ' ' : c;
  }
  return out + "'";
}

// The data gnuplot reads: one block per path ("# path" then "t value" lines),
// blocks separated by two blank lines; t in seconds from the first message.
void write_data(const std::string& file, const std::vector<Series>& series, int64_t t0) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file);
  for (size_t k = 0; k < series.size(); ++k) {
    if (k) out << "\n\n";
    out << "# " << series[k].path << " (channel " << series[k].channel << ", field " << series[k].field << ")\n";
    for (const auto& [t, v] : series[k].points) out << fmt::format("{:.6f} {}\n", double(t - t0) * 1e-6, v);
  }
  if (!out.flush()) throw std::runtime_error("cannot write " + file);
}

// --xy: one block per pair ("x y" lines), the y sample taken at the x sample's time (fields of one message
// share it); x samples without a y at their time are left out.
void write_xy_data(const std::string& file, const std::vector<Series>& series) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file);
  for (size_t k = 0; k + 1 < series.size(); k += 2) {
    if (k) out << "\n\n";
    out << "# " << series[k + 1].path << " against " << series[k].path << "\n";
    std::map<int64_t, double> y(series[k + 1].points.begin(), series[k + 1].points.end());
    for (const auto& [t, x] : series[k].points)
      if (const auto it = y.find(t); it != y.end()) out << fmt::format("{} {}\n", x, it->second);
  }
  if (!out.flush()) throw std::runtime_error("cannot write " + file);
}

// The y axis: the one unit all series share, else a pointer to the legend, which gives each series' unit.
std::string ylabel(const std::vector<Series>& series) {
  std::set<std::string> units;
  for (const auto& s : series) units.insert(s.unit);
  if (units.size() == 1) return units.begin()->empty() ? "value" : "[" + *units.begin() + "]";
  return "value (units in the legend)";
}

std::string legend(const Series& s) { return s.unit.empty() ? s.path : fmt::format("{} [{}]", s.path, s.unit); }

// A text plot (--terminal) puts each legend entry on a line of its own: side by side they run together.
std::string gnuplot_script(const std::string& terminal, const std::string& output, const std::string& data,
                           const std::vector<Series>& series, const std::string& title, const std::string& xlabel,
                           bool text = false) {
  std::string s = fmt::format("set terminal {}\n", terminal);
  s += output.empty() ? std::string("set output\n") : fmt::format("set output {}\n", quoted(output));
  s += "set termoption noenhanced\nset grid\n";
  s += text ? "set key below left vertical maxcols 1 Left reverse\n" : "set key outside bottom center horizontal\n";
  s += fmt::format("set xlabel {}\nset ylabel {}\n", quoted(xlabel), quoted(ylabel(series)));
  if (!title.empty()) s += fmt::format("set title {}\n", quoted(title));
  s += "plot ";
  for (size_t k = 0; k < series.size(); ++k)
    s += fmt::format("{}{} index {} using 1:2 with {} title {}", k ? ", \\\n     " : "", quoted(data), k,
                     series[k].points.size() < 2 ? "points pt 7" : "lines lw 1.5",
                     quoted((text ? " " : "") + legend(series[k])));
  return s + "\n";
}

// --xy: each pair a curve, y against x, on equal axes (a path in the plane).
std::string xy_script(const std::string& terminal, const std::string& output, const std::string& data,
                      const std::vector<Series>& series, const std::string& title) {
  std::string s = fmt::format("set terminal {}\n", terminal);
  s += output.empty() ? std::string("set output\n") : fmt::format("set output {}\n", quoted(output));
  s += "set termoption noenhanced\nset grid\nset size ratio -1\nset key below vertical\n";
  s += fmt::format("set xlabel {}\nset ylabel {}\n", quoted(legend(series[0])), quoted(legend(series[1])));
  if (!title.empty()) s += fmt::format("set title {}\n", quoted(title));
  s += "plot ";
  for (size_t k = 0; k + 1 < series.size(); k += 2)
    s += fmt::format("{}{} index {} using 1:2 with lines lw 1.5 title {}", k ? ", \\\n     " : "", quoted(data),
                     k / 2, quoted(fmt::format("{} against {}", series[k + 1].path, series[k].path)));
  return s + "\n";
}

// A private folder (mode 0700, made by mkdtemp) for the data and script files, removed with them: no name in the
// shared temp folder that another user could create or link first.
struct TempDir {
  std::string path;
  TempDir() {
    std::string t = (std::filesystem::temp_directory_path() / "plotter_XXXXXX").string();
    if (!mkdtemp(t.data()))
      throw std::runtime_error("cannot create a folder in " + std::filesystem::temp_directory_path().string());
    path = t;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

std::string run_gnuplot(const std::string& script_file) {
  std::string out;
  const int rc = run_and_wait({"gnuplot", script_file}, 30.0, &out);
  if (rc != 0)
    throw std::runtime_error(rc == -1 && out.rfind("cannot start", 0) == 0
                                 ? out + " (install gnuplot-nox)"
                                 : fmt::format("gnuplot failed (exit {}): {}", rc, out));
  return out;
}

}  // namespace

void add_plotter_flags(CLI::App& app, PlotterFlags& f) {
  app.add_option("PATH", f.paths, "CHANNEL.FIELD, e.g. joint_states.velocity[1] or joint_states.velocity[j2]")
      ->required();
  auto* log_opt = app.add_option("--log", f.log_path, "read an lcm-logger log file");
  auto* dur_opt = app.add_option("--duration", f.duration, "listen to the bus for S seconds")->check(CLI::PositiveNumber);
  log_opt->excludes(dur_opt);
  app.add_option("-o,--output", f.output, "image file: .png or .svg (none with --terminal: the plot as text only)");
  app.add_option("--data", f.data_file, "also keep the data gnuplot plots in FILE (blocks of `t value` per path)");
  app.add_option("--title", f.title, "plot title");
  app.add_option("--time", f.time_source, "x axis: receive (log or receive time) or utime (the messages' own clock)")
      ->check(CLI::IsMember({"receive", "utime"}));
  app.add_option("--width", f.width, "image width in pixels")->check(CLI::Range(100, 10000));
  app.add_option("--height", f.height, "image height in pixels")->check(CLI::Range(100, 10000));
  app.add_flag("--xy", f.xy,
               "PATHs in pairs X Y: each pair is one curve of Y against X (the values of one message time), on equal "
               "axes: a path in the plane, e.g. odometry against ground truth");
  app.add_flag("--terminal", f.terminal, "draw the plot as text in the terminal (gnuplot's dumb terminal), besides "
                                       "--output when it is given");
  app.add_flag("--live", f.live, "with --duration: redraw a text plot in the terminal every second");
  add_bus_flags(app, f.bus);
}

int run_plotter(PlotterFlags f) {
  if (f.log_path.empty() && f.duration <= 0) throw std::runtime_error("give --log FILE or --duration S");
  if (f.output.empty() && !f.terminal)
    throw CLI::ValidationError("--output", "give an image file (-o run.png or .svg), or --terminal for a text plot");
  if (f.output == "-" && f.terminal) f.output.clear();  // the spelling before --output was optional
  const std::string ext = std::filesystem::path(f.output).extension().string();
  std::string term;
  if (ext == ".png")
    term = fmt::format("pngcairo size {},{}", f.width, f.height);
  else if (ext == ".svg")
    term = fmt::format("svg size {},{} dynamic", f.width, f.height);
  else if (!f.output.empty())
    throw std::runtime_error(fmt::format("--output '{}': the name must end in .png or .svg", f.output));

  if (f.xy && f.paths.size() % 2 != 0)
    throw std::runtime_error(fmt::format("--xy takes the PATHs in pairs X Y; {} given", f.paths.size()));
  std::vector<Series> series;
  for (const auto& p : f.paths) series.push_back(Series{p, "", "", "", false, {}});
  Collector collector(series, f.time_source == "utime");
  const std::string xlabel = f.time_source == "utime" ? "t [s] (message utime)" : "t [s]";
  const bool keep = !f.data_file.empty();
  const TempDir scratch;
  const std::string tmp = scratch.path + "/plot";
  if (!keep) f.data_file = tmp + ".dat";
  const std::string script_file = tmp + ".gp";
  // Writes the data and runs gnuplot: the image (with_image) and/or a text plot it returns.
  auto render = [&](bool with_image, bool with_text) {
    std::vector<Series> have;
    for (size_t k = 0; k < series.size(); k += f.xy ? 2 : 1)
      if (!series[k].points.empty() && (!f.xy || !series[k + 1].points.empty()))
        have.insert(have.end(), series.begin() + long(k), series.begin() + long(k + (f.xy ? 2 : 1)));
    if (have.empty()) return std::string("(no data yet)\n");
    if (f.xy) {
      write_xy_data(f.data_file, have);
      std::ofstream sc(script_file);
      if (with_image) sc << xy_script(term, f.output, f.data_file, have, f.title);
      if (with_text) sc << xy_script("dumb size 100,30", "", f.data_file, have, f.title);
    }
    int64_t t0 = have[0].points.front().first;
    for (const auto& s : have) t0 = std::min(t0, s.points.front().first);
    if (!f.xy) {
      write_data(f.data_file, have, t0);
      std::ofstream sc(script_file);
      if (with_image) sc << gnuplot_script(term, f.output, f.data_file, have, f.title, xlabel);
      if (with_text) sc << gnuplot_script("dumb size 100,30", "", f.data_file, have, f.title, xlabel, true);
    }
    std::string text;
    try {
      text = run_gnuplot(script_file);
    } catch (...) {
      std::remove(script_file.c_str());
      if (!keep) std::remove(f.data_file.c_str());
      throw;
    }
    std::remove(script_file.c_str());
    return text;
  };
  if (!f.log_path.empty()) {
    read_log(f.log_path, collector);
  } else {
    install_stop_signals();
    Bus bus(f.bus.lcm_url, f.bus.ns, "", HardwareReader::Direct);
    LiveListener listener(bus, collector);
    fmt::print(stderr, "plotter: listening for {} on {}\n", seconds_text(f.duration), bus.url());
    const int64_t end = monotonic_us() + int64_t(f.duration * 1e6);
    while (!stop_requested() && monotonic_us() < end) {
      if (pump_until(bus, [&] { return any_text(series); }, std::min(1.0, double(end - monotonic_us()) / 1e6)))
        break;
      if (f.live && !stop_requested() && monotonic_us() < end)
        fmt::print("\033[H\033[2J{}plotter: {:.0f} s left (Ctrl-C ends early and still writes {})\n",
                   render(false, true), double(end - monotonic_us()) / 1e6, f.output.empty() ? "the plot" : f.output);
      std::fflush(stdout);
    }
    clear_stop();
  }
  for (const auto& s : series) {
    if (!s.text) continue;
    if (!keep) std::remove(f.data_file.c_str());
    throw std::runtime_error(fmt::format(
        "{}: column {} of channel {} holds text, not numbers, and cannot be plotted; plot a numeric field, or "
        "read the text with log2csv or state-logger",
        s.path, s.field, s.channel));
  }
  if (f.time_source == "utime")
    for (const auto& s : series) {
      if (s.points.empty() || series[0].points.empty()) continue;
      const std::string mixed =
          mixed_clocks(series[0].channel, series[0].points.front().first, s.channel, s.points.front().first);
      if (mixed.empty()) continue;
      if (!keep) std::remove(f.data_file.c_str());
      throw std::runtime_error(mixed + "; plot against receive time (--time receive, the default), or publish the "
                                       "commands on the sim clock (turret-cmd and bus pub stamp sim time when "
                                       "sim_server's clock is on the bus)");
    }
  std::string missing, hints;
  for (const auto& s : series)
    if (s.points.empty()) {
      missing += (missing.empty() ? "" : ", ") + s.path;
      hints += hints.empty() ? collector.hint(s.path) : fmt::format("\n for {}:{}", s.path, collector.hint(s.path));
    }
  if (!missing.empty()) {
    if (!keep) std::remove(f.data_file.c_str());
    const std::string why = fmt::format("no data for {} in {}; what there was:{}", missing,
                                        f.log_path.empty() ? "the bus" : f.log_path, hints);
    if (f.log_path.empty()) throw BusError(why);  // nothing came: exit code 4
    throw std::runtime_error(why);
  }
  const std::string text = render(!term.empty(), f.terminal);
  if (!keep) std::remove(f.data_file.c_str());
  if (f.terminal) std::fputs(text.c_str(), stdout);
  if (!term.empty()) {
    std::error_code ec;
    if (std::filesystem::file_size(f.output, ec) == 0 || ec)
      throw std::runtime_error("gnuplot wrote no image to " + f.output + ": " + text);
    size_t n = 0;
    for (const auto& s : series) n += s.points.size();
    fmt::print(stderr, "plotter: {} points of {} paths -> {}\n", n, series.size(), f.output);
  }
  return int(kExitOk);
}

}  // namespace lcm_control::tools
