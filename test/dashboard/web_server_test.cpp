#include "dashboard/web_server.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
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
