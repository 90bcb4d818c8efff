#!/usr/bin/env python3
"""Reads joint_states and commands a joint from Python, with the generated types.

    python3 joint_states_example.py [CONTROLLER JOINT [POSITION]]   # default: j1_controller j1 0.5

Prints the joint_states it receives for a moment, sends CONTROLLER/command
(float64_t) until JOINT, the joint the controller drives, reaches POSITION
(within 0.02), then prints the final positions. Uses LCM's own Python module
when installed, else lcm_lite (same wire format). Set LCM_DEFAULT_URL as for the
other programs. Runs where the build or `cmake --install` put it
(build/share/python/, PREFIX/share/lcm_control/python/) and from the checkout
(python/, after the build: it takes the classes from ../build/share/python/).
Exit code 0 when the joint got there, 1 when it did not or has no such joint,
2 for bad arguments, 4 when no joint_states came.
"""
import argparse
import os
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
if not os.path.isdir(os.path.join(here, "lcm_control")):  # the checkout's python/: the build's classes
    sys.path.insert(1, os.path.join(os.path.dirname(here), "build", "share", "python"))
try:
    import lcm
except ImportError:
    import lcm_lite as lcm
try:
    from lcm_control import float64_t, joint_state_t
except ImportError:
    sys.exit("%s: error: no Python package lcm_control: build first (./scripts/build writes build/share/python/), "
             "or put the folder holding it on PYTHONPATH" % os.path.basename(__file__))

parser = argparse.ArgumentParser(description="Read joint_states and command one joint through its controller.")
parser.add_argument("controller", nargs="?", default="j1_controller", metavar="CONTROLLER", help="its commands go to CONTROLLER/command")
parser.add_argument("joint", nargs="?", metavar="JOINT", help="the joint CONTROLLER drives, as joint_states names it")
parser.add_argument("position", nargs="?", type=float, default=0.5, metavar="POSITION", help="the command (default 0.5)")
args = parser.parse_args()
if args.joint is None:
    if args.controller != "j1_controller":
        parser.error("name the joint %s drives: %s %s JOINT [POSITION]" % (args.controller, parser.prog,
                                                                             args.controller))
    args.joint = "j1"
controller, joint, target = args.controller, args.joint, args.position

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
joints = [k for k in latest if k != "utime"]
print("joint_states at t=%.3f s: %s" % (latest["utime"] * 1e-6, ", ".join("%s=%.3f" % (k, latest[k]) for k in joints)))
if joint not in latest:
    print("joint_states has no joint '%s' (it has %s)" % (joint, ", ".join(joints)), file=sys.stderr)
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
