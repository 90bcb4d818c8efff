#include "dashboard/web_server.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
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

// A WebSocket client socket after the handshake (-1 if refused); it reads only when the test reads.
int ws_connect(int port) {
  const int fd = connect_loopback(port, 4096);  // a small receive buffer fills at once when the client does not read
  if (fd < 0) return -1;
  const std::string req = "GET /ws HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                          "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                          "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n";
  (void)!::write(fd, req.data(), req.size());
  std::string head;
  char c;
  while (head.find("\r\n\r\n") == std::string::npos && ::read(fd, &c, 1) == 1) head += c;
  if (head.find(" 101 ") == std::string::npos) return ::close(fd), -1;
  return fd;
}

TEST(DashboardWebServer, ABrowserThatStopsReadingHoldsUpNobody) {
  const fs::path root = testing::temp_dir("dashboard_stall");
  std::ofstream(root / "index.html") << "<html></html>";
  std::atomic<int> opened{0};
  WebServer web("127.0.0.1", 0, root.string(), {[&](int) { ++opened; }, {}, {}});
  const int stalled = ws_connect(web.port());
  const int reader = ws_connect(web.port());
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

}  // namespace
}  // namespace lcm_control::dashboard
