#include "description/substitution.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "description/packages.hpp"
#include "description/robot_model.hpp"
#include "description/text.hpp"
#include "description/xacro/process_error.hpp"
#include "description/xacro/substitution_args.hpp"

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

// roslaunch's $(eval EXPR): a Python expression over the args (by name, or arg('NAME')) and find(), env(),
// optenv(), evaluated by xacro's evaluator (description/xacro), as roslaunch and xacro share it.
std::string evaluate(const std::string& expression, const Substitutions& subs, const std::string& where) {
  std::map<std::string, std::string> args;
  for (const auto& [k, v] : subs.args) args[k] = v;
  const auto path = subs.package_path.empty() ? default_package_path() : subs.package_path;
  xacro::SubstitutionContext context;
  context.args = &args;
  context.find_package = [&path](const std::string& name) {
    const std::string dir = find_package_dir(name, path);
    return dir.empty() ? dir : fs::absolute(dir).string();
  };
  context.package_search_note = fmt::format(
      "the package path is {}; give the folder that holds it with --package-path DIR or LCM_CONTROL_PACKAGE_PATH",
      path.empty() ? "empty" : fmt::format("{}", fmt::join(path, ":")));
  try {
    return xacro::resolve_substitution("eval " + expression, context);
  } catch (const xacro::ProcessError& e) {
    std::string why = e.what();
    why = why.substr(0, why.find("\nwhen evaluating"));
    for (char& c : why)
      if (c == '\n') c = ' ';
    throw ModelError(fmt::format("{}: $(eval {}): {}", where, expression, why));
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
    const auto words = split_words(text.substr(start + 2, end - start - 2));
    const std::string kind = words.empty() ? "" : words[0];
    if (eval) {
      out += evaluate(text.substr(start + 7, end - start - 7), subs, where);
    } else if (kind == "find" && words.size() == 2) {
      const auto path = subs.package_path.empty() ? default_package_path() : subs.package_path;
      const std::string dir = find_package_dir(words[1], path);
      if (dir.empty())
        throw ModelError(fmt::format(
            "{}: $(find {}): package '{}' is not on the package path ({}); give the folder that holds it with "
            "--package-path DIR or LCM_CONTROL_PACKAGE_PATH",
            where, words[1], words[1], path.empty() ? "empty" : fmt::format("{}", fmt::join(path, ":"))));
      out += fs::absolute(dir).string();
    } else if ((kind == "arg" || kind == "var") && words.size() == 2) {  // $(var): ROS 2 launch's name for it
      const std::string* value = nullptr;
      for (const auto& [k, v] : subs.args)
        if (k == words[1]) value = &v;
      if (!value)
        throw ModelError(fmt::format("{}: $({} {}) has no value; {}", where, kind, words[1],
                                     fmt::format(fmt::runtime(subs.missing_arg_fix), words[1])));
      out += *value;
    } else if ((kind == "env" && words.size() == 2) || (kind == "optenv" && words.size() >= 2)) {
      const char* v = std::getenv(words[1].c_str());
      if (v)
        out += v;
      else if (kind == "optenv")
        for (size_t k = 2; k < words.size(); ++k) out += (k > 2 ? " " : "") + words[k];
      else
        throw ModelError(fmt::format("{}: $(env {}): the environment variable is not set", where, words[1]));
    } else {
      const size_t whole = closing_paren(text, start + 1);  // the whole of `$(cmd f(x))`, for the message
      throw ModelError(fmt::format("{}: '{}' is not supported (supported: $(find PKG), $(arg NAME), $(var NAME), "
                                   "$(env VAR), $(optenv VAR [default]), $(eval EXPR))",
                                   where, text.substr(start, (whole == std::string::npos ? end : whole) - start + 1)));
    }
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
