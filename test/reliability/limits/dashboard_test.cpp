// The dashboard program against a hostile local client (issue 51): JSON it cannot take, frames larger than it allows,
// connections left idle or half-sent. Each is answered or refused, the program lives, and a browser that comes after
// is served. Each test prints its figures as a RELIABILITY line.
#include <gtest/gtest.h>

#include <sys/socket.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <regex>
#include <thread>

#include "test/dashboard/http_get.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lt = lcm_control::testing;
using namespace lcm_control::dashboard;

namespace {

long rss_kb(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

struct Dashboard {
  Dashboard(std::vector<std::string> extra = {}) {
    std::vector<std::string> argv = {lt::bin("dashboard"), "--port", "0", "--lcm-url", lt::unique_lcm_url(),
                                     "--duration", "60"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    process = std::make_unique<lt::ChildProcess>(argv);
    if (!process->wait_for_output("dashboard: http", 10)) return;
    std::smatch m;
    const std::string out = process->output();
    if (std::regex_search(out, m, std::regex(R"(http://127\.0\.0\.1:(\d+)/)"))) port = std::stoi(m[1]);
  }
  // A browser's WebSocket, past the hello the dashboard sends first.
  int browser() {
    const int fd = ws_connect(port);
    if (fd >= 0) ws_read(fd);
    return fd;
  }
  std::unique_ptr<lt::ChildProcess> process;
  int port = -1;
};

}  // namespace

// `[1e400]` once ended the dashboard, --read-only included. Every request it cannot take is answered with why, and
// the log names each browser's first one only.
TEST(Limits, DashboardAnswersEveryBadRequestAndLogsOncePerBrowser) {
  for (const bool read_only : {false, true}) {
    Dashboard d(read_only ? std::vector<std::string>{"--read-only"} : std::vector<std::string>{});
    ASSERT_GT(d.port, 0) << d.process->output();
    const int a = d.browser(), b = d.browser();
    ASSERT_GE(a, 0);
    ASSERT_GE(b, 0);
    const std::vector<std::string> bad = {"[1e400]", "{", R"({"op": 5})", R"({"id": 1e999, "op": "cm"})",
                                          R"({"op": "publish", "channel": "x", "type": "float64_t", "msg": {"data": 1e400}})",
                                          std::string(30000, '[') + std::string(30000, ']')};
    int answered = 0;
    for (const int fd : {a, b})
      for (const std::string& text : bad) {
        ASSERT_TRUE(ws_send_text(fd, text));
        for (WsFrame f = ws_read(fd); f.opcode != -1; f = ws_read(fd))
          if (f.payload.find("\"kind\":\"reply\"") != std::string::npos) {
            answered += f.payload.find("\"ok\":false") != std::string::npos;
            break;
          }
      }
    EXPECT_EQ(answered, int(2 * bad.size()));
    // Text that is not UTF-8 breaks the WebSocket protocol itself: that browser is closed with status 1007.
    ASSERT_TRUE(ws_send_text(a, "\"\xff\""));
    WsFrame f = ws_read(a);
    while (f.opcode != -1 && f.opcode != 8) f = ws_read(a);
    EXPECT_EQ(f.opcode, 8);
    EXPECT_TRUE(f.payload.size() >= 2 && ((uint8_t(f.payload[0]) << 8) | uint8_t(f.payload[1])) == 1007);
    EXPECT_TRUE(d.process->running()) << d.process->output();
    EXPECT_EQ(http_get(d.port, "/").status, 200);
    const std::string log = d.process->output();
    EXPECT_EQ(count_of(log, "sent a request that was refused"), 2u) << log;
    ::close(a);
    ::close(b);
    EXPECT_EQ(d.process->stop(), 0) << d.process->output();
    std::printf("RELIABILITY|limits|dashboard%s: %zu malformed or out-of-range requests from each of 2 browsers|"
                "tried=%zu|ok=%d|crashes=0|hangs=0|each answered; one log line per browser\n",
                read_only ? " --read-only" : "", bad.size(), 2 * bad.size(), answered);
  }
}

// A frame is refused from its header: a 1 GB frame and four of 256 MB leave the dashboard's memory where it was
// (it took 1 GB before). Sixteen idle browsers and twenty half-sent requests lock nobody out: a 17th browser gets its
// hello at once.
TEST(Limits, DashboardRefusesHugeFramesAtTheirHeaderAndServesA17thBrowser) {
  Dashboard d;
  ASSERT_GT(d.port, 0) << d.process->output();
  const int warm = d.browser();
  ASSERT_GE(warm, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const long before = rss_kb(d.process->pid());
  int refused = 0;
  for (uint64_t length : {uint64_t(1) << 30, uint64_t(256) << 20, uint64_t(256) << 20, uint64_t(256) << 20,
                          uint64_t(256) << 20}) {
    const int fd = ws_connect(d.port);
    ASSERT_GE(fd, 0);
    ws_read(fd);  // the hello
    const std::string head = ws_frame_header(length);
    ASSERT_EQ(::write(fd, head.data(), head.size()), ssize_t(head.size()));
    const std::string chunk(1 << 20, 'x');
    for (int k = 0; k < 8; ++k)
      if (::send(fd, chunk.data(), chunk.size(), MSG_NOSIGNAL | MSG_DONTWAIT) < 0) break;
    for (WsFrame f = ws_read(fd); f.opcode != -1; f = ws_read(fd))
      if (f.opcode == 8) {
        refused += f.payload.size() >= 2 && ((uint8_t(f.payload[0]) << 8) | uint8_t(f.payload[1])) == 1009;
        break;
      }
    ::close(fd);
  }
  const long grown = rss_kb(d.process->pid()) - before;
  EXPECT_EQ(refused, 5);
  EXPECT_LT(grown, 1024) << "kB";

  std::vector<int> idle;
  for (int k = 0; k < 16; ++k) idle.push_back(ws_connect(d.port));
  for (int k = 0; k < 20; ++k) {
    const int fd = connect_loopback(d.port);
    (void)!::write(fd, "GET / HTTP/1.1\r\nHost: 127", 25);
    idle.push_back(fd);
  }
  const auto t0 = std::chrono::steady_clock::now();
  const int seventeenth = ws_connect(d.port);
  const WsFrame hello = seventeenth >= 0 ? ws_read(seventeenth) : WsFrame{};
  const double served_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_NE(hello.payload.find("\"kind\":\"hello\""), std::string::npos);
  EXPECT_EQ(http_get(d.port, "/").status, 200);
  EXPECT_LT(served_s, 1.0);
  EXPECT_TRUE(d.process->running()) << d.process->output();
  for (const int fd : idle) ::close(fd);
  ::close(seventeenth);
  ::close(warm);
  EXPECT_EQ(d.process->stop(), 0) << d.process->output();
  std::printf("RELIABILITY|limits|dashboard: a 1 GB and four 256 MB WebSocket frames; a 17th browser beside 16 idle "
              "ones and 20 half-sent requests|tried=6|ok=%d|crashes=0|hangs=0|frames refused at their header, "
              "resident memory grew %ld kB; the 17th browser's hello in %.3f s\n",
              refused + (hello.opcode == 1), grown, served_s);
}
