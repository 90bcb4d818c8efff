#include "description/substitution.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <map>
#include <stdexcept>

#include "description/packages.hpp"
#include "description/robot_model.hpp"
#include "description/text.hpp"
#include "xacro/process_error.hpp"
#include "xacro/substitution_args.hpp"

namespace fs = std::filesystem;

namespace lcm_control {

namespace {

// The ')' closing the '(' at `open`, past nested parentheses and quoted strings; npos if there is none.
size_t closing_paren(const std::string& text, size_t open) {
  int depth = 0;
  char quote = 0;
  for (size_t k = open; k < text.size(); ++k) {
    const char c = text[k];
    if (quote) {
      if (c == '\\') ++k;
      else if (c == quote) quote = 0;
    } else if (c == '\'' || c == '"') {
      quote = c;
    } else if (c == '(') {
      ++depth;
    } else if (c == ')' && --depth == 0) {
      return k;
    }
  }
  return std::string::npos;
}

// The engine (xacro/substitution_args) in roslaunch's dialect, its refusals worded for a launch file's or a YAML's
// user: what to pass, where the packages were looked for.
std::string resolve(const std::string& inner, const Substitutions& subs, const std::string& where) {
  std::map<std::string, std::string> args;
  for (const auto& [k, v] : subs.args) args[k] = v;  // later entries win
  const auto path = subs.package_path.empty() ? default_package_path() : subs.package_path;
  const std::string searched = path.empty() ? "empty" : fmt::format("{}", fmt::join(path, ":"));
  xacro::SubstitutionContext context;
  context.dialect = xacro::Dialect::RosParam;
  context.args = &args;
  context.find_package = [&path](const std::string& name) {
    const std::string dir = find_package_dir(name, path);
    return dir.empty() ? dir : fs::absolute(dir).string();
  };
  context.package_search_note = fmt::format(
      "the package path is {}; give the folder that holds it with --package-path DIR or LCM_CONTROL_PACKAGE_PATH",
      searched);
  context.messages.missing_arg = [&subs](const std::string& command, const std::string& name) {
    return fmt::format("$({} {}) has no value; {}", command, name, fmt::format(fmt::runtime(subs.missing_arg_fix), name));
  };
  context.messages.missing_package = [&searched](const std::string& name) {
    return fmt::format("$(find {}): package '{}' is not on the package path ({}); give the folder that holds it with "
                       "--package-path DIR or LCM_CONTROL_PACKAGE_PATH",
                       name, name, searched);
  };
  context.messages.missing_env = [](const std::string& variable) {
    return fmt::format("$(env {}): the environment variable is not set", variable);
  };
  context.messages.unsupported = [](const std::string& whole) {
    return fmt::format("'{}' is not supported (supported: $(find PKG), $(arg NAME), $(var NAME), $(env VAR), "
                       "$(optenv VAR [default]), $(eval EXPR))",
                       whole);
  };
  try {
    return xacro::resolve_substitution(inner, context);
  } catch (const xacro::ProcessError& e) {
    std::string why = e.what();
    const bool eval = inner.rfind("eval ", 0) == 0;
    why = why.substr(0, why.find("\nwhen evaluating"));
    for (char& c : why)
      if (c == '\n') c = ' ';
    throw ModelError(eval ? fmt::format("{}: $({}): {}", where, inner, why) : fmt::format("{}: {}", where, why));
  }
}

}  // namespace

std::string substitute(const std::string& text, const Substitutions& subs, const std::string& where) {
  std::string out;
  size_t pos = 0;
  while (true) {
    const size_t start = text.find("$(", pos);
    if (start == std::string::npos) break;
    const bool eval = text.compare(start, 7, "$(eval ") == 0;
    const size_t end = eval ? closing_paren(text, start + 1) : text.find(')', start);
    if (end == std::string::npos)
      throw ModelError(fmt::format("{}: unclosed '$(' in '{}'", where, trim(text)));
    out += text.substr(pos, start - pos);
    const std::string inner = text.substr(start + 2, end - start - 2);
    if (!eval && (text.find('(', start + 2) < end || split_words(inner).empty())) {
      const size_t whole = closing_paren(text, start + 1);  // `$(cmd f(x))` as written, or `$()`
      throw ModelError(fmt::format("{}: '{}' is not supported (supported: $(find PKG), $(arg NAME), $(var NAME), "
                                   "$(env VAR), $(optenv VAR [default]), $(eval EXPR))",
                                   where, text.substr(start, (whole == std::string::npos ? end : whole) - start + 1)));
    }
    out += resolve(inner, subs, where);
    pos = end + 1;
  }
  return out + text.substr(pos);
}

std::string substitute_file(const std::string& text, const Substitutions& subs, const std::string& file) {
  if (text.find("$(") == std::string::npos) return text;
  std::string out;
  // The same problem on many lines (one $(arg) used throughout) is said once, at its first line.
  std::vector<std::pair<std::string, int>> problems;  // text without "file:line: ", lines it occurs on
  std::vector<int> first_line;
  size_t start = 0;
  for (int line = 1; start <= text.size(); ++line) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string piece = text.substr(start, end - start);
    const std::string where = fmt::format("{}:{}", file, line);
    const size_t first = piece.find_first_not_of(" \t");
    try {
      out += first != std::string::npos && piece[first] == '#' ? piece : substitute(piece, subs, where);
    } catch (const ModelError& e) {
      for (const auto& p : e.problems()) {
        const std::string what = p.substr(std::min(p.size(), where.size() + 2));
        size_t k = 0;
        while (k < problems.size() && problems[k].first != what) ++k;
        if (k == problems.size()) {
          problems.emplace_back(what, 0);
          first_line.push_back(line);
        }
        ++problems[k].second;
      }
    }
    if (end < text.size()) out += '\n';
    start = end + 1;
  }
  if (problems.empty()) return out;
  std::vector<std::string> lines;
  for (size_t k = 0; k < problems.size(); ++k)
    lines.push_back(fmt::format("{}:{}: {}{}", file, first_line[k], problems[k].first,
                                problems[k].second > 1 ? fmt::format(" ({} lines use it)", problems[k].second) : ""));
  throw ModelError(lines);
}

std::pair<std::string, std::string> parse_arg(const std::string& assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0 || (eq == 1 && assignment[0] == ':'))
    throw std::invalid_argument("expected NAME=VALUE (or NAME:=VALUE), got '" + assignment + "'");
  const size_t name_end = assignment[eq - 1] == ':' ? eq - 1 : eq;
  return {assignment.substr(0, name_end), assignment.substr(eq + 1)};
}

}  // namespace lcm_control
