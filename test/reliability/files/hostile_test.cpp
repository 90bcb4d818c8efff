// The hostile-file corpus (issue 51): xacro, XML and YAML written to exhaust a reader (deep nesting, billion
// laughs, doubling, huge repeats and widths, anchor bombs, include bombs, loops that build nothing), generated here
// rather than checked in. Each must be refused with exit code 3 (never a signal), a message naming file:line and the
// limit or budget it crossed, in a bounded time and < 500 MB; the real robots' files expand as before. In-process
// (what every program runs, and what scripts/sanitize runs under the sanitizers), then through the xacro program
// with its time and peak memory printed (docs/reliability-figures.md).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "description/robot_file.hpp"
#include "test/support/process.hpp"

namespace lt = lcm_control::testing;
using namespace lcm_control;

namespace {

std::string robot(const std::string& body) {
  return "<?xml version=\"1.0\"?>\n<robot name=\"r\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n" + body +
         "\n</robot>\n";
}

std::string expression(const std::string& e) { return robot("<a v=\"${" + e + "}\"/>"); }

std::string repeated(const std::string& s, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += s;
  return out;
}

struct Case {
  std::string name;
  std::map<std::string, std::string> files;  // the first is the one expanded: "main.xacro"
  std::string where;                         // the file:line the message must name
  std::string limit;                         // and the limit it must name
};

std::vector<Case> corpus() {
  std::vector<Case> cases;
  auto one = [&](std::string name, std::string text, std::string limit) {
    cases.push_back({std::move(name), {{"main.xacro", std::move(text)}}, "main.xacro:3", std::move(limit)});
  };
  const std::string budget = "expansion budget exceeded";
  {
    std::string b = "<xacro:macro name=\"l0\"><link name=\"x\"/></xacro:macro>\n";
    for (int i = 1; i <= 9; ++i)
      b += "<xacro:macro name=\"l" + std::to_string(i) + "\">" + repeated("<xacro:l" + std::to_string(i - 1) + "/>", 10) +
           "</xacro:macro>\n";
    cases.push_back({"billion laughs: 9 macro levels, each calling the one below 10 times",
                     {{"main.xacro", robot(b + "<xacro:l9/>")}},
                     "main.xacro:4",
                     budget + ": 100001 macro calls"});
  }
  {
    std::string b = "<xacro:property name=\"p0\" value=\"xxxxxxxxxx\"/>\n";
    for (int i = 1; i <= 40; ++i)
      b += "<xacro:property name=\"p" + std::to_string(i) + "\" value=\"${p" + std::to_string(i - 1) + "+p" +
           std::to_string(i - 1) + "}\"/>\n";
    cases.push_back({"a property doubled 40 times", {{"main.xacro", robot(b + "<a v=\"${p40}\"/>")}}, "main.xacro:44",
                     budget + ": a string of"});
  }
  one("[0]*10**9", expression("[0]*10**9"), budget + ": a list of 1000000000 items");
  one("'%2000000000d' % 1", expression("'%2000000000d' % 1"), budget + ": a string of 2000000000 bytes");
  one("'%.2000000000f' % 1.0", expression("'%.2000000000f' % 1.0"), budget + ": a string of 2000000000 bytes");
  one("'{:2000000000}'.format(1)", expression("(chr(123)+':2000000000'+chr(125)).format(1)"),
      budget + ": a string of 2000000000 bytes");
  one("'x'*10**10", expression("'x'*10**10"), budget + ": a string of 10000000000 bytes");
  one("range(10**9)", expression("len(range(10**9))"), budget + ": a list of 1000000000 items");
  one("' '.join([1 MB]*1000)", expression("len(' '.join(['x'*1000000]*1000))"), budget + ": a string of");
  one("a comprehension of 10**9 items", expression("len([i for i in range(10**6) for j in range(10**3)])"),
      budget + ": a list of");
  one("a loop of 10**10 steps that builds nothing",
      expression("len([i for i in range(100000) for j in range(100000) if 0])"), budget + ": 4194305 evaluation steps");
  one("str.replace('', 1 KB) on 1 MB", expression("('x'*1000000).replace('', 'y'*1000)"), budget + ": a string of");
  one("list() of a 10 MB string", expression("len(list('x'*10000000))"), budget + ": a list of 10000000 items");
  one("5,000 parentheses", expression(std::string(5000, '(') + "1" + std::string(5000, ')')),
      "nests deeper than 400 levels");
  one("20,000 unary minus", expression(std::string(20000, '-') + "1"), "nests deeper than 400 levels");
  one("a lambda calling itself", expression("(lambda f: f(f))(lambda f: f(f))"), "maximum recursion depth exceeded");
  one("a macro calling itself", robot("<xacro:macro name=\"m\"><xacro:m/></xacro:macro><xacro:m/>"),
      "maximum recursion depth exceeded");
  one("200,000 macro calls", robot("<xacro:macro name=\"m\"/>" + repeated("<xacro:m/>", 200000)),
      budget + ": 100001 macro calls");
  cases.push_back({"XML 10,000 elements deep",
                   {{"main.xacro", robot(repeated("<a>", 10000) + repeated("</a>", 10000))}},
                   "main.xacro",
                   "elements nest deeper than 1000 levels"});
  cases.push_back({"an empty file", {{"main.xacro", ""}}, "main.xacro:1", "no element found"});
  {
    std::string y = "a: &a [x, x, x, x, x, x, x, x, x, x]\n";
    const std::string names = "abcdefghij";
    for (size_t i = 1; i < names.size(); ++i) {
      y += std::string(1, names[i]) + ": &" + names[i] + " [";
      for (int k = 0; k < 10; ++k) y += std::string(k ? ", " : "") + "*" + names[i - 1];
      y += "]\n";
    }
    cases.push_back({"a YAML anchor bomb (10**9 items if copied), printed whole",
                     {{"main.xacro", robot("<xacro:property name=\"y\" value=\"${xacro.load_yaml('bomb.yaml')}\"/>\n"
                                           "<a v=\"${len(str(y))}\"/>")},
                      {"bomb.yaml", y}},
                     "main.xacro:4",
                     budget + ": a string of"});
  }
  {
    Case c{"an include bomb: 8 levels of 10 includes each", {}, "inc6.xacro:2", budget + ": 10001 files included"};
    c.files["main.xacro"] = robot("<xacro:include filename=\"inc0.xacro\"/>");
    for (int i = 0; i < 8; ++i) {
      const std::string body =
          i < 7 ? repeated("<xacro:include filename=\"inc" + std::to_string(i + 1) + ".xacro\"/>", 10) : "<link name=\"l\"/>";
      c.files["inc" + std::to_string(i) + ".xacro"] =
          "<?xml version=\"1.0\"?>\n<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\">" + body + "</robot>\n";
    }
    cases.push_back(c);
  }
  return cases;
}

// Writes a case's files into a fresh folder; returns the path of main.xacro.
std::string write_case(const Case& c) {
  const std::string dir = lt::temp_dir("hostile");
  for (const auto& [name, text] : c.files) std::ofstream(dir + "/" + name, std::ios::binary) << text;
  return dir + "/main.xacro";
}

std::string expansion_error(const std::string& path, const LoadOptions& options = {}) {
  try {
    expand_xacro(path, options);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(HostileFiles, EachIsRefusedInProcessNamingFileLineAndTheLimit) {
  for (const Case& c : corpus()) {
    const std::string path = write_case(c);
    const std::string dir = path.substr(0, path.rfind('/') + 1);
    const std::string msg = expansion_error(path);
    EXPECT_NE(msg.find(dir + c.where), std::string::npos) << c.name << ": " << msg.substr(0, 600);
    EXPECT_NE(msg.find(c.limit), std::string::npos) << c.name << ": " << msg.substr(0, 600);
  }
}

// The budget is a factor a user can raise: what one budget refuses, twice the budget builds.
TEST(HostileFiles, RaisingTheBudgetLetsALargerFileThrough) {
  const std::string path = write_case(
      {"150,000 calls", {{"main.xacro", robot("<xacro:macro name=\"m\"/>" + repeated("<xacro:m/>", 150000))}}, "", ""});
  EXPECT_NE(expansion_error(path).find("100001 macro calls"), std::string::npos);
  LoadOptions twice;
  twice.xacro_budget = 2;
  EXPECT_EQ(expansion_error(path, twice), "");
  // A legitimate use of everything the corpus abuses, at real sizes, expands.
  const std::string fine = write_case(
      {"fine",
       {{"main.xacro", robot("<xacro:property name=\"y\" value=\"${xacro.load_yaml('ok.yaml')}\"/>\n"
                             "<a v=\"${len(y['b'])} ${'%5.2f' % 1.5} ${len(dict([(i, i) for i in range(10000)]))} "
                             "${len(' '.join(['x'] * 1000))}\"/>")},
        {"ok.yaml", "a: &a [1, 2, 3]\nb: [*a, *a, *a]\n"}},
       "",
       ""});
  EXPECT_EQ(expansion_error(fine), "");
}

// Strings are text, not bytes: indexing, len and case mapping count code points, so no expansion writes a broken
// UTF-8 sequence into the URDF (before: ${'é'[0]} wrote a lone 0xC3 byte, and len('é') was 2).
TEST(HostileFiles, NonAsciiStringsStayValidUtf8) {
  const std::string path = write_case(
      {"utf-8",
       {{"main.xacro", expression("'é'[0] + str(len('é')) + 'привет'.upper() + 'héllo'[1:3] + '→'.zfill(3)")}},
       "",
       ""});
  const std::string urdf = expand_xacro(path, {});
  EXPECT_NE(urdf.find("v=\"é1ПРИВЕТél00→\""), std::string::npos) << urdf;
  size_t bad = 0;  // bytes that are no part of a well-formed UTF-8 sequence
  for (size_t i = 0; i < urdf.size();) {
    const auto c = static_cast<unsigned char>(urdf[i]);
    const size_t n = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
    bool ok = n > 0 && i + n <= urdf.size();
    for (size_t k = 1; ok && k < n; ++k) ok = (static_cast<unsigned char>(urdf[i + k]) >> 6) == 2;
    if (!ok) {
      ++bad;
      ++i;
    } else {
      i += n;
    }
  }
  EXPECT_EQ(bad, 0u);
  std::printf("RELIABILITY|files|non-ASCII strings indexed, measured, sliced and case-mapped|tried=1|ok=%d|crashes=0|"
              "hangs=0|output valid UTF-8 (%zu bad bytes)\n",
              bad == 0 && urdf.find("é1ПРИВЕТ") != std::string::npos ? 1 : 0, bad);
}

TEST(HostileFiles, ThroughTheXacroProgramEachExitsThreeWithinBoundsOfTimeAndMemory) {
  int tried = 0, ok = 0, crashes = 0, hangs = 0;
  for (const Case& c : corpus()) {
    const std::string path = write_case(c);
    const auto start = std::chrono::steady_clock::now();
    // Under an address-space limit of 500 MB: a file that needed more would fail to allocate and not exit 3.
    lt::ChildProcess xacro({"/usr/bin/prlimit", "--as=524288000", lt::bin("xacro"), path, "-o", path + ".urdf"});
    const int rc = xacro.wait(30);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (rc == -1) xacro.stop(1);
    const long rss_mb = xacro.peak_rss_kb() / 1024;
    const std::string out = xacro.output();
    ++tried;
    hangs += rc == -1;
    crashes += rc >= 128;
    const bool good = rc == 3 && out.find(c.limit) != std::string::npos && rss_mb < 500;
    ok += good;
    EXPECT_TRUE(good) << c.name << ": exit " << rc << ", " << rss_mb << " MB\n" << out.substr(0, 600);
    std::printf("RELIABILITY|files|hostile xacro: %s|tried=1|ok=%d|crashes=%d|hangs=%d|exit %d in %.2f s, peak RSS "
                "%ld MB (sampled every 5 ms; address space capped at 500 MB): %s\n",
                c.name.c_str(), good ? 1 : 0, rc >= 128 ? 1 : 0, rc == -1 ? 1 : 0, rc, seconds, rss_mb, c.limit.c_str());
  }
  EXPECT_EQ(ok, tried);
  EXPECT_EQ(crashes, 0);
  EXPECT_EQ(hangs, 0);
}

// doctor, sim_server and launch read xacro through the same library: one hostile file through each program.
TEST(HostileFiles, DoctorSimServerAndLaunchRefuseItTheSameWay) {
  const std::vector<Case> cases = corpus();
  const std::string path = write_case(cases[0]);
  for (const std::vector<std::string>& argv :
       {std::vector<std::string>{lt::bin("doctor"), "--urdf", path},
        std::vector<std::string>{lt::bin("sim_server"), "--urdf", path, "--duration", "0.1"},
        std::vector<std::string>{lt::bin("launch"), "--urdf", path, "--duration", "0.1"}}) {
    lt::ChildProcess p(argv);
    const int rc = p.wait(30);
    EXPECT_EQ(rc, 3) << argv[0] << "\n" << p.output().substr(0, 600);
    EXPECT_NE(p.output().find(cases[0].limit), std::string::npos) << argv[0] << "\n" << p.output().substr(0, 600);
    EXPECT_NE(p.output().find(path.substr(0, path.rfind('/')) + "/main.xacro:4"), std::string::npos) << argv[0];
  }
}
