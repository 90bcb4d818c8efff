// lcm-control: the one command `cmake --install` puts in bin/. `lcm-control PROGRAM ARGS...` runs PROGRAM, as
// `ros2 launch` runs launch: installed from libexec/lcm_control/, in the build tree from beside it (build/bin/).
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/cli.hpp"
#include "description/text.hpp"

namespace {

namespace fs = std::filesystem;

struct Program {
  std::string name, purpose;
};

// packaging/programs.txt: "PROGRAM<TAB>purpose" lines, '#' comments.
std::vector<Program> programs() {
  static const char* const table =
#include "programs.inc"
      ;
  std::vector<Program> out;
  for (const std::string& line : lcm_control::split(table, '\n')) {
    const size_t tab = line.find('\t');
    if (line.empty() || line[0] == '#' || tab == std::string::npos) continue;
    out.push_back({line.substr(0, tab), line.substr(line.find_first_not_of('\t', tab))});
  }
  return out;
}

// Installed: PREFIX/bin/lcm-control runs PREFIX/libexec/lcm_control/PROGRAM; in the build tree (no such folder)
// build/bin/lcm-control runs build/bin/PROGRAM.
fs::path program_dir() {
  const fs::path exe_dir = fs::read_symlink("/proc/self/exe").parent_path();
  const fs::path installed = exe_dir / LCM_CONTROL_LIBEXEC_FROM_BIN;
  std::error_code ec;
  return fs::is_directory(installed, ec) ? installed : exe_dir;
}

void print_help(std::FILE* out) {
  std::fprintf(out,
               "Run one of lcm_control's programs: lcm-control PROGRAM [ARGS...], as `ros2 launch` and `ros2 topic` "
               "run theirs. `lcm-control PROGRAM --help` describes PROGRAM; its man page is lcm-control-PROGRAM(1). "
               "In a build tree the same program is build/bin/PROGRAM (`lcm-control launch` = `build/bin/launch`).\n"
               "Examples:\n"
               "  lcm-control doctor --urdf robot.urdf --config robot.yaml\n"
               "  lcm-control launch robot.launch.yaml\n"
               "  lcm-control cmctl list\n"
               "  lcm-control bus echo joint_states --count 1\n"
               "Usage: lcm-control [OPTIONS] PROGRAM [ARGS...]\n\n"
               "Options:\n"
               "  -h,--help                   Print this help message and exit\n"
               "  --version                   Print the version of lcm_control and exit\n\n"
               "Subcommands:\n");
  for (const Program& p : programs()) std::fprintf(out, "  %-27s %s\n", p.name.c_str(), p.purpose.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lcm_control;
  if (argc < 2) {
    print_help(stderr);
    std::fprintf(stderr, "lcm-control: error: name a program to run (listed above)\n");
    return kExitUsage;
  }
  const std::string name = argv[1];
  if (name == "-h" || name == "--help") {
    print_help(stdout);
    return kExitOk;
  }
  if (name == "--version") {
    std::printf("lcm-control %s\n", LCM_CONTROL_VERSION);
    return kExitOk;
  }
  std::vector<std::string> names;
  for (const Program& p : programs()) names.push_back(p.name);
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    const bool flag = !name.empty() && name[0] == '-';
    const std::string near = flag ? "" : closest_name(name, names, std::min<size_t>(3, (name.size() + 1) / 2));
    const std::string what = std::string(flag ? "no flag '" : "no program '") + name + "'";
    if (!near.empty())
      std::fprintf(stderr, "lcm-control: error: %s; did you mean '%s'? (lcm-control --help lists the programs)\n",
                   what.c_str(), near.c_str());
    else
      std::fprintf(stderr, "lcm-control: error: %s; the programs: %s (lcm-control --help says what each does)\n",
                   what.c_str(), join(names).c_str());
    return kExitUsage;
  }
  const std::string path = (program_dir() / name).string();
  execv(path.c_str(), argv + 1);
  std::fprintf(stderr, "lcm-control: error: cannot run %s: %s (is the installation complete?)\n", path.c_str(),
               std::strerror(errno));
  return kExitFailure;
}
