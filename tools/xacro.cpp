// xacro: expands a .xacro robot description (macros, properties, includes, ${...}, $(arg/find/env ...),
// xacro.load_yaml) into the document the official ROS xacro prints, without ROS: $(find PKG) is searched on
// --package-path, $LCM_CONTROL_PACKAGE_PATH and $ROS_PACKAGE_PATH, then beside the file's own package. Exit 0 done, 2 bad command line, 3 a file that
// cannot be expanded (the message names the file:line and the macro calls and includes that led there).
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cli/cli.hpp"
#include "description/robot_file.hpp"
#include "description/xacro/xacro.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  CLI::App app{
      "Expand a xacro file (a robot's .urdf.xacro) into its URDF, as the official ROS xacro does, without ROS.\n"
      "Example: xacro ur_gz.urdf.xacro ur_type:=ur5e name:=ur --package-path ~/robots -o ur5e.urdf",
      "xacro"};
  std::vector<std::string> positional, package_path;
  std::string output;
  bool deps = false, inorder = false, stats = false;
  double budget = 0;
  app.add_option("input", positional, "the xacro file, then NAME:=VALUE arguments for $(arg NAME)")->required();
  app.add_option("-o", output, "write the output to FILE instead of stdout")->type_name("FILE");
  app.add_flag("--deps", deps, "print the files the expansion reads (includes, YAML), space-separated, not the XML");
  app.add_flag("--inorder,-i", inorder, "accepted for compatibility (in-order processing is the only one)");
  app.add_option("--budget", budget,
                 "raise (or lower) every expansion budget by this factor; default: $LCM_CONTROL_XACRO_BUDGET, else 1")
      ->type_name("FACTOR")
      ->check(CLI::PositiveNumber);
  app.add_flag("--stats", stats, "print what the expansion built against its budget to stderr");
  add_package_path_flag(app, package_path);
  app.get_option("--package-path")->allow_extra_args(false);  // NAME:=VALUE after it stays an argument
  return run_program(app, argc, argv, [&] {
    std::string input;
    LoadOptions options;
    options.package_path = package_path;
    options.xacro_budget = budget;
    for (const std::string& p : positional) {
      if (p.find(":=") != std::string::npos) {
        try {
          options.xacro_args.push_back(xacro::parse_arg(p));
        } catch (const std::invalid_argument& e) {
          throw CLI::ValidationError("input", e.what());
        }
      } else if (input.empty()) {
        input = p;
      } else {
        throw CLI::ValidationError("input", "expected exactly one input file, got '" + input + "' and '" + p + "'");
      }
    }
    if (input.empty()) throw CLI::ValidationError("input", "expected exactly one input file as argument");
    std::vector<std::string> files_read;
    xacro::BudgetUse use;
    const std::string xml = expand_xacro(input, options, &files_read, &use);
    if (stats) {
      const xacro::Budget b = xacro_budget(options);
      std::fprintf(stderr,
                   "%s",
                   fmt::format("expansion budget used (of the budget): largest string {} bytes ({}), largest list {} "
                               "items ({}), evaluation steps {} ({}), XML nodes {} ({}), macro calls {} ({}), includes {} ({}), document text {} bytes ({})\n",
                               use.largest_string, b.string_bytes, use.largest_list, b.list_items, use.operations, b.operations, use.nodes, b.nodes,
                               use.macro_calls, b.macro_calls, use.includes, b.includes, use.document_bytes,
                               b.document_bytes)
                       .c_str());
    }
    std::string text;
    if (deps) {
      // The official --deps: the files read besides the input, space-separated, no line end.
      std::vector<std::string> files(files_read.begin() + 1, files_read.end());
      text = fmt::format("{}", fmt::join(files, " "));
    } else {
      text = xml;
    }
    if (output.empty()) {
      std::fwrite(text.data(), 1, text.size(), stdout);
      return std::fflush(stdout) == 0 ? kExitOk : kExitFailure;
    }
    const std::filesystem::path parent = std::filesystem::path(output).parent_path();
    std::error_code ec;
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);  // as xacro does; open reports a failure
    std::ofstream out(output, std::ios::binary);
    out << text;
    out.close();
    if (!out) {
      std::fprintf(stderr, "xacro: error: cannot write %s\n", output.c_str());
      return kExitFailure;
    }
    return kExitOk;
  });
}
