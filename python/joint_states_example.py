#!/usr/bin/env python3
"""Reads joint_states and commands a joint from Python, with the generated types.

    python3 joint_states_example.py [CONTROLLER [POSITION]]   # default: j1_controller 0.5

Prints the joint_states it receives for a moment, sends CONTROLLER/command
(float64_t) until the joint the controller drives reaches POSITION (within 0.02),
then prints the final positions. Uses LCM's own Python module when installed,
else lcm_lite (same wire format). Set LCM_DEFAULT_URL as for the other programs.
Exit code 0 when the joint got there, 4 when no joint_states came.
"""
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
try:
    import lcm
except ImportError:
    import lcm_lite as lcm
from lcm_control import float64_t, joint_state_t

controller = sys.argv[1] if len(sys.argv) > 1 else "j1_controller"
target = float(sys.argv[2]) if len(sys.argv) > 2 else 0.5
joint = controller[: -len("_controller")] if controller.endswith("_controller") else controller

bus = lcm.LCM(os.environ.get("LCM_DEFAULT_URL"))
latest = {}


def on_joint_states(channel, data):
    try:
        msg = joint_state_t.decode(data)
    except ValueError:
        return  # not a joint_state_t
    latest.update(zip(msg.name, msg.position))
    latest["utime"] = msg.utime


bus.subscribe("joint_states", on_joint_states)
deadline = time.time() + 5
while "utime" not in latest and time.time() < deadline:
    bus.handle_timeout(100)
if "utime" not in latest:
    print("no joint_states within 5 s: is a robot running on this LCM URL?", file=sys.stderr)
    sys.exit(4)
print("joint_states at t=%.3f s: %s" % (latest["utime"] * 1e-6,
                                       ", ".join("%s=%.3f" % (k, v) for k, v in latest.items() if k != "utime")))
if joint not in latest:
    print("joint_states has no joint '%s' (the controller's name without _controller)" % joint, file=sys.stderr)
    sys.exit(1)

command = float64_t()
command.data = target
deadline = time.time() + 10
while abs(latest[joint] - target) > 0.02 and time.time() < deadline:
    command.utime = latest["utime"]  # sim time, as the other tools stamp it
    bus.publish(controller + "/command", command.encode())
    end = time.time() + 0.05
    while time.time() < end:
        bus.handle_timeout(10)
print("%s at %.4f (target %.4f) at t=%.3f s" % (joint, latest[joint], target, latest["utime"] * 1e-6))
sys.exit(0 if abs(latest[joint] - target) <= 0.02 else 1)
