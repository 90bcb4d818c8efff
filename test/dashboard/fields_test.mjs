// The page's field rows (dashboard/page/src/fields.js) read through the schema the server sends: row labels from
// the string array the schema names, columns from its components, nested messages by their type, and nothing guessed
// from a field's name. Run by ctest with node: node fields_test.mjs <path of fields.js>.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

const src = readFileSync(process.argv[2], 'utf8');
const { numericFields, fieldsOfType, valueAt } = await import(`data:text/javascript,${encodeURIComponent(src)}`);

const schema = {
  joint_state_t: { utime: { type: 'int64_t' }, name: { type: 'string', count: 'num_joints' },
    position: { type: 'double', count: 'num_joints', labels: 'name' } },
  link_poses_t: { name: { type: 'string', count: 'num_links' },
    position: { type: 'double', count: 'num_links', labels: 'name', components: 'x y z' } },
  joint_trajectory_t: { joint_names: { type: 'string', count: 'num_joints' },
    points: { type: 'trajectory_point_t', count: 'num_points', nested: 'trajectory_point_t' } },
  trajectory_point_t: { positions: { type: 'double', count: 'num_joints' } },
  other_t: { name: { type: 'string', count: 'n' }, value: { type: 'double', count: 'n' } },
  pid_gains_t: { utime: { type: 'int64_t' }, query: { type: 'boolean' }, p: { type: 'double' }, d: { type: 'double' },
    antiwindup: { type: 'boolean' } },
};
const rows = (msg, type) => numericFields(msg, schema, type).map((f) => `${f.path}=${f.label}=${f.value}`);

assert.deepEqual(rows({ utime: 5, name: ['j1', 'j2'], position: [0.1, 0.2] }, 'joint_state_t'),
  ['utime=utime=5', 'position[0]=position[j1]=0.1', 'position[1]=position[j2]=0.2']);
assert.deepEqual(rows({ name: ['base', 'rotor'], position: [[1, 2, 3], [4, 5, 6]] }, 'link_poses_t').slice(3),
  ['position[1][0]=position[rotor].x=4', 'position[1][1]=position[rotor].y=5', 'position[1][2]=position[rotor].z=6']);
assert.deepEqual(rows({ joint_names: ['a'], points: [{ positions: [7] }] }, 'joint_trajectory_t'),
  ['points[0].positions[0]=points[0].positions[0]=7']);
// A `name` array the schema does not tie to `value` labels nothing, and a type the schema lacks is shown by index.
assert.deepEqual(rows({ name: ['x'], value: [3] }, 'other_t'), ['value[0]=value[0]=3']);
assert.deepEqual(rows({ name: ['x'], position: [3] }, 'unknown_t'), ['position[0]=position[0]=3']);
// A label list of another length (a malformed message) is not used.
assert.deepEqual(rows({ name: ['j1'], position: [0.1, 0.2] }, 'joint_state_t'),
  ['position[0]=position[0]=0.1', 'position[1]=position[1]=0.2']);

assert.deepEqual(fieldsOfType(schema, 'pid_gains_t', ['double']), ['p', 'd']);
assert.deepEqual(fieldsOfType(schema, 'pid_gains_t', ['boolean']), ['query', 'antiwindup']);
assert.deepEqual(fieldsOfType(null, 'pid_gains_t', ['double']), []);
assert.equal(valueAt({ points: [{ positions: [1, 2] }] }, 'points[0].positions[1]'), 2);
console.log('fields.js: labels, components, nesting and gains fields from the schema: ok');
