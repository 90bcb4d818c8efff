#include "tools/lib/files/xacro_program.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "description/robot_file.hpp"
#include "xacro/xacro.hpp"

namespace lcm_control::tools {

void add_xacro_flags(CLI::App& app, XacroFlags& f) {
  app.add_option("input", f.positional, "the xacro file, then NAME:=VALUE arguments for $(arg NAME)")->required();
  app.add_option("-o", f.output, "write the output to FILE instead of stdout")->type_name("FILE");
  app.add_flag("--deps", f.deps, "print the files the expansion reads (includes, YAML), space-separated, not the XML");
  app.add_flag("--inorder,-i", f.inorder, "accepted for compatibility (in-order processing is the only one)");
  app.add_option("--budget", f.budget,
                 "raise (or lower) every expansion budget by this factor; default: $LCM_CONTROL_XACRO_BUDGET, else 1")
      ->type_name("FACTOR")
      ->check(CLI::PositiveNumber);
  app.add_flag("--stats", f.stats, "print what the expansion built against its budget to stderr");
  add_package_path_flag(app, f.package_path);
  app.get_option("--package-path")->allow_extra_args(false);  // NAME:=VALUE after it stays an argument
}

int run_xacro(const XacroFlags& f) {
  std::string input;
  LoadOptions options;
  options.package_path = f.package_path;
  options.xacro_budget = f.budget;
  for (const std::string& p : f.positional) {
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
  if (f.stats) {
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
  if (f.deps) {
    // The official --deps: the files read besides the input, space-separated, no line end.
    std::vector<std::string> files(files_read.begin() + 1, files_read.end());
    text = fmt::format("{}", fmt::join(files, " "));
  } else {
    text = xml;
  }
  if (f.output.empty()) {
    std::fwrite(text.data(), 1, text.size(), stdout);
    return std::fflush(stdout) == 0 ? kExitOk : kExitFailure;
  }
  const std::filesystem::path parent = std::filesystem::path(f.output).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);  // as xacro does; open reports a failure
  std::ofstream out(f.output, std::ios::binary);
  out << text;
  out.close();
  if (!out) {
    std::fprintf(stderr, "xacro: error: cannot write %s\n", f.output.c_str());
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace lcm_control::tools
