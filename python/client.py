"""A Python client of a running lcm_control robot: what cmctl, turret-cmd, send-trajectory and gripper do, as calls.

    from lcm_control.client import Robot
    robot = Robot()                                   # LCM_DEFAULT_URL; Robot(namespace="r0") for a namespaced robot
    robot.joint_states()["shoulder_pan_joint"]        # a position, from joint_states
    robot.controllers()                               # cmctl list: controller_info_t, name, type, state, joints ...
    robot.command("forward_position_controller", [0, -1.2, 1.0, 0, 0, 0])   # float64_t or float64_array_t, as it takes
    robot.send_trajectory("joint_trajectory_controller", [(2.0, [0, -1.2, 1.0, 0, 0, 0])])  # waits for SUCCEEDED
    robot.gripper("gripper_controller", 0.4)          # a GripperCommand goal; waits for its result
    robot.switch(start=["a"], stop=["b"])             # cmctl switch-controllers (strict)

Installed as the `client` module of the `lcm_control` package, beside lcm-gen's message classes (build/share/python
in the checkout, PREFIX/share/lcm_control/python installed). LCM's own module is used when installed (pip install
lcm), else lcm_lite, which speaks the same wire format. Errors are exceptions that say what to do: NoAnswer when
nothing answers within the timeout (is the robot running on this LCM URL and namespace?), Refused when the
controller manager refuses a request, GoalFailed when a goal ends other than SUCCEEDED (its status and message).
"""
import itertools
import os
import re
import time

try:
    import lcm  # LCM's own module, when pip installed it
except ImportError:
    import lcm_lite as lcm  # the same wire format

from lcm_control import (cm_request_t, cm_response_t, float64_array_t, float64_t, gripper_command_t,
                         gripper_status_t, joint_state_t, joint_trajectory_t, trajectory_point_t,
                         trajectory_status_t)


class NoAnswer(RuntimeError):
    """Nothing answered within the timeout."""


class Refused(RuntimeError):
    """The controller manager refused the request (its message says why)."""


class GoalFailed(RuntimeError):
    """A goal ended other than SUCCEEDED; `result` is the controller's result message."""

    def __init__(self, text, result):
        super().__init__(text)
        self.result = result


def _status_name(status_type, status):
    for name in dir(status_type):
        if name.isupper() and getattr(status_type, name) == status:
            return name
    return str(status)


_ids = itertools.count(int(time.time() * 1000) % 1000000000 * 1000 + os.getpid() % 1000)


class Robot:
    def __init__(self, url=None, namespace="", timeout=5.0):
        """url: the LCM URL (default LCM_DEFAULT_URL, as every program here); namespace: the robot's --namespace;
        timeout: seconds to wait for an answer, a state or a list."""
        self.lc = lcm.LCM(url) if url else lcm.LCM()
        self.namespace = namespace.strip("/")
        self.timeout = timeout
        self._latest = None
        self._answers = {}
        self._listed = {}
        self.lc.subscribe(re.escape(self.channel("joint_states")), self._on_joint_states)
        self.lc.subscribe(re.escape(self.channel("controller_manager/response")), self._on_response)

    def channel(self, name):
        """A channel's name on the bus: NAMESPACE/name, or name without a namespace."""
        return f"{self.namespace}/{name}" if self.namespace else name

    # ---- joint_states ----------------------------------------------------------------------------------------

    def _on_joint_states(self, channel, data):
        self._latest = joint_state_t.decode(data)

    def joint_state(self, timeout=None):
        """The next joint_state_t (name, position, velocity, effort, utime in sim time)."""
        self._latest = None
        self._pump(lambda: self._latest is not None, timeout,
                   f"no {self.channel('joint_states')} (is the robot running, with a joint_state_controller or "
                   "joint_state_broadcaster, on this LCM URL and namespace?)")
        return self._latest

    def joint_states(self, timeout=None):
        """{joint: position} from the next joint_states."""
        m = self.joint_state(timeout)
        return dict(zip(m.name, m.position))

    # ---- the controller manager ------------------------------------------------------------------------------

    def _on_response(self, channel, data):
        m = cm_response_t.decode(data)
        if m.request_id in self._answers:
            self._answers[m.request_id] = m

    def _request(self, op, names=(), start=(), stop=(), strict=True, timeout=None):
        req = cm_request_t()
        req.utime = int(time.time() * 1e6)
        req.request_id = next(_ids)
        req.client = "python"
        req.op = op
        req.names, req.num_names = list(names), len(names)
        req.start, req.num_start = list(start), len(start)
        req.stop, req.num_stop = list(stop), len(stop)
        req.strictness = cm_request_t.STRICT if strict else cm_request_t.BEST_EFFORT
        self._answers[req.request_id] = None
        self.lc.publish(self.channel("controller_manager/request"), req.encode())
        self._pump(lambda: self._answers[req.request_id] is not None, timeout,
                   f"no answer on {self.channel('controller_manager/response')} (is controller_manager running on "
                   "this LCM URL and namespace?)")
        answer = self._answers.pop(req.request_id)
        if not answer.ok:
            raise Refused(answer.message)
        return answer

    def controllers(self, timeout=None):
        """cmctl list: the controllers (controller_info_t: name, type, state, joints, command_type, ...)."""
        answer = self._request(cm_request_t.LIST, timeout=timeout)
        self._listed = {c.name: c for c in answer.controllers}
        return list(answer.controllers)

    def load(self, *names, timeout=None):
        return self._request(cm_request_t.LOAD, names=names, timeout=timeout).message

    def unload(self, *names, timeout=None):
        return self._request(cm_request_t.UNLOAD, names=names, timeout=timeout).message

    def switch(self, start=(), stop=(), strict=True, timeout=None):
        """Stops `stop` and starts `start` in one switch; raises Refused with the manager's reason."""
        return self._request(cm_request_t.SWITCH, start=start, stop=stop, strict=strict, timeout=timeout).message

    def _controller(self, name, timeout=None):
        if name not in self._listed:
            self.controllers(timeout)
        if name not in self._listed:
            raise Refused(f"no controller '{name}' is loaded (loaded: {', '.join(self._listed) or 'none'})")
        return self._listed[name]

    # ---- commands --------------------------------------------------------------------------------------------

    def command(self, controller, value, timeout=None):
        """One command to a forwarding controller, as it takes it: a number (float64_t) or one per joint
        (float64_array_t), on CONTROLLER/<its command channel>, stamped with the latest joint_states' time."""
        c = self._controller(controller, timeout)
        values = [float(v) for v in (value if isinstance(value, (list, tuple)) else [value])]
        if c.command_type == "float64_t":
            if len(values) != 1:
                raise ValueError(f"{controller} takes one number (float64_t), got {len(values)}")
            msg = float64_t()
            msg.data = values[0]
        elif c.command_type == "float64_array_t":
            if c.command_width and len(values) != c.command_width:
                raise ValueError(f"{controller} takes {c.command_width} numbers ({', '.join(c.joints)}), "
                                 f"got {len(values)}")
            msg = float64_array_t()
            msg.data, msg.size = values, len(values)
        else:
            raise ValueError(f"{controller} takes {c.command_type or 'no command'}, not numbers: use "
                             "send_trajectory() for a trajectory controller, gripper() for a gripper controller")
        msg.utime = self._latest.utime if self._latest is not None else 0
        self.lc.publish(self.channel(f"{controller}/{c.command_channel or 'command'}"), msg.encode())

    # ---- goals -----------------------------------------------------------------------------------------------

    def _goal(self, controller, goal, status_type, timeout, what):
        results = []

        def on_result(channel, data):
            m = status_type.decode(data)
            if m.goal_id == goal.goal_id:
                results.append(m)

        sub = self.lc.subscribe(re.escape(self.channel(f"{controller}/result")), on_result)
        try:
            self.lc.publish(self.channel(f"{controller}/command"), goal.encode())
            self._pump(lambda: bool(results), timeout,
                       f"no result of {what} on {self.channel(controller + '/result')} within {timeout:g} s (is "
                       f"{controller} running?)")
        finally:
            self.lc.unsubscribe(sub)
        r = results[0]
        if r.status != status_type.SUCCEEDED:
            reason = r.message[len(controller) + 2:] if r.message.startswith(controller + ": ") else r.message
            raise GoalFailed(f"{controller}: {_status_name(status_type, r.status)}: {reason}", r)
        return r

    def send_trajectory(self, controller, points, joints=None, timeout=None):
        """A trajectory goal: points are (time_from_start, positions) or (time, positions, velocities), for
        `joints` (default: the controller's, in its order). Waits for the result (timeout: the last point's time
        + 10 s) and returns it (trajectory_status_t); raises GoalFailed with the status and the controller's reason."""
        c = self._controller(controller)
        goal = joint_trajectory_t()
        goal.utime = int(time.time() * 1e6)
        goal.goal_id = next(_ids)
        goal.joint_names = list(joints or c.joints)
        goal.num_joints = len(goal.joint_names)
        goal.points = []
        for p in points:
            tp = trajectory_point_t()
            tp.time_from_start = float(p[0])
            tp.positions = [float(x) for x in p[1]]
            tp.num_positions = len(tp.positions)
            tp.velocities = [float(x) for x in p[2]] if len(p) > 2 else []
            tp.num_velocities = len(tp.velocities)
            tp.accelerations, tp.num_accelerations = [], 0
            goal.points.append(tp)
        goal.num_points = len(goal.points)
        span = goal.points[-1].time_from_start if goal.points else 0.0
        return self._goal(controller, goal, trajectory_status_t, timeout or span + 10.0,
                          f"the trajectory goal {goal.goal_id}")

    def gripper(self, controller, position, max_effort=0.0, timeout=10.0):
        """A GripperCommand goal (position, max_effort; <= 0: the controller's own); waits for the result
        (gripper_status_t: position, effort, stalled, reached_goal) and returns it; raises GoalFailed otherwise."""
        goal = gripper_command_t()
        goal.utime = int(time.time() * 1e6)
        goal.goal_id = next(_ids)
        goal.position = float(position)
        goal.max_effort = float(max_effort)
        return self._goal(controller, goal, gripper_status_t, timeout, f"the gripper goal {goal.goal_id}")

    # ---- the bus ---------------------------------------------------------------------------------------------

    def _pump(self, done, timeout, what):
        timeout = self.timeout if timeout is None else timeout
        end = time.monotonic() + timeout
        while not done():
            left = end - time.monotonic()
            if left <= 0:
                raise NoAnswer(what)
            self.lc.handle_timeout(int(min(left, 0.1) * 1000) + 1)
