#!/usr/bin/env python3
"""lcm_control.client (python/client.py) against real robots: the UR-like arm (a trajectory goal SUCCEEDED at its
target, a bad goal REJECTED with the controller's reason, a switch to its group effort controller and a command of
six numbers), the gripper (a goal SUCCEEDED, one outside the limits REJECTED) and turret_bot (a float64_t command),
each started with launch on a bus of its own; and NoAnswer on a silent bus.

  test/e2e/python_client_test.py --bin-dir build/bin --source-dir . --python-dir build/share/python
"""
import argparse
import os
import random
import signal
import subprocess
import sys
import tempfile
import time


class Launched:
    """A robot started with launch on its own LCM URL; stopped (SIGINT, then SIGKILL) by its process group."""

    def __init__(self, bin_dir, launch_file, work):
        self.url = f"udpm://239.255.76.67:{random.randint(21000, 40000)}?ttl=0"
        self.log_path = os.path.join(work, os.path.basename(launch_file) + ".log")
        self.proc = subprocess.Popen([os.path.join(bin_dir, "launch"), launch_file, "--lcm-url", self.url],
                                     stdout=open(self.log_path, "w"), stderr=subprocess.STDOUT, start_new_session=True)
        end = time.monotonic() + 60
        while "[launch] up:" not in self.log():
            if self.proc.poll() is not None or time.monotonic() > end:
                self.stop()
                raise AssertionError(f"launch {launch_file} did not come up:\n{self.log()}")
            time.sleep(0.1)

    def log(self):
        with open(self.log_path) as f:
            return f.read()

    def stop(self):
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGINT)
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()


def near(a, b, tol):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin-dir", required=True)
    ap.add_argument("--source-dir", required=True)
    ap.add_argument("--python-dir", required=True)
    a = ap.parse_args()
    sys.path.insert(0, a.python_dir)
    from lcm_control.client import GoalFailed, NoAnswer, Refused, Robot
    from lcm_control import trajectory_status_t, gripper_status_t

    work = tempfile.mkdtemp(prefix="lcm_control_python_client_")
    robots = os.path.join(a.source_dir, "test/robots")

    # Nothing on the bus: NoAnswer, saying what to check.
    silent = Robot(url=f"udpm://239.255.76.67:{random.randint(41000, 50000)}?ttl=0", timeout=0.5)
    try:
        silent.controllers()
        raise AssertionError("a silent bus answered")
    except NoAnswer as e:
        print("silent bus:", e)
        assert "controller_manager/response" in str(e), e

    arm = Launched(a.bin_dir, os.path.join(robots, "ur_like.launch.yaml"), work)
    try:
        robot = Robot(url=arm.url, timeout=5)
        names = {c.name: c.state for c in robot.controllers()}
        print("controllers:", names)
        assert names.get("eff_joint_traj_controller") == "running", names
        jtc = next(c for c in robot.controllers() if c.name == "eff_joint_traj_controller")
        target = [0.3, -1.2, 1.4, -0.2, 0.5, 0.1]
        t0 = time.monotonic()
        r = robot.send_trajectory("eff_joint_traj_controller", [(1.5, target)])
        print(f"trajectory goal: {r.status == trajectory_status_t.SUCCEEDED and 'SUCCEEDED'} in "
              f"{time.monotonic() - t0:.1f} s: {r.message}")
        at = robot.joint_states()
        reached = [at[j] for j in jtc.joints]
        print("joint_states after it:", [round(x, 4) for x in reached])
        assert near(reached, target, 0.02), (reached, target)
        try:
            robot.send_trajectory("eff_joint_traj_controller", [(1.0, [0.0] * 6)], joints=["no_such_joint"] * 6)
            raise AssertionError("a goal for joints the controller does not have succeeded")
        except GoalFailed as e:
            print("bad goal:", e)
            assert e.result.status == trajectory_status_t.REJECTED and "no_such_joint" in str(e), e
        try:
            robot.switch(start=["not_a_controller"])
            raise AssertionError("a switch to a controller that is not loaded succeeded")
        except Refused as e:
            print("bad switch:", e)
            assert "not_a_controller" in str(e), e
        robot.load("joint_group_eff_controller")
        robot.switch(start=["joint_group_eff_controller"], stop=["eff_joint_traj_controller"])
        states = {c.name: c.state for c in robot.controllers()}
        assert states["joint_group_eff_controller"] == "running", states
        robot.command("joint_group_eff_controller", [0.0] * 6)
        try:
            robot.command("joint_group_eff_controller", [0.0] * 5)
            raise AssertionError("five numbers for six joints were sent")
        except ValueError as e:
            print("five numbers:", e)
            assert "takes 6 numbers" in str(e), e
        print("switched to joint_group_eff_controller and commanded it")
    finally:
        arm.stop()

    gripper = Launched(a.bin_dir, os.path.join(robots, "gripper_action.launch.yaml"), work)
    try:
        robot = Robot(url=gripper.url)
        r = robot.gripper("gripper_controller", 0.02)
        print(f"gripper goal: SUCCEEDED at {r.position:.4f} (goal {r.goal_position:.4f}): {r.message}")
        assert r.status == gripper_status_t.SUCCEEDED and abs(r.position - 0.02) < 0.005, r.message
        try:
            robot.gripper("gripper_controller", 5.0)
            raise AssertionError("a goal outside the finger's limits succeeded")
        except GoalFailed as e:
            print("gripper goal outside the limits:", e)
            assert e.result.status == gripper_status_t.REJECTED, e
    finally:
        gripper.stop()

    turret = Launched(a.bin_dir, os.path.join(a.source_dir, "config/turret_bot.launch.yaml"), work)
    try:
        robot = Robot(url=turret.url)
        end = time.monotonic() + 15
        while abs(robot.joint_states()["j2"] - 0.3) > 0.02:
            assert time.monotonic() < end, robot.joint_states()
            robot.command("j2_controller", 0.3)
        print(f"turret_bot: j2 at {robot.joint_states()['j2']:.4f} from float64_t commands")
    finally:
        turret.stop()
    print("python client: ok")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except AssertionError as e:
        print(f"FAILED: {e}")
        sys.exit(1)
