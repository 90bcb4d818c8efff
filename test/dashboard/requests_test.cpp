#include "dashboard/requests.hpp"

#include <gtest/gtest.h>

namespace lcm_control::dashboard {
namespace {

TEST(DashboardRequests, ReadsEachOp) {
  auto p = parse_request(R"({"id": 4, "op": "publish", "channel": "/j1_controller/command", "type": "float64_t",
                             "msg": {"data": 0.5}})", false);
  ASSERT_TRUE(p.ok()) << p.error;
  EXPECT_EQ(p.request.id, 4);
  const auto& pub = std::get<Publish>(p.request.what);
  EXPECT_EQ(pub.channel, "j1_controller/command");  // a ROS-style leading slash is dropped
  EXPECT_EQ(pub.fields["data"], 0.5);

  p = parse_request(R"({"op": "cm", "call": "switch", "start": ["a"], "stop": ["b", "c"], "strict": false})", false);
  ASSERT_TRUE(p.ok()) << p.error;
  const auto& cm = std::get<CmCall>(p.request.what);
  EXPECT_EQ(cm.stop.size(), 2u);
  EXPECT_FALSE(cm.strict);

  p = parse_request(R"j({"op": "expr", "channel": "j2_controller/command", "expressions": ["3.14*sin(i/100)"],
                         "rate": 60})j", false);
  ASSERT_TRUE(p.ok()) << p.error;
  EXPECT_EQ(std::get<ExprStart>(p.request.what).rate_hz, 60);
  EXPECT_TRUE(parse_request(R"({"op": "expr_stop", "channel": "x"})", false).ok());
}

TEST(DashboardRequests, RefusesWhatIsMalformedAndSaysWhy) {
  const std::pair<const char*, const char*> cases[] = {
      {"{", "not JSON"},
      {"[1]", "JSON object"},
      {R"({"op": "reboot"})", "unknown op 'reboot'"},
      {R"({"op": "publish", "type": "float64_t"})", "'channel' is missing"},
      {R"({"op": "publish", "channel": "a b", "type": "float64_t"})", "space or control"},
      {R"({"op": "publish", "channel": "x", "type": "float64_t", "msg": 3})", "'msg' must be an object"},
      {R"({"op": "cm", "call": "format_disk"})", "unknown call 'format_disk'"},
      {R"({"op": "cm", "call": "load"})", "'load' needs 'names'"},
      {R"({"op": "cm", "call": "switch"})", "needs 'start' or 'stop'"},
      {R"({"op": "cm", "call": "load", "names": [1]})", "list of names"},
      {R"({"op": "expr", "channel": "x", "expressions": []})", "1 to 64"},
      {R"({"op": "expr", "channel": "x", "expressions": ["t"], "rate": 0})", "'rate'"},
      {R"({"op": "expr", "channel": "x", "expressions": ["t"], "rate": 1e9})", "'rate'"},
      {R"({"id": "seven", "op": "cm", "call": "list"})", "'id' must be an integer"},
      // What ended the dashboard once (a number out of range is not a parse_error), and other types in odd places.
      {"[1e400]", "not JSON"},
      {R"({"op": "publish", "channel": "x", "type": "float64_t", "msg": {"data": -1e400}})", "not JSON"},
      {R"({"id": 1e30, "op": "cm", "call": "list"})", "'id' must be an integer"},
      {R"({"op": 5})", "'op'"},
      {R"({"op": "cm", "call": "switch", "start": "j1"})", "list of names"},
      {R"({"op": "expr", "channel": "x", "expressions": ["t"], "rate": "fast"})", "'rate'"},
      {"\"\xff\"", "not JSON"},
  };
  for (const auto& [text, why] : cases) {
    const auto p = parse_request(text, false);
    EXPECT_FALSE(p.ok()) << text;
    EXPECT_NE(p.error.find(why), std::string::npos) << text << " -> " << p.error;
  }
}

TEST(DashboardRequests, DeepNestingWithinTheMessageLimitIsRefusedNotACrash) {
  const size_t depth = 30000;  // 60 KB: under the WebSocket's 64 KB limit
  const auto p = parse_request(std::string(depth, '[') + std::string(depth, ']'), false);
  EXPECT_FALSE(p.ok());
  EXPECT_NE(p.error.find("JSON object"), std::string::npos) << p.error;
}

TEST(DashboardRequests, ReadOnlyShowsButRefusesEveryCommand) {
  for (const char* text : {R"({"op": "publish", "channel": "e_stop", "type": "e_stop_t", "msg": {"engaged": 1}})",
                           R"({"op": "cm", "call": "switch", "stop": ["j1_controller"]})",
                           R"({"op": "expr", "channel": "x", "expressions": ["t"]})",
                           R"({"op": "publish", "channel": "sim_server/gains/set", "type": "pid_gains_t",
                               "msg": {"joint": "j1", "p": 5}})"}) {
    const auto p = parse_request(text, true);
    EXPECT_FALSE(p.ok()) << text;
    EXPECT_NE(p.error.find("--read-only"), std::string::npos) << p.error;
  }
  // Looking is allowed: the list, and a gains query.
  EXPECT_TRUE(parse_request(R"({"op": "cm", "call": "list"})", true).ok());
  EXPECT_TRUE(parse_request(R"({"op": "publish", "channel": "sim_server/gains/set", "type": "pid_gains_t",
                                "msg": {"joint": "j1", "query": 1}})", true).ok());
}

TEST(DashboardRequests, ReplyIsJson) {
  const auto j = nlohmann::json::parse(reply_json(3, false, "bad \xff byte"));
  EXPECT_EQ(j["kind"], "reply");
  EXPECT_EQ(j["id"], 3);
  EXPECT_EQ(j["ok"], false);
}

}  // namespace
}  // namespace lcm_control::dashboard
