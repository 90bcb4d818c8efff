#include "dashboard/cm_worker.hpp"

#include <algorithm>
#include <optional>

#include "rt/clock.hpp"
#include "tools/lib/clients/cm_client.hpp"

namespace lcm_control::dashboard {

using nlohmann::json;
using tools::CmClient;

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

CmWorker::CmWorker(const BusFlags& flags, WebServer& web, double timeout_s)
    : bus_(flags.lcm_url, flags.ns, "", HardwareReader::Direct), web_(web), timeout_s_(timeout_s), thread_([this] { run(); }) {}

CmWorker::~CmWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void CmWorker::call(int conn, int64_t id, CmCall c) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (jobs_.size() < 100) jobs_.push_back(Job{conn, id, std::move(c)});
  }
  cv_.notify_all();
}

std::string CmWorker::last_list() {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_list_;
}

void CmWorker::run() {
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
void CmWorker::publish_list(CmClient& cm) {
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
void CmWorker::serve(CmClient& cm, const Job& job) {
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

}  // namespace lcm_control::dashboard
