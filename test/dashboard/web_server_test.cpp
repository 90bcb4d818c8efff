#include "dashboard/web_server.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <sys/socket.h>
#include <fstream>
#include <thread>
#include <utility>
#include <vector>

#include "test/dashboard/http_get.hpp"
#include "test/support/process.hpp"

namespace lcm_control::dashboard {
namespace {

namespace fs = std::filesystem;

int get_status(int port, const std::string& path) { return http_get(port, path).status; }

long rss_kb() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A page folder with an index.html, and a server on it that counts what browsers open and send.
struct Served {
  explicit Served(const std::string& name) : root(testing::temp_dir(name)) {
    std::ofstream(root / "index.html") << "<html></html>";
    web = std::make_unique<WebServer>("127.0.0.1", 0, root.string(),
                                      WebServer::Handlers{[&](int) { ++opened; },
                                                          [&](int, const std::string& t) {
                                                            ++texts;
                                                            last_size = t.size();
                                                          },
                                                          {}});
  }
  fs::path root;
  std::atomic<int> opened{0}, texts{0};
  std::atomic<size_t> last_size{0};
  std::unique_ptr<WebServer> web;
};

TEST(DashboardWebServer, FilesUnderARootOnly) {
  const fs::path root = fs::path(testing::temp_dir("dashboard_root")) / "robot";
  fs::create_directories(root);
  fs::create_directories(root / "meshes");
  std::ofstream(root / "meshes" / "base.stl") << "solid";
  std::ofstream(root.parent_path() / "secret.txt") << "no";
  fs::create_symlink(root.parent_path() / "secret.txt", root / "link.txt");
  EXPECT_EQ(WebServer::file_under(root.string(), "meshes/base.stl"), (fs::canonical(root) / "meshes/base.stl").string());
  EXPECT_EQ(WebServer::file_under(root.string(), "meshes/../meshes/base.stl"), (fs::canonical(root) / "meshes/base.stl").string());
  for (const char* bad : {"../secret.txt", "meshes/../../secret.txt", "/etc/passwd", "link.txt", "meshes", "",
                          "nothing.stl"})
    EXPECT_EQ(WebServer::file_under(root.string(), bad), "") << bad;
  EXPECT_EQ(WebServer::file_under("", "meshes/base.stl"), "");
}

TEST(DashboardWebServer, OnlyItsOwnPageOnItsOwnNames) {
  // Loopback: the page itself, and tools without an Origin (curl, the bench's client).
  for (const auto& [host, origin] : std::vector<std::pair<std::string, std::string>>{
           {"127.0.0.1:8080", ""}, {"127.0.0.1:8080", "http://127.0.0.1:8080"}, {"localhost:8080", ""},
           {"localhost:8080", "http://localhost:8080"}, {"[::1]:8080", "http://[::1]:8080"}, {"127.0.0.1", ""}})
    EXPECT_EQ(WebServer::refuse_reason(host, origin, true), "") << host << " " << origin;
  // Another site's page connecting to the robot, and DNS rebinding (a name of the attacker's on 127.0.0.1).
  EXPECT_NE(WebServer::refuse_reason("127.0.0.1:8080", "https://evil.example", true).find("evil.example"),
            std::string::npos);
  EXPECT_NE(WebServer::refuse_reason("127.0.0.1:8080", "http://127.0.0.1:9999", true), "");
  EXPECT_NE(WebServer::refuse_reason("evil.example:8080", "http://evil.example:8080", true).find("127.0.0.1"),
            std::string::npos);
  EXPECT_NE(WebServer::refuse_reason("", "", true), "");
  // Served to the network (--bind): any name of the machine, still only its own page.
  EXPECT_EQ(WebServer::refuse_reason("robot-pc:8080", "http://robot-pc:8080", false), "");
  EXPECT_NE(WebServer::refuse_reason("robot-pc:8080", "http://evil.example", false), "");
}

TEST(DashboardWebServer, ABrowserThatStopsReadingHoldsUpNobody) {
  const fs::path root = testing::temp_dir("dashboard_stall");
  std::ofstream(root / "index.html") << "<html></html>";
  std::atomic<int> opened{0};
  WebServer web("127.0.0.1", 0, root.string(), {[&](int) { ++opened; }, {}, {}});
  const int stalled = ws_connect(web.port(), 4096);
  const int reader = ws_connect(web.port(), 4096);
  ASSERT_GE(stalled, 0);
  ASSERT_GE(reader, 0);
  for (int k = 0; k < 100 && opened < 2; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(web.connections(), 2u);

  // Two rounds of 900 frames of 64 KB (under the queue's bound each): the reader gets all of them while the stalled
  // browser's queue fills and then loses its oldest.
  const std::string frame(64 * 1024, 'x');
  const int64_t round_bytes = 900 * int64_t(frame.size());
  std::atomic<int64_t> got{0};
  std::thread read_all([&] {
    char buf[65536];
    ssize_t n;
    while (got < 2 * round_bytes && (n = ::read(reader, buf, sizeof buf)) > 0) got += n;
  });
  for (int round = 1; round <= 2; ++round) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < 900; ++k) web.broadcast(frame);
    const double broadcast_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_LT(broadcast_s, 1.0) << "round " << round << ": the sender waited for a browser";
    for (int k = 0; k < 1000 && got < round * round_bytes; ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_GE(got.load(), round * round_bytes) << "round " << round << ": the reading browser lost frames";
  }
  read_all.join();
  EXPECT_GT(web.dropped(), 500) << "the stalled browser's queue is not bounded";
  ::close(stalled);
  ::close(reader);
}

TEST(DashboardWebServer, ServesThePageAndRoutesOnAPortItPicks) {
  const fs::path root = testing::temp_dir("dashboard_web");
  std::ofstream(root / "index.html") << "<html></html>";
  WebServer web("127.0.0.1", 0, root.string(), {});
  ASSERT_GT(web.port(), 0);
  web.route("/robot/", [&](const std::string& rest) {
    return rest == "r.urdf" ? (root / "index.html").string() : std::string();
  });
  EXPECT_EQ(get_status(web.port(), "/"), 200);
  EXPECT_EQ(get_status(web.port(), "/robot/r.urdf"), 200);
  EXPECT_EQ(get_status(web.port(), "/robot/other.urdf"), 404);
  EXPECT_EQ(web.connections(), 0u);

  // A second server on the same port says what to do.
  try {
    WebServer again("127.0.0.1", web.port(), root.string(), {});
    FAIL() << "a second server listened on a port in use";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--port"), std::string::npos) << e.what();
  }
}

// A frame's length is read from its header and refused there: a 1 GB frame (and four of 256 MB) cost the server no
// memory, and the next message within the limit is still taken.
TEST(DashboardWebServer, AFrameOverTheLimitIsRefusedFromItsHeaderWithoutBufferingIt) {
  Served s("dashboard_big_frame");
  const int ok = ws_connect(s.web->port());
  ASSERT_GE(ok, 0);
  ASSERT_TRUE(ws_send_text(ok, std::string(WebServer::kMaxIncoming, 'a')));
  for (int k = 0; k < 200 && s.texts < 1; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_EQ(s.texts.load(), 1);
  EXPECT_EQ(s.last_size.load(), WebServer::kMaxIncoming);

  const long before = rss_kb();
  std::vector<int> big;
  for (uint64_t length : {uint64_t(1) << 30, uint64_t(256) << 20, uint64_t(256) << 20, uint64_t(256) << 20,
                          uint64_t(256) << 20}) {
    const int fd = ws_connect(s.web->port());
    ASSERT_GE(fd, 0);
    const std::string head = ws_frame_header(length);
    ASSERT_EQ(::write(fd, head.data(), head.size()), ssize_t(head.size()));
    const std::string chunk(1 << 20, 'x');  // what a sender gets in before the server closes: none of it is kept
    for (int k = 0; k < 8; ++k)
      if (::send(fd, chunk.data(), chunk.size(), MSG_NOSIGNAL | MSG_DONTWAIT) < 0) break;
    big.push_back(fd);
  }
  for (const int fd : big) {
    const WsFrame close = ws_read(fd);  // a close frame, status 1009 (message too big)
    EXPECT_EQ(close.opcode, 8);
    ASSERT_GE(close.payload.size(), 2u);
    EXPECT_EQ((uint8_t(close.payload[0]) << 8) | uint8_t(close.payload[1]), 1009);
    ::close(fd);
  }
  const long grown = rss_kb() - before;
  EXPECT_LT(grown, 1024) << "kB";
  std::printf("frames of 1 GB and 4 x 256 MB refused at their headers: resident memory grew %ld kB\n", grown);
  ASSERT_TRUE(ws_send_text(ok, "{}"));
  for (int k = 0; k < 200 && s.texts < 2; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(s.texts.load(), 2);
  ::close(ok);
}

// Idle connections cannot lock anyone out: a 17th browser with 16 idle ones open is served at once, and at the
// per-client bound the one idle longest is closed to make room.
TEST(DashboardWebServer, IdleConnectionsNeverLockANewClientOut) {
  Served s("dashboard_idle");
  std::vector<int> idle;
  for (int k = 0; k < 16; ++k) idle.push_back(ws_connect(s.web->port()));
  for (const int fd : idle) ASSERT_GE(fd, 0);
  auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(get_status(s.web->port(), "/"), 200);
  const int seventeenth = ws_connect(s.web->port());
  EXPECT_GE(seventeenth, 0);
  EXPECT_LT(seconds_since(t0), 0.5);
  idle.push_back(seventeenth);
  for (int k = 0; k < 200 && s.opened < 17; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(s.web->connections(), 17u);

  // Up to the bound and past it: the first ones (idle longest) are closed, every new one is served.
  for (size_t k = idle.size(); k < WebServer::kMaxPerClient + 8; ++k) {
    const int fd = ws_connect(s.web->port());
    ASSERT_GE(fd, 0) << "connection " << k;
    idle.push_back(fd);
  }
  EXPECT_EQ(get_status(s.web->port(), "/"), 200);
  EXPECT_GE(s.web->closed_for_room(), 8);
  EXPECT_EQ(ws_read(idle.front()).opcode, -1) << "the connection idle longest was closed";
  for (int k = 0; k < 200 && s.web->connections() >= WebServer::kMaxPerClient; ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_LT(s.web->connections(), WebServer::kMaxPerClient);
  for (const int fd : idle) ::close(fd);
}

// A request's headers arrive whole within a second or the connection is closed; others are served meanwhile, and
// headers over the size bound are refused.
TEST(DashboardWebServer, TrickledOrOversizeRequestsHoldNothing) {
  Served s("dashboard_trickle");
  std::vector<int> slow;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < 20; ++k) {
    const int fd = connect_loopback(s.web->port());
    ASSERT_GE(fd, 0);
    (void)!::write(fd, "GET / HTTP/1.1\r\nHost: 127", 25);
    slow.push_back(fd);
  }
  const auto t1 = std::chrono::steady_clock::now();
  EXPECT_EQ(get_status(s.web->port(), "/"), 200);
  EXPECT_LT(seconds_since(t1), 0.5);
  for (int k = 0; k < 3; ++k) {  // a byte every 300 ms does not renew the deadline
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    for (const int fd : slow) (void)!::send(fd, ".", 1, MSG_NOSIGNAL);
  }
  char c;
  for (const int fd : slow) {
    EXPECT_LE(::read(fd, &c, 1), 0);
    ::close(fd);
  }
  const double closed_after = seconds_since(t0);
  EXPECT_LT(closed_after, 2.5);
  std::printf("20 trickled requests closed within %.2f s\n", closed_after);

  const std::string huge(WebServer::kMaxHeaderBytes + 1, 'h');
  EXPECT_EQ(http_get(s.web->port(), "/", "X-Big: " + huge + "\r\n").status, 431);
  EXPECT_EQ(http_get(s.web->port(), "/%zz").status, 400);
  EXPECT_EQ(http_get(s.web->port(), "/index.html?v=1").status, 200);
}

TEST(DashboardWebServer, DecodesPathsAndRefusesBadEscapes) {
  std::string path;
  EXPECT_TRUE(WebServer::decode_path("/a%20b/%2e%2e/c?x=%zz", path));
  EXPECT_EQ(path, "/a b/../c");
  for (const char* bad : {"/a%2", "/a%", "/%00", "/%g0", "a/b", ""}) EXPECT_FALSE(WebServer::decode_path(bad, path)) << bad;
}

}  // namespace
}  // namespace lcm_control::dashboard
