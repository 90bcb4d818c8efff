// Launch files read into plans: our YAML, the tutorial's ROS launch XML (as a
// user writes it, and as copied with the web page's stray </pre>), and errors.
#include "tools/lib/launch/launch_file.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <filesystem>
#include <fstream>

#include "description/robot_model.hpp"
#include "test/support/process.hpp"
#include "test/tools/tool_test_util.hpp"

using namespace lcm_control;
using namespace lcm_control::tools;
namespace lt = lcm_control::testing;

namespace {
const std::vector<std::string> kControllers{"joint_state_controller", "j1_controller", "j2_controller"};

std::string write(const std::string& dir, const std::string& name, const std::string& text) {
  std::ofstream(dir + "/" + name) << text;
  return dir + "/" + name;
}

std::string problems_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ModelError& e) {
    std::string s;
    for (const auto& p : e.problems()) s += p + "\n";
    return s;
  }
  return "";
}
}  // namespace

TEST(LaunchFile, TurretBotYaml) {
  const LaunchPlan plan = read_launch_file(lt::source("config/turret_bot.launch.yaml"), {});
  EXPECT_EQ(plan.urdf, lt::source("config/turret_bot.urdf"));
  EXPECT_EQ(plan.configs, std::vector<std::string>{lt::source("config/turret_bot.yaml")});
  EXPECT_EQ(plan.mode, "realtime");
  EXPECT_EQ(plan.physics_rate, 1000);
  EXPECT_EQ(plan.controllers, kControllers);
  EXPECT_TRUE(plan.state_publisher);
  EXPECT_TRUE(plan.sim);
  EXPECT_TRUE(plan.controller_manager);
  EXPECT_EQ(plan.cpu, "auto");
}

TEST(LaunchFile, TutorialRosLaunchWithThePackagePath) {
  const std::string pkg = lt::source("test/tools/data/turret_bot");
  const LaunchPlan plan = read_launch_file(pkg + "/launch/gazebo_ros_control.launch", {lt::source("test/tools/data")});
  EXPECT_EQ(plan.urdf, pkg + "/urdf/turret_bot.urdf");
  EXPECT_EQ(plan.configs, std::vector<std::string>{pkg + "/config/config.yaml"});
  EXPECT_EQ(plan.controllers, kControllers);
  EXPECT_TRUE(plan.state_publisher);
  EXPECT_EQ(plan.state_publisher_name, "robot_state_publisher");
  EXPECT_EQ(plan.spawner_name, "controller_spawner");
  EXPECT_TRUE(plan.sim);
  EXPECT_EQ(plan.mode, "realtime");
  // The package's copies are the robot in config/.
  EXPECT_EQ(lt::read_text(pkg + "/urdf/turret_bot.urdf"), lt::read_text(lt::source("config/turret_bot.urdf")));
  EXPECT_EQ(lt::read_text(pkg + "/config/config.yaml"), lt::read_text(lt::source("config/turret_bot.yaml")));
}

// Section 3.3 of the tutorial, character for character, </pre> artefacts included.
TEST(LaunchFile, TutorialTextAsPrintedWithStrayPre) {
  const std::string dir = lt::temp_dir("launch_pre");
  const std::string file = write(dir, "gazebo_ros_control.launch", R"L(<?xml version="1.0"?>
<launch>
    <param name = "/robot_description"</pre>
           textfile="$(find turret_bot)/urdf/turret_bot.urdf"/>
    <rosparam command="load"</pre>
              file="$(find turret_bot)/config/config.yaml"/>
    <node name="robot_state_publisher"</pre>
          pkg="robot_state_publisher"
          type="robot_state_publisher"/>
    <include file = "$(find gazebo_ros)/launch/empty_world.launch"/>
    <node name="urdf_spawner" pkg="gazebo_ros" type="spawn_model"</pre>
        args=" -unpause -urdf -model turret_bot
            -param robot_description " respawn="false"/>
    <node name="controller_spawner"</pre>
          pkg = "controller_manager"
          type = "spawner" respawn = "false"
          args = "joint_state_controller j1_controller j2_controller" />
</launch>
)L");
  const LaunchPlan plan = read_launch_file(file, {lt::source("test/tools/data")});
  EXPECT_EQ(plan.controllers, kControllers);
  EXPECT_EQ(plan.urdf, lt::source("test/tools/data/turret_bot/urdf/turret_bot.urdf"));
  bool noted = false;
  for (const auto& n : plan.notes) noted = noted || n.find("removed 5 stray '</pre>'") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(LaunchFile, ArgsConditionsAndSpawnerFlags) {
  const std::string dir = lt::temp_dir("launch_args");
  const std::string file = write(dir, "x.launch", R"L(<launch>
  <arg name="controllers" default="j1_controller j2_controller"/>
  <arg name="rsp" default="false"/>
  <param name="robot_description" textfile="$(find turret_bot)/urdf/turret_bot.urdf"/>
  <rosparam command="load" file="$(find turret_bot)/config/config.yaml"/>
  <node name="rsp" pkg="robot_state_publisher" type="robot_state_publisher" if="$(arg rsp)"/>
  <node name="jsp" pkg="joint_state_publisher" type="joint_state_publisher"/>
  <node name="urdf_spawner" pkg="gazebo_ros" type="spawn_model" args="-urdf -param robot_description -model x"/>
  <node name="sp" pkg="controller_manager" type="spawner" args="--stopped --timeout 5 $(arg controllers)"/>
</launch>)L");
  const LaunchPlan plan = read_launch_file(file, {lt::source("test/tools/data")});
  EXPECT_TRUE(plan.controllers.empty());  // --stopped: loaded and left stopped, as ROS 1's spawner
  EXPECT_EQ(plan.inactive, (std::vector<std::string>{"j1_controller", "j2_controller"}));
  EXPECT_EQ(plan.spawner_args, (std::vector<std::string>{"--timeout", "5"}));
  EXPECT_FALSE(plan.state_publisher);
  bool ignored = false;
  for (const auto& n : plan.notes) ignored = ignored || n.find("joint_state_publisher/joint_state_publisher has no") != std::string::npos;
  EXPECT_TRUE(ignored);
}

TEST(LaunchFile, ErrorsNameTheFileLineAndKey) {
  const std::string dir = lt::temp_dir("launch_bad");
  std::string p = problems_of([&] {
    read_launch_file(write(dir, "a.yaml", "urdf: x.urdf\nconfig: y.yaml\ncontroler: [a]\n"), {});
  });
  EXPECT_NE(p.find("a.yaml:3: 'controler': unknown key"), std::string::npos) << p;

  p = problems_of([&] { read_launch_file(write(dir, "b.yaml", "urdf: missing.urdf\nconfig: y.yaml\n"), {}); });
  EXPECT_NE(p.find("the URDF " + dir + "/missing.urdf does not exist"), std::string::npos) << p;

  p = problems_of([&] {
    read_launch_file(lt::source("test/tools/data/turret_bot/launch/gazebo_ros_control.launch"), {dir});
  });
  EXPECT_NE(p.find(":3: <param name=\"/robot_description\">: $(find turret_bot): package 'turret_bot' is not on the "
                   "package path"),
            std::string::npos)
      << p;

  p = problems_of([&] { read_launch_file(write(dir, "c.launch", "<launch><param name='x'</launch>"), {}); });
  EXPECT_NE(p.find("c.launch:1: malformed XML"), std::string::npos) << p;

  p = problems_of([&] { read_launch_file(write(dir, "d.yaml", "urdf: x\nmode: fast\n"), {}); });
  EXPECT_NE(p.find("'mode' must be realtime or lockstep, not 'fast'"), std::string::npos) << p;

  p = problems_of([&] { read_launch_file(write(dir, "e.yaml", "urdf: x\ncpu: fastest\n"), {}); });
  EXPECT_NE(p.find("e.yaml:2: 'cpu' must be auto (lockstep: sim_server and controller_manager on the least busy CPU), "
                   "none, or a CPU number, not 'fastest'"),
            std::string::npos)
      << p;
}

TEST(LaunchFile, DemoCommandsBecomeCommandSources) {
  const LaunchPlan plan = read_launch_file(lt::source("config/turret_bot_demo.launch.yaml"), {});
  EXPECT_EQ(plan.mode, "lockstep");
  EXPECT_EQ(plan.controllers, kControllers);
  ASSERT_EQ(plan.commands.size(), 2u);
  EXPECT_EQ(plan.commands[0].target, "j1_controller");
  EXPECT_EQ(plan.commands[0].expr, std::vector<std::string>{"0.5"});
  EXPECT_EQ(plan.commands[0].count, 1);
  EXPECT_EQ(plan.commands[0].rate, 0);
  EXPECT_EQ(plan.commands[1].target, "j2_controller");
  EXPECT_EQ(plan.commands[1].expr, std::vector<std::string>{"3.14*sin(i/100)"});
  EXPECT_EQ(plan.commands[1].rate, 60);
  EXPECT_EQ(plan.commands[1].count, 0);

  const std::string dir = lt::temp_dir("launch_commands");
  const std::string head = "urdf: " + lt::source("config/turret_bot.urdf") + "\nconfig: " +
                           lt::source("config/turret_bot.yaml") + "\ncontrollers: [j2_controller]\n";
  std::string p = problems_of([&] {
    read_launch_file(write(dir, "a.yaml", head + "commands: [{target: j1_controller, expr: 1, rat: 5}]\n"), {});
  });
  EXPECT_NE(p.find("'commands.rat': unknown key; valid: target, expr, rate, count, duration"), std::string::npos) << p;
  EXPECT_NE(p.find("commands: target 'j1_controller' is not one of the spawned controllers (j2_controller)"),
            std::string::npos)
      << p;
  p = problems_of([&] {
    read_launch_file(write(dir, "b.yaml", head + "commands: [{target: j2_controller, count: 1.5, expr: x}]\n"), {});
  });
  EXPECT_NE(p.find("'commands.count' must be a whole number"), std::string::npos) << p;
}

TEST(LaunchFile, YamlNamespaceArgsAndInitialPositions) {
  const std::string dir = lt::temp_dir("launch_robot_keys");
  const std::string file = write(dir, "arm.launch.yaml", "urdf: " + lt::source("config/turret_bot.urdf") +
                                                             "\nconfig: " + lt::source("config/turret_bot.yaml") +
                                                             "\nnamespace: /arm/\n"
                                                             "args: {arm_id: panda, hand: 'false'}\n"
                                                             "initial_positions: {j1: 0.25, j2: -1.5}\n");
  const LaunchPlan plan = read_launch_file(file, {});
  EXPECT_EQ(plan.ns, "arm");
  EXPECT_EQ(plan.args, (std::vector<std::pair<std::string, std::string>>{{"arm_id", "panda"}, {"hand", "false"}}));
  EXPECT_EQ(plan.initial_positions, (std::vector<std::pair<std::string, double>>{{"j1", 0.25}, {"j2", -1.5}}));

  const std::string p = problems_of([&] {
    read_launch_file(write(dir, "bad.yaml", "urdf: x\nconfig: y\ninitial_positions: {j1: up}\nargs: [a]\n"), {});
  });
  EXPECT_NE(p.find("bad.yaml:3: 'initial_positions.j1' must be a number"), std::string::npos) << p;
  EXPECT_NE(p.find("bad.yaml:4: 'args' must be a map NAME: VALUE"), std::string::npos) << p;
}

TEST(LaunchFile, RobotsAsACountOrNamespacesAndTheHardwareUrl) {
  const std::string dir = lt::temp_dir("launch_robots");
  const std::string head = "urdf: " + lt::source("config/turret_bot.urdf") + "\nconfig: " +
                           lt::source("config/turret_bot.yaml") + "\n";
  const LaunchPlan three = read_launch_file(write(dir, "three.yaml", head + "robots: 3\n"), {});
  EXPECT_EQ(three.robots, (std::vector<std::string>{"r0", "r1", "r2"}));
  EXPECT_EQ(three.hardware_lcm_url, "");
  const LaunchPlan named =
      read_launch_file(write(dir, "named.yaml", head + "robots: [/left/, right]\nhardware_lcm_url: auto\n"), {});
  EXPECT_EQ(named.robots, (std::vector<std::string>{"left", "right"}));
  EXPECT_EQ(named.hardware_lcm_url, "auto");
  EXPECT_TRUE(read_launch_file(lt::source("config/turret_bot.launch.yaml"), {}).robots.empty());

  std::string p = problems_of([&] { read_launch_file(write(dir, "zero.yaml", head + "robots: 0\n"), {}); });
  EXPECT_NE(p.find("zero.yaml:3: 'robots' must be a whole number of robots from 1 to 64"), std::string::npos) << p;
  p = problems_of([&] { read_launch_file(write(dir, "twice.yaml", head + "robots: [a, b, a]\n"), {}); });
  EXPECT_NE(p.find("namespace 'a' is empty or given twice"), std::string::npos) << p;
}

TEST(LaunchFile, RealTimeProfileSpinsOnlyWithAPriorityUnlessToldAndOutOfRangeIsRefused) {
  const std::string dir = lt::temp_dir("launch_rt");
  const std::string head = "urdf: " + lt::source("config/turret_bot.urdf") + "\nconfig: " +
                           lt::source("config/turret_bot.yaml") + "\n";
  const LaunchPlan plain = read_launch_file(lt::source("config/turret_bot.launch.yaml"), {});
  EXPECT_EQ(plain.rt_priority, 0);
  EXPECT_EQ(effective_spin_us(plain), 0);
  const LaunchPlan fifo = read_launch_file(write(dir, "fifo.yaml", head + "rt_priority: 80\n"), {});
  EXPECT_EQ(fifo.rt_priority, 80);
  EXPECT_EQ(effective_spin_us(fifo), kRealTimeSpinUs);
  const LaunchPlan still = read_launch_file(write(dir, "still.yaml", head + "rt_priority: 80\nspin_us: 0\n"), {});
  EXPECT_EQ(effective_spin_us(still), 0);
  EXPECT_EQ(read_launch_file(write(dir, "auto.yaml", head + "rt_priority: 5\nspin_us: auto\n"), {}).spin_us, -1);
  const LaunchPlan spin = read_launch_file(write(dir, "spin.yaml", head + "spin_us: 40\n"), {});
  EXPECT_EQ(spin.rt_priority, 0);
  EXPECT_EQ(effective_spin_us(spin), 40);

  std::string p = problems_of([&] { read_launch_file(write(dir, "hi.yaml", head + "rt_priority: 100\n"), {}); });
  EXPECT_NE(p.find("hi.yaml:3: 'rt_priority' must be a whole number from 0 to 99 (0: the normal scheduler; 1-99: "
                   "SCHED_FIFO)"),
            std::string::npos)
      << p;
  p = problems_of([&] { read_launch_file(write(dir, "half.yaml", head + "spin_us: 12.5\n"), {}); });
  EXPECT_NE(p.find("half.yaml:3: 'spin_us' must be a whole number from 0 to 100000 (microseconds), or auto"),
            std::string::npos)
      << p;
  p = problems_of([&] { read_launch_file(write(dir, "word.yaml", head + "spin_us: lots\n"), {}); });
  EXPECT_NE(p.find("word.yaml:3: 'spin_us' must be a number"), std::string::npos) << p;
}

TEST(LaunchFile, PausedFromYamlAndFromGazebosPausedArgUnlessSpawnModelUnpauses) {
  const std::string dir = lt::temp_dir("launch_paused");
  const std::string files = "urdf: " + lt::source("config/turret_bot.urdf") + "\nconfig: " +
                            lt::source("config/turret_bot.yaml") + "\n";
  EXPECT_TRUE(read_launch_file(write(dir, "p.launch.yaml", files + "paused: true\n"), {}).paused);
  EXPECT_FALSE(read_launch_file(write(dir, "r.launch.yaml", files), {}).paused);
  auto xml = [&](const std::string& spawn_args) {
    return write(dir, "x.launch", R"L(<launch>
  <param name="robot_description" textfile=")L" + lt::source("config/turret_bot.urdf") + R"L("/>
  <rosparam command="load" file=")L" + lt::source("config/turret_bot.yaml") + R"L("/>
  <include file="$(find gazebo_ros)/launch/empty_world.launch"><arg name="paused" value="true"/></include>
  <node name="urdf_spawner" pkg="gazebo_ros" type="spawn_model" args=")L" + spawn_args + R"L("/>
</launch>
)L");
  };
  EXPECT_TRUE(read_launch_file(xml("-urdf -model turret_bot -param robot_description"), {}).paused);
  const LaunchPlan unpaused = read_launch_file(xml("-unpause -urdf -model turret_bot -param robot_description"), {});
  EXPECT_FALSE(unpaused.paused);
  bool noted = false;
  for (const auto& n : unpaused.notes) noted = noted || n.find("spawn_model -unpause") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(LaunchFile, RosSpawnerNamespaceArgsAndSpawnModelJ) {
  const std::string dir = lt::temp_dir("launch_ros_ns");
  const std::string file = write(dir, "x.launch", R"L(<launch>
  <arg name="arm_id" default="panda"/>
  <param name="robot_description" textfile="$(find turret_bot)/urdf/turret_bot.urdf"/>
  <rosparam command="load" file="$(find turret_bot)/config/config.yaml" subst_value="true"/>
  <node name="urdf_spawner" pkg="gazebo_ros" type="spawn_model"
        args="-urdf -param robot_description -model x -J j1 0.5 -x 1.5 -J j2 -0.25 -z 0.1 -Y -0.3 -R 0.2"/>
  <group ns="/lab">
    <node name="sp" pkg="controller_manager" type="spawner" ns="rrbot" args="j1_controller"/>
  </group>
</launch>)L");
  const LaunchPlan plan = read_launch_file(file, {lt::source("test/tools/data")});
  EXPECT_EQ(plan.ns, "lab/rrbot");
  EXPECT_EQ(plan.initial_positions, (std::vector<std::pair<std::string, double>>{{"j1", 0.5}, {"j2", -0.25}}));
  EXPECT_EQ(plan.args, (std::vector<std::pair<std::string, std::string>>{{"arm_id", "panda"}}));
  // spawn_model's pose (-x -y -z -Y; -y defaults to 0) for sim_server --base-pose; roll and pitch are named.
  ASSERT_TRUE(plan.base_pose.has_value());
  EXPECT_EQ(*plan.base_pose, (std::array<double, 4>{1.5, 0, 0.1, -0.3}));
  bool roll_named = false;
  for (const auto& n : plan.notes) roll_named = roll_named || n.find("spawn_model -R 0.2 ignored") != std::string::npos;
  EXPECT_TRUE(roll_named);

  const std::string p = problems_of([&] {
    read_launch_file(write(dir, "y.launch", R"L(<launch>
  <param name="robot_description" textfile="$(find turret_bot)/urdf/turret_bot.urdf"/>
  <rosparam command="load" file="$(find turret_bot)/config/config.yaml"/>
  <node name="s" pkg="gazebo_ros" type="spawn_model" args="-param robot_description -J j1 high -z low"/>
</launch>)L"),
                     {lt::source("test/tools/data")});
  });
  EXPECT_NE(p.find("y.launch:4: <node name=\"s\">: -J j1 high: the position must be a number"), std::string::npos) << p;
  EXPECT_NE(p.find("y.launch:4: <node name=\"s\">: -z low: the pose must be a number"), std::string::npos) << p;
}

// robot_description from xacro, as ROS launch files load it: the file and its arguments go to our own xacro;
// --inorder is accepted; anything else on xacro's command line is named.
TEST(LaunchFile, XacroCommandOfRobotDescriptionAndXacroArgsKey) {
  const std::string dir = lt::temp_dir("launch_xacro");
  const std::string body = R"L(
  <rosparam command="load" file="$(find turret_bot)/config/config.yaml"/>
  <node name="urdf_spawner" pkg="gazebo_ros" type="spawn_model" args="-urdf -param robot_description -model x"/>
</launch>)L";
  const std::string xacro = lt::source("config/turret_bot_description/urdf/turret_bot.urdf.xacro");
  const std::string file = write(dir, "x.launch",
                                 "<launch>\n  <arg name=\"iface\" default=\"Effort\"/>\n  <param name=\"robot_description\" "
                                 "command=\"$(find xacro)/xacro --inorder " +
                                     xacro + " interface:=$(arg iface) extra:=1\"/>" + body);
  const LaunchPlan plan = read_launch_file(file, {lt::source("test/tools/data")});
  EXPECT_EQ(plan.urdf, xacro);
  EXPECT_EQ(plan.xacro_args, (std::vector<std::pair<std::string, std::string>>{{"interface", "Effort"}, {"extra", "1"}}));

  const std::string rosrun = write(dir, "r.launch",
                                   "<launch>\n  <param name=\"robot_description\" command=\"rosrun xacro xacro " + xacro +
                                       " -o out.urdf\"/>" + body);
  EXPECT_NE(problems_of([&] { read_launch_file(rosrun, {lt::source("test/tools/data")}); })
                .find("xacro argument '-o' is not supported (FILE, NAME:=VALUE and --inorder are)"),
            std::string::npos);
  const std::string other = write(dir, "o.launch",
                                  "<launch>\n  <param name=\"robot_description\" command=\"cat robot.urdf\"/>" + body);
  EXPECT_NE(problems_of([&] { read_launch_file(other, {lt::source("test/tools/data")}); }).find("is not a xacro call"),
            std::string::npos);

  const std::string yaml = write(dir, "x.launch.yaml",
                                 "urdf: " + xacro + "\nconfig: " + lt::source("config/turret_bot.yaml") +
                                     "\nxacro_args: {interface: Velocity, prefix: ''}\n");
  const LaunchPlan y = read_launch_file(yaml, {});
  EXPECT_EQ(y.xacro_args, (std::vector<std::pair<std::string, std::string>>{{"interface", "Velocity"}, {"prefix", ""}}));
  const std::string empty = write(dir, "e.launch.yaml", "urdf: " + xacro + "\nconfig: " +
                                                         lt::source("config/turret_bot.yaml") + "\nxacro_args:\n");
  EXPECT_TRUE(read_launch_file(empty, {}).xacro_args.empty());
  const std::string bad = write(dir, "bad.launch.yaml", "urdf: " + xacro + "\nxacro_args: [interface]\n");
  EXPECT_NE(problems_of([&] { read_launch_file(bad, {}); }).find("'xacro_args' must be a map NAME: VALUE"),
            std::string::npos);
}

TEST(LaunchFile, SpawnAndInactiveNameWhatStartsAndWhatIsOnlyLoaded) {
  const std::string dir = lt::temp_dir("launch_spawn");
  const std::string head = "urdf: " + lt::source("config/turret_bot.urdf") + "\nconfig: " +
                           lt::source("config/turret_bot.yaml") + "\n";
  const LaunchPlan plan = read_launch_file(
      write(dir, "a.yaml", head + "spawn: [joint_state_controller, j1_controller]\ninactive: [j2_controller]\n"), {});
  EXPECT_EQ(plan.controllers, (std::vector<std::string>{"joint_state_controller", "j1_controller"}));
  EXPECT_EQ(plan.inactive, std::vector<std::string>{"j2_controller"});
  const std::string p = problems_of([&] {
    read_launch_file(write(dir, "b.yaml", head + "controllers: [j1_controller]\nspawn: [j2_controller]\n"), {});
  });
  EXPECT_NE(p.find("give controllers or spawn (the same list), not both"), std::string::npos) << p;
}

// A ROS launch file with two <rosparam> files and the args people compute with $(optenv) and $(eval).
TEST(LaunchFile, TwoRosparamFilesOptenvAndEvalAsRoslaunchReadsThem) {
  const std::string robots = lt::source("test/robots");
  unsetenv("LCM_CONTROL_TEST_ROBOT");
  unsetenv("LCM_CONTROL_TEST_START");
  LaunchPlan plan = read_launch_file(robots + "/industrial_arm.launch", {lt::source("test")});
  EXPECT_EQ(plan.urdf, robots + "/industrial_arm.urdf");
  EXPECT_EQ(plan.configs,
            (std::vector<std::string>{robots + "/industrial_arm.yaml", robots + "/industrial_arm_overrides.yaml"}));
  EXPECT_EQ(plan.controllers, (std::vector<std::string>{"joint_state_controller", "arm_controller"}));

  // $(optenv VAR default) takes the variable when it is set; eval's optenv() too.
  setenv("LCM_CONTROL_TEST_ROBOT", "no_such_robot", 1);
  setenv("LCM_CONTROL_TEST_START", "no", 1);
  plan = read_ros_launch(robots + "/industrial_arm.launch", {lt::source("test")});  // the files are not checked
  unsetenv("LCM_CONTROL_TEST_ROBOT");
  unsetenv("LCM_CONTROL_TEST_START");
  EXPECT_EQ(plan.urdf, robots + "/no_such_robot.urdf");
  EXPECT_EQ(plan.configs.back(), robots + "/no_such_robot_overrides.yaml");
  EXPECT_TRUE(plan.controllers.empty());
}

TEST(LaunchFile, YamlConfigTakesAListOfFilesInOrder) {
  const std::string dir = lt::temp_dir("launch_configs");
  const LaunchPlan plan = read_launch_yaml(
      write(dir, "two.launch.yaml", "urdf: arm.urdf\nconfig: [arm.yaml, " + dir + "/gripper.yaml]\n"), {});
  EXPECT_EQ(plan.configs, (std::vector<std::string>{dir + "/arm.yaml", dir + "/gripper.yaml"}));
}

TEST(LaunchFile, AnEvalErrorShowsTheWholeExpression) {
  const std::string dir = lt::temp_dir("launch_eval");
  const std::string p = problems_of([&] {
    read_launch_file(write(dir, "eval.launch", R"L(<launch>
  <arg name="scale" default="2"/>
  <arg name="size" value="$(eval max(1, min(arg('scale') * (3 + no_such_arg), 10)))"/>
</launch>)L"),
                     {});
  });
  EXPECT_NE(p.find("eval.launch:3: <arg name=\"size\">: $(eval max(1, min(arg('scale') * (3 + no_such_arg), 10))): "),
            std::string::npos)
      << p;
  EXPECT_NE(p.find("no_such_arg"), std::string::npos) << p;
}

// Issue 48: a robot's launch file included by another, as catkin packages split them: <include> followed with its
// <arg>s (and pass_all_args), relative files from the included file's own folder, and NAME:=VALUE from the command
// line overriding a default; each mistake named with the file and line.
// A package's own launch file as ROS 1 packages write them: the robot in a <group ns>, its controllers' YAML inline
// (one with subst_value, one under an ns), and two spawner nodes, the second --stopped: each node's controllers as
// it asked, the group's namespace for the robot.
TEST(LaunchFile, EachSpawnerNodeInlineRosparamAndTheGroupsNamespace) {
  const std::string dir = lt::temp_dir("launch_groups");
  const std::string file = write(dir, "robot.launch", R"L(<launch>
  <arg name="rate" default="50"/>
  <include file="$(find gazebo_ros)/launch/empty_world.launch"/>
  <group ns="robot1">
    <param name="robot_description" textfile="$(find turret_bot)/urdf/turret_bot.urdf"/>
    <rosparam subst_value="true">
      joint_state_controller:
        type: joint_state_controller/JointStateController
        publish_rate: $(arg rate)   # from the launch file's arg
    </rosparam>
    <rosparam ns="j1_controller">
type: effort_controllers/JointPositionController
joint: j1
pid: {p: 100, d: $(arg rate)}
    </rosparam>
    <node name="spawn" pkg="gazebo_ros" type="spawn_model" args="-urdf -param robot_description -model x"/>
    <node name="running" pkg="controller_manager" type="spawner" args="joint_state_controller j1_controller --timeout 5"/>
    <node name="idle" pkg="controller_manager" type="spawner" args="--stopped j2_controller --timeout 9"/>
  </group>
</launch>)L");
  const LaunchPlan plan = read_launch_file(file, {lt::source("test/tools/data")}, {{"rate", "125"}});
  EXPECT_EQ(plan.ns, "robot1");
  EXPECT_EQ(plan.controllers, (std::vector<std::string>{"joint_state_controller", "j1_controller"}));
  EXPECT_EQ(plan.inactive, (std::vector<std::string>{"j2_controller"}));
  EXPECT_EQ(plan.spawner_args, (std::vector<std::string>{"--timeout", "9"}));
  ASSERT_EQ(plan.configs.size(), 2u);
  const YAML::Node first = YAML::LoadFile(plan.configs[0]), second = YAML::LoadFile(plan.configs[1]);
  EXPECT_EQ(first["joint_state_controller"]["publish_rate"].as<int>(), 125);
  EXPECT_EQ(second["j1_controller"]["joint"].as<std::string>(), "j1");
  EXPECT_EQ(second["j1_controller"]["pid"]["d"].as<std::string>(), "$(arg rate)") << "no subst_value: as written";
  std::string notes;
  for (const auto& n : plan.notes) notes += n + "\n";
  EXPECT_NE(notes.find("robot.launch:18: <node name=\"idle\">: loaded, left stopped (--stopped): j2_controller"),
            std::string::npos)
      << notes;
  EXPECT_NE(notes.find("robot.launch:11: <rosparam>: inline YAML under j1_controller -> "), std::string::npos) << notes;

  // Nested groups compose; a spawner's own ns goes inside them.
  const LaunchPlan nested = read_launch_file(write(dir, "nested.launch", R"L(<launch>
  <param name="robot_description" textfile="$(find turret_bot)/urdf/turret_bot.urdf"/>
  <rosparam command="load" file="$(find turret_bot)/config/config.yaml"/>
  <node name="spawn" pkg="gazebo_ros" type="spawn_model" args="-urdf -param robot_description -model x"/>
  <group ns="lab"><group ns="cell2"><node name="sp" pkg="controller_manager" type="spawner" args="j1_controller"/></group></group>
</launch>)L"),
                                             {lt::source("test/tools/data")});
  EXPECT_EQ(nested.ns, "lab/cell2");
}

TEST(LaunchFile, IncludesAreFollowedWithTheirArgsAndTheCommandLineOverridesDefaults) {
  const std::string dir = lt::temp_dir("launch_include");
  std::filesystem::create_directories(dir + "/robot/urdf");
  write(dir + "/robot/urdf", "arm.urdf", "<robot name='arm'/>");
  write(dir + "/robot", "controllers.yaml", "a: 1\n");
  write(dir + "/robot", "upload.launch", R"L(<launch>
  <arg name="model" default="urdf/missing.urdf"/>
  <arg name="controllers" default="joint_state_controller"/>
  <param name="robot_description" textfile="$(arg model)"/>
  <rosparam command="load" file="controllers.yaml"/>
  <node name="spawner" pkg="controller_manager" type="spawner" args="$(arg controllers)"/>
</launch>)L");
  const std::string top = write(dir, "top.launch", R"L(<launch>
  <arg name="controllers" default="j1_controller"/>
  <include file="$(find gazebo_ros)/launch/empty_world.launch"/>
  <node name="spawn" pkg="gazebo_ros" type="spawn_model" args="-urdf -param robot_description -model arm"/>
  <include file="robot/upload.launch">
    <arg name="model" value="urdf/arm.urdf"/>
    <arg name="controllers" value="$(arg controllers) j2_controller"/>
  </include>
</launch>)L");
  LaunchPlan plan = read_launch_file(top, {});
  EXPECT_EQ(plan.urdf, std::filesystem::canonical(dir + "/robot/urdf/arm.urdf").string());
  ASSERT_EQ(plan.configs.size(), 1u);
  EXPECT_EQ(plan.configs[0], std::filesystem::canonical(dir + "/robot/controllers.yaml").string());
  EXPECT_EQ(plan.controllers, (std::vector<std::string>{"j1_controller", "j2_controller"}));
  bool noted = false;
  for (const auto& n : plan.notes) noted = noted || n.find("included " + dir + "/robot/upload.launch with 2") != std::string::npos;
  EXPECT_TRUE(noted);
  // NAME:=VALUE on the command line takes the place of a default, as roslaunch's.
  plan = read_launch_file(top, {}, {{"controllers", "j9_controller"}});
  EXPECT_EQ(plan.controllers, (std::vector<std::string>{"j9_controller", "j2_controller"}));
  // pass_all_args: the included file sees every argument of the file that includes it.
  const std::string all = write(dir, "all.launch", R"L(<launch>
  <arg name="model" default="urdf/arm.urdf"/>
  <arg name="controllers" default="j1_controller"/>
  <node name="spawn" pkg="gazebo_ros" type="spawn_model" args="-urdf -param robot_description -model arm"/>
  <include file="robot/upload.launch" pass_all_args="true"/>
</launch>)L");
  plan = read_launch_file(all, {}, {{"controllers", "j2_controller"}});
  EXPECT_EQ(plan.controllers, (std::vector<std::string>{"j2_controller"}));

  // An argument the included file does not declare, a fixed one passed, a file that includes itself.
  std::string p = problems_of([&] {
    read_launch_file(write(dir, "bad.launch", R"L(<launch>
  <node name="spawn" pkg="gazebo_ros" type="spawn_model" args="-urdf -param robot_description -model arm"/>
  <include file="robot/upload.launch"><arg name="modle" value="urdf/arm.urdf"/></include>
</launch>)L"),
                     {});
  });
  EXPECT_NE(p.find("bad.launch:3: <include>: modle:=urdf/arm.urdf is not an argument of " + dir +
                   "/robot/upload.launch (it declares: model, controllers)"),
            std::string::npos)
      << p;
  write(dir, "fixed.launch", "<launch><arg name='x' value='1'/></launch>");
  p = problems_of([&] {
    read_launch_file(write(dir, "f.launch", "<launch><include file='fixed.launch'><arg name='x' value='2'/></include>"
                                            "</launch>"),
                     {});
  });
  EXPECT_NE(p.find("x:=2 cannot be passed: value=\"1\" fixes this argument"), std::string::npos) << p;
  p = problems_of([&] { read_launch_file(write(dir, "loop.launch", "<launch><include file='loop.launch'/></launch>"), {}); });
  EXPECT_NE(p.find("loop.launch:1: <include>: " + dir + "/loop.launch includes itself"), std::string::npos) << p;
}
