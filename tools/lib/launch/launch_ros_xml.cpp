// ROS launch XML (the tutorial's gazebo_ros_control.launch and its kind), mapped onto our programs.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tinyxml2.h>
#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <algorithm>
#include <map>

#include "description/robot_model.hpp"
#include "description/substitution.hpp"
#include "description/text.hpp"
#include "tools/lib/launch/launch_file.hpp"

namespace fs = std::filesystem;

namespace lcm_control::tools {

namespace {

using Args = std::vector<std::pair<std::string, std::string>>;

struct RosReader {
  RosReader(std::string file, const std::vector<std::string>& packages, LaunchPlan& out, Args given)
      : path(std::move(file)), package_path(packages), plan(out), passed(std::move(given)) {}
  const std::string path;
  const std::vector<std::string>& package_path;
  LaunchPlan& plan;
  Args args;
  Args passed;                   // NAME:=VALUE from the command line (the top file) or the <include>'s <arg>s
  std::vector<std::string> used;  // the passed names an <arg> took
  std::vector<std::string> files;  // this file and those that included it, innermost last (for cycles)
  std::vector<std::pair<std::string, std::string>> textfile_params;  // name -> file
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> xacro_params;  // name -> its xacro args
  bool gazebo = false, spawn_model = false, unpause = false;
  std::string spawn_param;
  std::vector<std::string> problems;

  std::string where(const tinyxml2::XMLElement* e) const {
    return fmt::format("{}:{}: <{}{}>", path, e->GetLineNum(), e->Name(),
                       e->Attribute("name") ? fmt::format(" name=\"{}\"", e->Attribute("name")) : "");
  }
  std::string attr(const tinyxml2::XMLElement* e, const char* name) {
    const char* v = e->Attribute(name);
    return v ? trim(substitute(v, Substitutions{package_path, args, kLaunchArgFix}, where(e))) : "";
  }
  bool enabled(const tinyxml2::XMLElement* e) {
    for (const char* cond : {"if", "unless"}) {
      if (!e->Attribute(cond)) continue;
      std::string v = attr(e, cond);
      for (char& c : v) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));  // roslaunch: "True" too
      const bool truth = v == "true" || v == "1";
      if (v != "true" && v != "false" && v != "1" && v != "0")
        throw ModelError(fmt::format("{}: {}=\"{}\" must be true/false/1/0", where(e), cond, v));
      if (truth != (std::string(cond) == "if")) return false;
    }
    return true;
  }
  std::string group_ns;  // ns of the enclosing <group>s, if any ("a/b" for nested groups)
  int spawner_nodes = 0;
  int inline_params = 0;

  // --timeout SECONDS and the like once among the spawner's flags: the longest of the spawner nodes'.
  void longest_flag(const std::string& flag, const std::string& value) {
    auto& a = plan.spawner_args;
    for (size_t k = 0; k + 1 < a.size(); ++k)
      if (a[k] == flag) {
        if (std::atof(value.c_str()) > std::atof(a[k + 1].c_str())) a[k + 1] = value;
        return;
      }
    a.push_back(flag);
    a.push_back(value);
  }

  // An inline <rosparam> (its text, with $(arg)s and $(find)s replaced when subst_value="true"), under its ns, as a
  // YAML file of its own beside the others: /tmp/lcm_control-UID/, named after the launch file and line, so that a
  // relaunch rewrites it.
  std::string inline_yaml(const tinyxml2::XMLElement* e) {
    std::string text = e->GetText() ? e->GetText() : "";
    if (attr(e, "subst_value") == "true") text = substitute(text, Substitutions{package_path, args, kLaunchArgFix}, where(e));
    std::vector<std::string> lines;
    size_t indent = std::string::npos;
    for (size_t at = 0; at <= text.size();) {
      const size_t end = std::min(text.find('\n', at), text.size());
      std::string line = text.substr(at, end - at);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const size_t first = line.find_first_not_of(" \t");
      if (first != std::string::npos && line[first] != '#') indent = std::min(indent, first);
      lines.push_back(line);
      at = end + 1;
    }
    if (indent == std::string::npos) return "";
    std::string prefix;
    std::string yaml;
    if (e->Attribute("ns"))
      for (const auto& part : split_ns(attr(e, "ns"))) {
        yaml += prefix + part + ":\n";
        prefix += "  ";
      }
    for (const std::string& line : lines)
      yaml += line.find_first_not_of(" \t") == std::string::npos ? "\n" : prefix + line.substr(std::min(indent, line.size())) + "\n";
    const fs::path dir = fs::temp_directory_path() / fmt::format("lcm_control-{}", getuid());
    std::error_code ec;
    fs::create_directory(dir, ec);
    fs::permissions(dir, fs::perms::owner_all, ec);
    const fs::path file =
        dir / fmt::format("{}-{:x}-line{}.yaml", fs::path(path).stem().string(),
                          std::hash<std::string>{}(fs::weakly_canonical(fs::absolute(path)).string()), e->GetLineNum());
    std::ofstream out(file);
    out << yaml;
    if (!out) throw ModelError(fmt::format("{}: cannot write the inline YAML to {}", where(e), file.string()));
    return file.string();
  }
  static std::vector<std::string> split_ns(const std::string& ns) {
    std::vector<std::string> parts;
    size_t at = 0;
    while (at <= ns.size()) {
      const size_t end = std::min(ns.find('/', at), ns.size());
      if (end > at) parts.push_back(ns.substr(at, end - at));
      at = end + 1;
    }
    return parts;
  }

  // The controllers' namespace: the spawner's ns (inside its group's), as ROS resolves it.
  void set_ns(const tinyxml2::XMLElement* e, const std::string& ns) {
    const std::string full = normalize_namespace(ns.rfind('/', 0) == 0 || group_ns.empty() ? ns : group_ns + "/" + ns);
    if (!plan.ns.empty() && plan.ns != full) {
      problems.push_back(fmt::format("{}: ns \"{}\" differs from the namespace '{}' set before; lcm_control runs one "
                                     "robot namespace per launch",
                                     where(e), ns, plan.ns));
      return;
    }
    if (plan.ns.empty()) plan.notes.push_back(fmt::format("{}: namespace '{}' (as --namespace {})", where(e), full, full));
    plan.ns = full;
  }
  static std::string strip_slash(std::string s) {
    while (!s.empty() && s[0] == '/') s.erase(0, 1);
    return s;
  }

  void node(const tinyxml2::XMLElement* e) {
    const std::string pkg = attr(e, "pkg"), type = attr(e, "type"), name = attr(e, "name");
    const auto words = split_words(attr(e, "args"));
    if (attr(e, "respawn") == "true") plan.notes.push_back(where(e) + ": respawn is not supported; ignored");
    if (pkg == "robot_state_publisher" && (type == "robot_state_publisher" || type == "state_publisher")) {
      plan.state_publisher = true;
      if (!name.empty()) plan.state_publisher_name = name;
      plan.notes.push_back(where(e) + ": robot_state_publisher -> state-publisher (link_poses)");
    } else if (pkg == "gazebo_ros" && type == "spawn_model") {
      spawn_model = true;
      for (size_t k = 0; k < words.size(); ++k) {
        if (words[k] == "-unpause") unpause = true;
        static const std::map<std::string, int> kPose{{"-x", 0}, {"-y", 1}, {"-z", 2}, {"-Y", 3}};
        if (const auto p = kPose.find(words[k]); p != kPose.end() && k + 1 < words.size()) {
          double v = 0;
          if (!parse_double(words[k + 1], v)) {
            problems.push_back(fmt::format("{}: {} {}: the pose must be a number (m or rad)", where(e), words[k],
                                           words[k + 1]));
          } else {
            if (!plan.base_pose) plan.base_pose = std::array<double, 4>{};
            (*plan.base_pose)[p->second] = v;
          }
          ++k;
          continue;
        }
        if ((words[k] == "-R" || words[k] == "-P") && k + 1 < words.size()) {
          double v = 0;
          if (parse_double(words[k + 1], v) && v != 0)
            plan.notes.push_back(fmt::format("{}: spawn_model {} {} ignored: the base starts level (sim_server "
                                             "--base-pose takes x, y, z and yaw)",
                                             where(e), words[k], words[k + 1]));
          ++k;
          continue;
        }
        if (words[k] == "-param" && k + 1 < words.size()) spawn_param = strip_slash(words[k + 1]);
        if (words[k] == "-file" && k + 1 < words.size()) plan.urdf = words[k + 1];
        if (words[k] == "-J" && k + 2 < words.size()) {
          double q = 0;
          if (!parse_double(words[k + 2], q))
            problems.push_back(fmt::format("{}: -J {} {}: the position must be a number (rad or m)", where(e),
                                           words[k + 1], words[k + 2]));
          else
            plan.initial_positions.emplace_back(words[k + 1], q);
          k += 2;
        }
      }
      plan.notes.push_back(where(e) + ": gazebo_ros spawn_model -> sim_server loads the URDF");
    } else if (pkg == "controller_manager" && type == "spawner") {
      if (!name.empty()) plan.spawner_name = name;
      if (e->Attribute("ns")) {
        set_ns(e, attr(e, "ns"));
      } else if (!group_ns.empty()) {
        set_ns(e, "/" + group_ns);  // the <group ns> it is in
      }
      bool stopped = false;
      std::vector<std::string> names;
      for (size_t k = 0; k < words.size(); ++k) {
        const std::string& w = words[k];
        if (w == "--stopped") {
          stopped = true;
        } else if ((w == "--timeout" || w == "--shutdown-timeout") && k + 1 < words.size()) {
          if (std::atof(words[k + 1].c_str()) > 0) longest_flag(w, words[k + 1]);
          ++k;
        } else if (w == "--namespace" || w == "--wait-for") {
          plan.notes.push_back(where(e) + ": spawner " + w + " is not supported; ignored");
          ++k;
        } else if (w.rfind("-", 0) == 0) {
          plan.notes.push_back(where(e) + ": spawner flag " + w + " ignored");
        } else if (w.size() > 5 && w.substr(w.size() - 5) == ".yaml") {
          problems.push_back(where(e) + ": spawner argument " + w +
                             " is a YAML file; name the controllers instead (the config is the <rosparam> file)");
        } else {
          names.push_back(w);
        }
      }
      // Each spawner node's controllers as it asked: started, or (--stopped) loaded and left stopped.
      auto& into = stopped ? plan.inactive : plan.controllers;
      into.insert(into.end(), names.begin(), names.end());
      if (++spawner_nodes > 1 || stopped)
        plan.notes.push_back(fmt::format("{}: {} {}", where(e), stopped ? "loaded, left stopped (--stopped):" : "started:",
                                         names.empty() ? "no controllers" : fmt::format("{}", fmt::join(names, ", "))));
    } else {
      plan.notes.push_back(fmt::format("{}: node {}/{} has no lcm_control equivalent; ignored", where(e), pkg, type));
    }
  }

  // <param command="$(find xacro)/xacro FILE [--inorder] [NAME:=VALUE ...]"/> (also xacro.py, rosrun xacro xacro):
  // the file and its arguments, which our own xacro expands.
  void xacro_command(const tinyxml2::XMLElement* e, const std::string& name) {
    std::string cmd = e->Attribute("command");
    for (const char* program : {"$(find xacro)/xacro.py", "$(find xacro)/xacro", "rosrun xacro xacro.py",
                                "rosrun xacro xacro"}) {
      const std::string p = program;
      if (trim(cmd).rfind(p, 0) == 0) {
        cmd = "xacro" + trim(cmd).substr(p.size());
        break;
      }
    }
    const auto words = split_words(substitute(cmd, Substitutions{package_path, args, kLaunchArgFix}, where(e)));
    const bool is_xacro = !words.empty() && (words[0] == "xacro" || words[0] == "xacro.py");
    std::string file;
    std::vector<std::pair<std::string, std::string>> xacro_args;
    for (size_t k = 1; is_xacro && k < words.size(); ++k) {
      if (words[k] == "--inorder") continue;
      if (words[k].find(":=") != std::string::npos)
        xacro_args.push_back(parse_arg(words[k]));
      else if (file.empty() && words[k].rfind("-", 0) != 0)
        file = words[k];
      else
        return (void)problems.push_back(fmt::format("{}: xacro argument '{}' is not supported (FILE, NAME:=VALUE "
                                                    "and --inorder are)",
                                                    where(e), words[k]));
    }
    if (file.empty())
      return (void)problems.push_back(fmt::format(
          "{}: command=\"{}\" is not a xacro call; give the URDF with textfile= or the xacro with command=\"$(find "
          "xacro)/xacro FILE NAME:=VALUE ...\"",
          where(e), e->Attribute("command")));
    textfile_params.emplace_back(name, file);
    xacro_params[name] = xacro_args;
    plan.notes.push_back(where(e) + ": xacro " + file + " is expanded by lcm_control's own xacro");
  }

  // <include file="..."> followed as roslaunch does: the file's <arg>s take the include's <arg name value> children
  // (and all of this file's with pass_all_args="true"); one it does not declare is an error, as in roslaunch.
  void include(const tinyxml2::XMLElement* e) {
    const std::string file = absolute_from(attr(e, "file"), fs::path(path).parent_path().string());
    if (file.empty()) return (void)problems.push_back(where(e) + ": no file=");
    if (std::find(files.begin(), files.end(), file) != files.end())
      return (void)problems.push_back(fmt::format("{}: {} includes itself (through {})", where(e), file,
                                                  fmt::join(files, " -> ")));
    if (files.size() >= 20)
      return (void)problems.push_back(fmt::format("{}: includes nest deeper than 20 files", where(e)));
    Args given;
    if (attr(e, "pass_all_args") == "true") given = args;
    for (auto* a = e->FirstChildElement("arg"); a; a = a->NextSiblingElement("arg")) {
      if (!enabled(a)) continue;
      const std::string name = attr(a, "name");
      given.erase(std::remove_if(given.begin(), given.end(), [&](const auto& g) { return g.first == name; }), given.end());
      given.emplace_back(name, attr(a, a->Attribute("value") ? "value" : "default"));
    }
    tinyxml2::XMLDocument doc;
    const std::string text = read_launch_text(file);
    if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS)
      return (void)problems.push_back(fmt::format("{}:{}: malformed XML (included from {})", file, doc.ErrorLineNum(),
                                                  where(e)));
    const tinyxml2::XMLElement* root = doc.FirstChildElement("launch");
    if (!root) return (void)problems.push_back(fmt::format("{}: no <launch> element (included from {})", file, where(e)));
    RosReader child(file, package_path, plan, given);
    child.files = files;
    child.files.push_back(file);
    child.group_ns = group_ns;
    const size_t configs_before = plan.configs.size();
    for (auto* c = root->FirstChildElement(); c; c = c->NextSiblingElement()) {
      try {
        child.element(c);
      } catch (const ModelError& err) {
        child.problems.insert(child.problems.end(), err.problems().begin(), err.problems().end());
      }
    }
    // Its relative files are its own folder's.
    const std::string dir = fs::path(file).parent_path().string();
    for (size_t k = configs_before; k < plan.configs.size(); ++k) plan.configs[k] = absolute_from(plan.configs[k], dir);
    for (auto& [name, f] : child.textfile_params) textfile_params.emplace_back(name, absolute_from(f, dir));
    for (auto& x : child.xacro_params) xacro_params[x.first] = x.second;
    if (plan.urdf.size() && fs::path(plan.urdf).is_relative() && child.spawn_model) plan.urdf = absolute_from(plan.urdf, dir);
    gazebo = gazebo || child.gazebo;
    spawn_model = spawn_model || child.spawn_model;
    unpause = unpause || child.unpause;
    if (!child.spawn_param.empty()) spawn_param = child.spawn_param;
    problems.insert(problems.end(), child.problems.begin(), child.problems.end());
    if (attr(e, "pass_all_args") != "true")
      for (const auto& [name, value] : given)
        if (std::find(child.used.begin(), child.used.end(), name) == child.used.end())
          problems.push_back(fmt::format("{}: {}:={} is not an argument of {} (it declares: {})", where(e), name, value,
                                         file, declared(child)));
    plan.notes.push_back(fmt::format("{}: included {}{}", where(e), file,
                                     given.empty() ? "" : fmt::format(" with {} argument(s)", given.size())));
  }
  static std::string declared(const RosReader& r) {
    std::vector<std::string> names;
    for (const auto& a : r.args) names.push_back(a.first);
    return names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "));
  }

  void element(const tinyxml2::XMLElement* e) {
    if (!enabled(e)) return;
    const std::string tag = e->Name();
    if (tag == "arg") {
      const std::string name = attr(e, "name");
      const auto given = std::find_if(passed.begin(), passed.end(), [&](const auto& a) { return a.first == name; });
      if (given != passed.end()) used.push_back(name);
      if (e->Attribute("value")) {
        if (given != passed.end())
          problems.push_back(fmt::format("{}: {}:={} cannot be passed: value=\"{}\" fixes this argument (roslaunch "
                                         "takes only those with default=)",
                                         where(e), name, given->second, attr(e, "value")));
        args.emplace_back(name, attr(e, "value"));
      } else if (given != passed.end()) {
        args.emplace_back(name, given->second);
      } else if (e->Attribute("default")) {
        args.emplace_back(name, attr(e, "default"));
      }
    } else if (tag == "param") {
      const std::string name = strip_slash(attr(e, "name"));
      if (e->Attribute("textfile")) {
        textfile_params.emplace_back(name, attr(e, "textfile"));
      } else if (e->Attribute("command")) {
        xacro_command(e, name);
      } else {
        plan.notes.push_back(where(e) + ": a plain parameter; ignored (controllers read the <rosparam> YAML)");
      }
    } else if (tag == "rosparam") {
      const std::string cmd = attr(e, "command");
      if (cmd != "load" && !cmd.empty()) {
        plan.notes.push_back(where(e) + ": rosparam command=\"" + cmd + "\" ignored");
        return;
      }
      if (!e->Attribute("file")) {
        const std::string file = inline_yaml(e);
        if (file.empty()) {
          plan.notes.push_back(where(e) + ": an empty <rosparam>; ignored");
          return;
        }
        plan.configs.push_back(file);
        plan.notes.push_back(fmt::format("{}: inline YAML{}{} -> {}", where(e),
                                         e->Attribute("ns") ? " under " + attr(e, "ns") : "",
                                         attr(e, "subst_value") == "true" ? " (substituted)" : "", file));
        ++inline_params;
        return;
      }
      if (e->Attribute("ns")) plan.notes.push_back(where(e) + ": ns=\"" + attr(e, "ns") + "\" ignored");
      plan.configs.push_back(attr(e, "file"));
    } else if (tag == "node") {
      node(e);
    } else if (tag == "include") {
      const char* raw = e->Attribute("file");
      const std::string file = raw ? raw : "";
      if (file.find("gazebo_ros") != std::string::npos && file.find("world") != std::string::npos) {
        gazebo = true;
        for (auto* a = e->FirstChildElement("arg"); a; a = a->NextSiblingElement("arg")) {
          const std::string n = attr(a, "name"), v = attr(a, "value");
          if (n == "paused" && v == "true") {
            plan.paused = true;
            plan.notes.push_back(where(a) + ": paused=true -> sim_server --paused (cmctl resume runs it), unless "
                                 "spawn_model has -unpause");
          }
        }
        plan.notes.push_back(where(e) + ": gazebo_ros world -> sim_server + controller_manager");
      } else {
        include(e);
      }
    } else if (tag == "group") {
      const std::string outer = group_ns;
      if (e->Attribute("ns")) {  // nested groups compose; a leading '/' starts from the root
        const std::string ns = attr(e, "ns");
        group_ns = ns.rfind('/', 0) == 0 || outer.empty() ? ns : outer + "/" + ns;
        while (!group_ns.empty() && group_ns.front() == '/') group_ns.erase(0, 1);
      }
      for (auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) element(c);
      group_ns = outer;
    } else if (tag == "remap" || tag == "machine" || tag == "env" || tag == "test") {
      plan.notes.push_back(where(e) + ": ignored");
    } else {
      problems.push_back(where(e) + ": unknown launch tag");
    }
  }
};

}  // namespace

LaunchPlan read_ros_launch(const std::string& path, const std::vector<std::string>& package_path,
                           const std::vector<std::pair<std::string, std::string>>& args) {
  std::string text = read_launch_text(path);
  LaunchPlan plan;
  plan.file = path;
  // Copied from a web page, the tutorial's file carries stray "</pre>" inside tags.
  size_t stray = 0;
  for (size_t p; (p = text.find("</pre>")) != std::string::npos; ++stray) text.erase(p, 6);
  if (stray) plan.notes.push_back(fmt::format("{}: removed {} stray '</pre>' (copied from a web page)", path, stray));
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS)
    throw ModelError(fmt::format("{}:{}: malformed XML: {}", path, doc.ErrorLineNum(),
                                 doc.ErrorStr() ? trim(doc.ErrorStr()) : "parse error"));
  const tinyxml2::XMLElement* root = doc.FirstChildElement("launch");
  if (!root) throw ModelError(fmt::format("{}: no <launch> element; is this a ROS launch file?", path));
  RosReader r(path, package_path, plan, args);
  r.files.push_back(fs::weakly_canonical(fs::absolute(path)).string());
  for (auto* e = root->FirstChildElement(); e; e = e->NextSiblingElement()) {
    try {
      r.element(e);
    } catch (const ModelError& err) {
      r.problems.insert(r.problems.end(), err.problems().begin(), err.problems().end());
    }
  }
  const bool earlier = !r.problems.empty();
  if (plan.urdf.empty()) {
    const std::string want = r.spawn_param.empty() ? "robot_description" : r.spawn_param;
    for (const auto& [name, file] : r.textfile_params)
      if (name == want) {
        plan.urdf = file;
        const auto x = r.xacro_params.find(name);
        plan.xacro_args = x == r.xacro_params.end() ? decltype(plan.xacro_args){} : x->second;
      }
    if (plan.urdf.empty() && !earlier)
      r.problems.push_back(fmt::format("{}: no URDF: expected <param name=\"{}\" textfile=\"...\"/> or command=\"$(find xacro)/xacro ...\"", path, want));
  }
  if (plan.configs.empty() && !earlier)
    r.problems.push_back(fmt::format("{}: no ros_control YAML: expected <rosparam command=\"load\" file=\"...\"/>", path));
  plan.sim = plan.controller_manager = r.gazebo || r.spawn_model;
  if (!plan.sim)
    r.problems.push_back(fmt::format(
        "{}: nothing to simulate: no <include> of gazebo_ros's world launch file and no spawn_model node", path));
  plan.args = r.args;
  for (const auto& [name, value] : args)  // not declared: still given to the controllers' YAML ($(arg NAME))
    if (std::find(r.used.begin(), r.used.end(), name) == r.used.end()) {
      plan.notes.push_back(fmt::format("{}: {}:={}: the file declares no <arg name=\"{}\">; passed to the "
                                       "controllers' YAML only",
                                       path, name, value, name));
      plan.args.emplace_back(name, value);
    }
  if (plan.paused && r.unpause) {
    plan.paused = false;  // as in Gazebo: spawn_model -unpause starts physics once the model is in
    plan.notes.push_back(path + ": paused=true with spawn_model -unpause: sim_server runs from the start");
  }
  if (!r.problems.empty()) throw ModelError(r.problems);
  const std::string dir = fs::absolute(path).parent_path().string();
  plan.urdf = absolute_from(plan.urdf, dir);
  for (auto& c : plan.configs) c = absolute_from(c, dir);
  return plan;
}

}  // namespace lcm_control::tools
