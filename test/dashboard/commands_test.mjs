// The page's command panel (dashboard/page/src/commands.js) gives sliders from what a controller's type declares in
// the controller manager's list (command_type, command_width, command_quantity), never from its type's name: a type
// the page has never heard of gets them, a built-in one that takes no numbers does not. Run by ctest with node:
// node commands_test.mjs <path of commands.js> <path of dom.js>. The sliders follow the commands heard on the
// controller's channel (commandedValues): only a message of the type the controller takes, one finite number a joint.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

const moduleUrl = (text) => `data:text/javascript,${encodeURIComponent(text)}`;
const dom = moduleUrl(readFileSync(process.argv[3], 'utf8'));
const src = readFileSync(process.argv[2], 'utf8').replace("'./dom.js'", `"${dom}"`);
const { commandKind, commandable, gripperGoal, commandedValues, setPointValues, setPointShown, kHandsOffMs } =
  await import(moduleUrl(src));

const controller = (name, type, command_type, command_width, command_quantity, joints, state = 'running') =>
  ({ name, type, state, interface: '', joints, command_type, command_channel: command_type ? 'command' : '',
     command_width, command_quantity, publishes: [] });

const listed = [
  controller('joint_state_controller', 'joint_state_controller/JointStateController', '', 0, '', []),
  controller('j1', 'position_controllers/JointPositionController', 'float64_t', 1, 'position', ['j1']),
  controller('arm', 'effort_controllers/JointGroupPositionController', 'float64_array_t', 2, 'position', ['a', 'b']),
  controller('pid', 'effort_controllers/JointVelocityController', 'float64_t', 1, 'velocity', ['j2']),
  controller('trajectory', 'position_controllers/JointTrajectoryController', 'joint_trajectory_t', 0, '', ['a', 'b']),
  controller('base', 'diff_drive_controller/DiffDriveController', 'twist_t', 0, '', ['l', 'r']),
  controller('stopped', 'position_controllers/JointPositionController', 'float64_t', 1, 'position', ['j3'], 'stopped'),
  // A type nobody here knows, declared in one file: its declaration is all the page needs.
  controller('tiny', 'test_controllers/TinyEffortController', 'float64_array_t', 3, 'effort', ['x', 'y', 'z']),
  // Numbers whose quantity its type does not declare (a plugin that says only what take_commands says).
  controller('plain', 'my_controllers/Sine', 'float64_t', 1, '', ['j4']),
  // Gripper goals (gripper_command_t): a position slider that sends a goal.
  controller('hand', 'parallel_gripper_action_controller/GripperActionController', 'gripper_command_t', 0, '',
    ['finger']),
];

assert.deepEqual(commandable(listed).map((c) => c.name), ['j1', 'arm', 'pid', 'tiny', 'plain', 'hand']);
assert.deepEqual(commandable(listed).map(commandKind), ['position', 'position', 'velocity', 'effort', 'value',
  'gripper']);
assert.deepEqual(gripperGoal(0.02, 5, 7), { goal_id: 7, position: 0.02, max_effort: 5 });
assert.deepEqual(gripperGoal(0.02, NaN, 8), { goal_id: 8, position: 0.02, max_effort: 0 });
// A width that does not fit the joints (a malformed list) gets no sliders.
assert.equal(commandKind(controller('odd', 'x/Y', 'float64_array_t', 2, 'position', ['a', 'b', 'c'])), null);
assert.equal(commandKind(controller('old', 'position_controllers/JointPositionController', undefined, undefined,
  undefined, ['j1'])), null);

const [, j1, arm, , trajectory, , , , , hand] = listed;
assert.deepEqual(commandedValues(j1, 'float64_t', { utime: 3, data: 0.5 }), [0.5]);
assert.deepEqual(commandedValues(arm, 'float64_array_t', { data: [0.1, -0.2] }), [0.1, -0.2]);
assert.deepEqual(commandedValues(hand, 'gripper_command_t', { goal_id: 4, position: 0.02, max_effort: 0 }), [0.02]);
// Not what the controller takes: another type, another width, a NaN (null in the JSON), a trajectory.
assert.equal(commandedValues(j1, 'float64_array_t', { data: [0.5] }), null);
assert.equal(commandedValues(arm, 'float64_array_t', { data: [0.1] }), null);
assert.equal(commandedValues(arm, 'float64_array_t', { data: [0.1, null] }), null);
assert.equal(commandedValues(j1, 'float64_t', { data: null }), null);
assert.equal(commandedValues(j1, 'float64_t', null), null);
assert.equal(commandedValues(trajectory, 'joint_trajectory_t', { joint_names: ['a', 'b'], points: [] }), null);
// Before any command, a PID controller's set point (controller_state_t on <name>/state) for its one joint.
const state = { controller: 'pid', joint: 'j2', set_point: 0.7, process_value: 0.69 };
assert.deepEqual(setPointValues(listed[3], 'controller_state_t', state), [0.7]);
assert.equal(setPointValues(listed[3], 'controller_state_t', { ...state, joint: 'j1' }), null);
assert.equal(setPointValues(listed[3], 'controller_state_t', { ...state, set_point: null }), null);
assert.equal(setPointValues(arm, 'controller_state_t', { ...state, joint: 'a' }), null);
assert.equal(setPointValues(listed[3], 'float64_t', { data: 0.7 }), null);
// A set point moves the sliders before any command, and after one once the controller's state has caught up with it
// (kHandsOffMs): a set point that changes without a command (controllers restarted after a silent hardware) shows.
assert.equal(setPointShown(-Infinity, -Infinity, 1000), true);
assert.equal(setPointShown(-Infinity, 1000, 1000 + kHandsOffMs - 1), false);
assert.equal(setPointShown(-Infinity, 1000, 1000 + kHandsOffMs), true);
assert.equal(setPointShown(2000, -Infinity, 2000 + kHandsOffMs / 2), false, 'not under the hand');
console.log('commands.js: ok');
