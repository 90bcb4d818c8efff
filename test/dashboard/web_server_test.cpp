#include "dashboard/web_server.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

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
