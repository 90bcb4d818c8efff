#include "tools/lib/clients/state_logger.hpp"

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include "tools/lib/clients/census.hpp"
#include "tools/lib/messages/csv.hpp"
#include "tools/lib/messages/fields.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"

namespace lcm_control::tools {

namespace {

struct ChannelLog {
  std::string channel;  // with the namespace
  std::string path;
  std::unique_ptr<CsvWriter> csv;
  std::string type;
  size_t skipped = 0;
  bool warned = false;
};

class Logger {
 public:
  Logger(Bus& bus, std::vector<ChannelLog>& logs, int64_t count) : logs_(logs), count_(count) {
    for (auto& l : logs_) {
      bus.subscribe(regex_escape(l.channel), &Logger::on_message, this);
    }
  }
  bool done() const {
    if (count_ <= 0) return false;
    for (const auto& l : logs_)
      if (!l.csv || int64_t(l.csv->rows()) < count_) return false;
    return true;
  }

 private:
  void on_message(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    for (auto& l : logs_) {
      if (l.channel != channel) continue;
      if (count_ > 0 && l.csv && int64_t(l.csv->rows()) >= count_) return;
      Decoded d = decode_fields(rbuf->data, rbuf->data_size);
      if (!d.ok() || (!l.type.empty() && d.type != l.type)) {
        ++l.skipped;
        if (!l.warned) {
          fmt::print(stderr, "state-logger: {}: skipping messages: {}\n", channel,
                     d.ok() ? fmt::format("{} after {}", d.type, l.type) : d.type + " " + d.skip_reason);
          l.warned = true;
        }
        return;
      }
      if (!l.csv) {
        l.csv = std::make_unique<CsvWriter>(l.path);
        l.type = d.type;
      }
      l.csv->write(d.fields);
    }
  }
  std::vector<ChannelLog>& logs_;
  int64_t count_;
};

}  // namespace

void add_state_logger_flags(CLI::App& app, StateLoggerFlags& f) {
  app.add_option("CHANNEL", f.channel_names, "channels to log (default joint_states); the namespace is prefixed");
  app.add_option("-o,--output", f.output, "CSV file for one channel (default: stdout)");
  app.add_option("--output-dir", f.output_dir, "folder for one CSV per channel (default . with several channels)");
  app.add_option("--duration", f.duration, "stop after S seconds")->check(CLI::PositiveNumber);
  app.add_option("--count", f.count, "stop once every channel has N rows")->check(CLI::PositiveNumber);
  add_bus_flags(app, f.bus);
}

int run_state_logger(StateLoggerFlags f) {
  if (f.channel_names.empty()) f.channel_names.push_back(channels::kJointStates);
  if (f.channel_names.size() > 1 && !f.output.empty())
    throw std::runtime_error("--output takes one channel; with several channels use --output-dir DIR");
  if (!f.output.empty() && !f.output_dir.empty()) throw std::runtime_error("give --output or --output-dir, not both");
  if (f.channel_names.size() > 1 && f.output_dir.empty()) f.output_dir = ".";
  if (!f.output_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(f.output_dir, ec);
    if (ec) throw std::runtime_error("cannot create " + f.output_dir + ": " + ec.message());
  }
  install_stop_signals();
  Bus bus(f.bus.lcm_url, f.bus.ns, "", HardwareReader::Direct);
  std::vector<ChannelLog> logs;
  for (const auto& name : f.channel_names) {
    ChannelLog l;
    l.channel = bus.channel(without_leading_slashes(name));  // ROS's /joint_states too
    l.path = !f.output_dir.empty() ? (std::filesystem::path(f.output_dir) / csv_file_name(l.channel)).string()
                                 : (f.output.empty() ? "-" : f.output);
    logs.push_back(std::move(l));
  }
  // Fail now, not at the first message, if a file cannot be written.
  for (auto& l : logs)
    if (l.path != "-") CsvWriter probe(l.path);
  Logger logger(bus, logs, f.count);
  Census census(bus);  // to say which channels there were when one had no messages
  for (const auto& l : logs)
    fmt::print(stderr, "state-logger: logging {} -> {}\n", l.channel, l.path == "-" ? "stdout" : l.path);
  const int64_t start = monotonic_us();
  int64_t next_flush = start + 200000;
  while (!stop_requested() && !logger.done()) {
    if (f.duration > 0 && monotonic_us() - start >= int64_t(f.duration * 1e6)) break;
    handle_bus(bus, 50);
    if (monotonic_us() >= next_flush) {
      for (auto& l : logs)
        if (l.csv) l.csv->flush();
      next_flush += 200000;
    }
  }
  std::vector<std::string> silent;
  for (auto& l : logs) {
    if (!l.csv) silent.push_back(l.channel);
    if (l.csv) {
      l.csv->flush();
      fmt::print(stderr, "state-logger: {}: {} rows, {} columns -> {}\n", l.channel, l.csv->rows(),
                 l.csv->columns(), l.path == "-" ? "stdout" : l.path);
    } else {
      fmt::print(stderr, "state-logger: {}: no messages{}\n", l.channel,
                 l.skipped ? fmt::format(" of an lcm_control type ({} skipped)", l.skipped) : "");
    }
  }
  if (!silent.empty())
    throw BusError(fmt::format("no messages on {} ({}); channels seen: {}. Check the channel name, --namespace and "
                               "--lcm-url (or LCM_DEFAULT_URL)",
                               fmt::join(silent, ", "), bus.url(), census.names()));
  return int(kExitOk);
}

}  // namespace lcm_control::tools
