// bench_xacro: what expanding a .urdf.xacro costs against reading the URDF it expands to, in one fresh process
// (the first of each is what a program pays at start: nothing cached). Both through description/robot_file, the
// path every program takes: the xacro through our xacro; the expanded URDF written to a temporary file and read as
// a URDF (file read + XML parse into the robot model's links and joints, meshes resolved).
//   bench_xacro [--repeat N] [--package-path DIRS] FILE [NAME:=VALUE ...]
// Prints:
//   xacro FIRST_EXPAND_MS MEDIAN_EXPAND_MS FIRST_READ_MS MEDIAN_READ_MS FILES_READ URDF_BYTES
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "description/robot_file.hpp"
#include "description/substitution.hpp"
#include "description/text.hpp"
#include "description/urdf_reader.hpp"

namespace {

using namespace lcm_control;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 20;
  LoadOptions options;
  std::string file;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--repeat" && k + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++k]));
    } else if (a == "--package-path" && k + 1 < argc) {
      for (const auto& d : split(argv[++k], ':'))
        if (!d.empty()) options.package_path.push_back(d);
    } else if (file.empty() && a.find(":=") == std::string::npos) {
      file = a;
    } else {
      options.xacro_args.push_back(parse_arg(a));
    }
  }
  if (file.empty()) {
    std::fprintf(stderr, "usage: bench_xacro [--repeat N] [--package-path DIRS] FILE [NAME:=VALUE ...]\n");
    return 2;
  }
  try {
    std::vector<double> expand, read;
    std::vector<std::string> files;
    std::string xml;
    for (int r = 0; r < repeat; ++r) {
      files.clear();
      const auto t0 = Clock::now();
      xml = read_robot_file(file, options, &files);
      expand.push_back(ms_since(t0));
    }
    const auto dir = std::filesystem::temp_directory_path() / ("bench_xacro_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string urdf = (dir / "expanded.urdf").string();
    std::ofstream(urdf) << xml;
    for (int r = 0; r < repeat; ++r) {
      RobotModel model;
      const auto t0 = Clock::now();
      load_urdf_into(model, urdf, options);
      read.push_back(ms_since(t0));
    }
    std::filesystem::remove_all(dir);
    std::printf("xacro %.3f %.3f %.3f %.3f %zu %zu\n", expand.front(), median(expand), read.front(), median(read),
                files.size(), xml.size());
    return 0;
  } catch (const ModelError& e) {
    for (const auto& p : e.problems()) std::fprintf(stderr, "bench_xacro: %s\n", p.c_str());
    return 3;
  }
}
