#include "dashboard/web_server.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "test/support/process.hpp"

namespace lcm_control::dashboard {
namespace {

namespace fs = std::filesystem;

// One HTTP/1.0 GET on 127.0.0.1:port; the status line's code, or -1.
int get_status(int port, const std::string& path) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(uint16_t(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  const std::string req = "GET " + path + " HTTP/1.0\r\n\r\n";
  (void)!::write(fd, req.data(), req.size());
  char buf[64] = {};
  const ssize_t n = ::read(fd, buf, sizeof buf - 1);
  ::close(fd);
  if (n < 12) return -1;
  return std::atoi(buf + 9);
}

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

TEST(DashboardWebServer, ServesThePageAndRoutesOnAPortItPicks) {
  const fs::path root = testing::temp_dir("dashboard_web");
  std::ofstream(root / "index.html") << "<html></html>";
  WebServer web("127.0.0.1", 0, root.string(), {});
  ASSERT_GT(web.port(), 0);
  web.route("/robot/", [&](const std::string& rest) -> std::optional<WebServer::Reply> {
    if (rest != "r.urdf") return std::nullopt;
    return WebServer::Reply{"", "<robot/>", "application/xml"};
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
