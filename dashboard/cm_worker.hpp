// The controller manager's services for the dashboard, on a thread and an LCM instance of their own, so that a
// manager that does not answer never holds up the stream: the list every second while a browser looks, and the
// calls browsers make.
#pragma once

#include <condition_variable>
#include <deque>
#include <mutex>
#include <string>
#include <thread>

#include "bus/bus.hpp"
#include "cli/cli.hpp"
#include "dashboard/requests.hpp"
#include "dashboard/web_server.hpp"
#include "lcm_control/cm_response_t.hpp"

namespace lcm_control::tools {
class CmClient;
}

namespace lcm_control::dashboard {

// The page's "controllers" frame from a LIST answer.
nlohmann::json controller_list_json(const cm_response_t& r);

class CmWorker {
 public:
  CmWorker(const BusFlags& flags, WebServer& web, double timeout_s);
  ~CmWorker();
  CmWorker(const CmWorker&) = delete;
  CmWorker& operator=(const CmWorker&) = delete;
  void call(int conn, int64_t id, CmCall c);  // its reply goes to conn
  std::string last_list();                    // the last "controllers" frame sent, "" before the first

 private:
  struct Job {
    int conn;
    int64_t id;
    CmCall call;
  };
  void run();
  void publish_list(tools::CmClient& cm);
  void serve(tools::CmClient& cm, const Job& job);

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

}  // namespace lcm_control::dashboard
