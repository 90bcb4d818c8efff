// xacro's `$(...)` substitution args (see substitution_args.hpp).
#include "xacro/substitution_args.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <climits>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <vector>

#include "xacro/process_error.hpp"
#include "xacro/python/python_expr.hpp"
#include "xacro/python/python_literals.hpp"
#include "xacro/python/value.hpp"

namespace lcm_control::xacro {

namespace {

const char* const kValidCommands = "['find', 'env', 'optenv', 'dirname', 'arg', 'anon', 'eval', 'cwd']";

// roslaunch's state machine: the `$(...)` groups of text, without their `$(` and `)`.
std::vector<std::string> collect_args(const std::string& text) {
  enum { Out, Dollar, LeftParen, In } state = Out;
  std::vector<std::string> args;
  std::string buffer;
  for (char c : text) {
    if (c == '$') {
      if (state == Out) {
        state = Dollar;
      } else if (state != Dollar) {
        throw ProcessError(fmt::format("Dollar signs \"$\" cannot be inside of substitution args [{}]", text));
      }
    } else if (c == '(') {
      if (state == Dollar) {
        state = LeftParen;
      } else if (state != Out) {
        throw ProcessError(fmt::format("Invalid left parenthesis \"(\" in substitution args [{}]", text));
      }
    } else if (c == ')') {
      if (state == In) {
        args.push_back(buffer);
        buffer.clear();
      }
      state = Out;
    } else if (state == Dollar) {
      state = Out;
    } else if (state == LeftParen) {
      state = In;
    }
    if (state == In) buffer += c;
  }
  return args;
}

std::vector<std::string> split_words(const std::string& s) {
  std::vector<std::string> words;
  size_t i = 0;
  while (i < s.size()) {
    size_t j = s.find(' ', i);
    if (j == std::string::npos) j = s.size();
    if (j > i) words.push_back(s.substr(i, j - i));
    i = j + 1;
  }
  return words;
}

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  size_t pos = 0;
  while ((pos = s.find(from, pos)) != std::string::npos) {
    s.replace(pos, from.size(), to);
    pos += to.size();
  }
}

std::string find_package(const std::string& name, SubstitutionContext& ctx) {
  std::string dir = ctx.find_package ? ctx.find_package(name) : std::string();
  if (dir.empty() && ctx.messages.missing_package) throw ProcessError(ctx.messages.missing_package(name));
  if (dir.empty()) {
    std::string msg = fmt::format("package '{}' not found ($(find {}))", name, name);
    if (!ctx.package_search_note.empty()) msg += "\n" + ctx.package_search_note;
    throw ProcessError(msg);
  }
  return dir;
}

std::string dirname_of(const std::string& file) {
  if (file.empty()) throw ProcessError("Cannot substitute $(dirname), no file/directory information available.");
  std::error_code ec;
  std::filesystem::path p = std::filesystem::absolute(std::filesystem::path(file).parent_path(), ec);
  std::string s = p.lexically_normal().string();
  if (s.size() > 1 && s.back() == '/') s.pop_back();
  return s;
}

std::string anon_name(const std::string& id, SubstitutionContext& ctx) {
  if (ctx.anon) {
    auto it = ctx.anon->find(id);
    if (it != ctx.anon->end()) return it->second;
  }
  char host[256] = "localhost";
  gethostname(host, sizeof host - 1);
  std::random_device rd;
  std::string name = fmt::format("{}_{}_{}_{}", id, host, getpid(), std::uniform_int_distribution<uint64_t>(0, INT64_MAX)(rd));
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  if (ctx.anon) (*ctx.anon)[id] = name;
  return name;
}

const std::string& arg_value(const std::string& name, SubstitutionContext& ctx, const std::string& command = "arg") {
  auto it = ctx.args->find(name);
  if (it == ctx.args->end() && ctx.messages.missing_arg) throw ProcessError(ctx.messages.missing_arg(command, name));
  if (it == ctx.args->end())
    throw ProcessError(fmt::format("Undefined substitution argument {}: give it on the command line ({}:=VALUE) or "
                                   "declare it with <xacro:arg name=\"{}\" default=\"...\"/>",
                                   name, name, name));
  return it->second;
}

// The names $(eval ...) sees: the args (typed as roslaunch's convert_value 'auto'), arg(), env(), optenv(), find(),
// dirname(), true/false.
class EvalNames : public Names {
 public:
  explicit EvalNames(SubstitutionContext& ctx) : ctx_(ctx) {}
  std::optional<Value> lookup(const std::string& name) const override {
    SubstitutionContext& ctx = ctx_;
    if (name == "true" || name == "True") return Value::boolean(true);
    if (name == "false" || name == "False") return Value::boolean(false);
    if (name == "arg")
      return Value::callable("arg", [&ctx](const List& a, const Kwargs&) {
        return convert_auto(arg_value(str(a.at(0)), ctx));
      });
    if (name == "env")
      return Value::callable("env", [](const List& a, const Kwargs&) {
        const std::string var = str(a.at(0));
        const char* v = std::getenv(var.c_str());
        if (!v) throw EvalError("SubstitutionException", fmt::format("environment variable '{}' is not set", var));
        return Value::string(v);
      });
    if (name == "optenv")
      return Value::callable("optenv", [](const List& a, const Kwargs&) {
        const char* v = std::getenv(str(a.at(0)).c_str());
        return Value::string(v ? std::string(v) : a.size() > 1 ? str(a[1]) : std::string());
      });
    if (name == "find")
      return Value::callable("find", [&ctx](const List& a, const Kwargs&) {
        return Value::string(find_package(str(a.at(0)), ctx));
      });
    if (name == "dirname")
      return Value::callable("dirname", [&ctx](const List&, const Kwargs&) {
        return Value::string(dirname_of(ctx.current_file));
      });
    if (name.find("__") == std::string::npos) {
      auto it = ctx.args->find(name);
      if (it != ctx.args->end()) return convert_auto(it->second);
    }
    return std::nullopt;
  }

 private:
  SubstitutionContext& ctx_;
};

std::string eval_command(const std::string& expression, SubstitutionContext& ctx) {
  if (expression.find("__") != std::string::npos)
    throw ProcessError("$(eval ...) may not contain double underscore expressions");
  try {
    return str(evaluate(expression, EvalNames(ctx)));
  } catch (const EvalError& e) {
    throw ProcessError(fmt::format("{}\nwhen evaluating $(eval {})", e.what(), expression));
  }
}

// One pass of roslaunch's _resolve_args over text, applying the commands in `apply`.
std::string resolve_pass(const std::string& text, SubstitutionContext& ctx, bool find_only) {
  std::string resolved = text;
  for (const std::string& a : collect_args(text)) {
    std::vector<std::string> words = split_words(a);
    const std::string command = words.empty() ? std::string() : words[0];
    const std::vector<std::string> args(words.begin() + (words.empty() ? 0 : 1), words.end());
    const std::string whole = "$(" + a + ")";
    const bool ros = ctx.dialect == Dialect::RosParam;
    const bool known = command == "find" || command == "env" || command == "optenv" || command == "arg" ||
                       (ros ? command == "var" : command == "dirname" || command == "anon");
    if (!known || (ros && (command == "find" || command == "var" || command == "env") && args.size() != 1) ||
        (ros && command == "arg" && args.size() != 1)) {
      if (ctx.messages.unsupported) throw ProcessError(ctx.messages.unsupported(whole));
      if (!known)
        throw ProcessError(fmt::format("Unknown substitution command [{}]. Valid commands are {}", a, kValidCommands));
    }
    if (command == "find") {
      if (args.size() != 1) throw ProcessError(fmt::format("$(find pkg) accepts exactly one argument [{}]", a));
      replace_all(resolved, whole, find_package(args[0], ctx));
      continue;
    }
    if (find_only) continue;
    if (command == "env") {
      if (args.size() != 1) throw ProcessError(fmt::format("$(env var) command only accepts one argument [{}]", a));
      const char* v = std::getenv(args[0].c_str());
      if (!v && ctx.messages.missing_env) throw ProcessError(ctx.messages.missing_env(args[0]));
      if (!v) throw ProcessError(fmt::format("environment variable '{}' is not set ($({}))", args[0], a));
      replace_all(resolved, whole, v);
    } else if (command == "optenv") {
      if (args.empty()) throw ProcessError(fmt::format("$(optenv var) must specify an environment variable [{}]", a));
      const char* v = std::getenv(args[0].c_str());
      std::string fallback;
      for (size_t i = 1; i < args.size(); ++i) fallback += (i > 1 ? " " : "") + args[i];
      replace_all(resolved, whole, v ? std::string(v) : fallback);
    } else if (command == "dirname") {
      replace_all(resolved, whole, dirname_of(ctx.current_file));
    } else if (command == "anon") {
      if (args.size() != 1) throw ProcessError(fmt::format("$(anon var) must specify exactly one name [{}]", a));
      replace_all(resolved, whole, anon_name(args[0], ctx));
    } else {  // arg, or ROS 2 launch's var
      if (args.empty()) throw ProcessError(fmt::format("$(arg var) must specify a variable name [{}]", a));
      if (args.size() > 1) throw ProcessError(fmt::format("$(arg var) may only specify one arg [{}]", a));
      replace_all(resolved, whole, arg_value(args[0], ctx, command));
    }
  }
  return resolved;
}

}  // namespace

Value convert_auto(const std::string& value) {
  if (value.find('.') != std::string::npos) {
    if (auto d = python_float(value)) return Value::floating(*d);
  } else if (auto i = python_int(value)) {
    return Value::integer(*i);
  }
  std::string lower;
  for (char c : value) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == "true") return Value::boolean(true);
  if (lower == "false") return Value::boolean(false);
  return Value::string(value);
}

std::string resolve_substitution(const std::string& text, SubstitutionContext& ctx) {
  if (text == "cwd" && ctx.dialect == Dialect::Xacro) {
    std::error_code ec;
    return std::filesystem::current_path(ec).string();
  }
  if (text.rfind("eval ", 0) == 0) return eval_command(text.substr(5), ctx);
  const std::string whole = "$(" + text + ")";
  // Everything first, then (xacro) a $(find) an arg's value brought in (xacro 2.0.10's two passes).
  std::string resolved = resolve_pass(whole, ctx, false);
  if (ctx.dialect == Dialect::Xacro && resolved.find("$(") != std::string::npos)
    resolved = resolve_pass(resolved, ctx, true);
  return resolved;
}

}  // namespace lcm_control::xacro
