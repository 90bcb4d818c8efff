// LCM for tests: a URL of its own for every test (a free UDP port on the
// loopback multicast route), and helpers to wait for messages with a deadline.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace lcm_control::testing {

// "udpm://239.255.76.67:PORT?ttl=0&recv_buf_size=4194304" with a port no other running test uses. Under lockstep
// the bus carries thousands of messages per second and every udpm socket on the port receives all of them, whatever
// it subscribes to: a receive buffer of 4 MB (net.core.rmem_max here) keeps a busy process (a JVM, a plotter running
// gnuplot) from dropping any.
std::string unique_lcm_url();

// Pumps lc until pred() is true or timeout_s passes; returns pred().
bool pump_until(lcm::LCM& lc, const std::function<bool()>& pred, double timeout_s);

// How far a sender's clock ran ahead of the arrival clock between the start and the end of a recording,
// in seconds (negative: it fell behind). Each end takes the earliest arrival relative to its stamp within
// window_s of that end, so a receiver that got to its first messages late does not count as drift.
double sender_clock_drift_s(const std::vector<int64_t>& sender_us, const std::vector<int64_t>& arrival_us,
                            double window_s);

// Collects every message of type Msg on one channel.
template <class Msg>
class Recorder {
 public:
  Recorder(lcm::LCM& lc, const std::string& channel) {
    sub_ = lc.subscribe(channel, &Recorder::on, this);
    sub_->setQueueCapacity(0);
  }
  std::vector<Msg> messages;
  std::vector<int64_t> receive_us;  // monotonic times when handled
  std::vector<int64_t> arrival_us;  // wall-clock times LCM's receive thread read them (recv_utime)

 private:
  void on(const lcm::ReceiveBuffer* rb, const std::string&, const Msg* m) {
    messages.push_back(*m);
    arrival_us.push_back(rb->recv_utime);
    receive_us.push_back(std::chrono::duration_cast<std::chrono::microseconds>(
                             std::chrono::steady_clock::now().time_since_epoch())
                             .count());
  }
  lcm::Subscription* sub_ = nullptr;
};

}  // namespace lcm_control::testing
