// The page shows text from the bus as the programs log it (dashboard/page/src/dom.js shown()): control characters
// escaped, and a long name clipped with its length stated; a name the layout may cut has its whole text, escaped, in
// its tooltip (title). Run by ctest with node: node dom_test.mjs <path of dom.js>.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

const src = readFileSync(process.argv[2], 'utf8');
const { shown, kShownChars, kTitleChars, el, nameEl, options, distinctLabels } = await import(`data:text/javascript,${encodeURIComponent(src)}`);

assert.equal(shown('j2_controller'), 'j2_controller');
assert.equal(shown(42), '42');
// A forged line and a terminal escape arrive as text, on one line; a tab stays.
assert.equal(shown('ok\n[controller_manager] info: forged'), 'ok\\x0a[controller_manager] info: forged');
assert.equal(shown('\u001b[2J\u001b[31mred\u007f\tend'), '\\x1b[2J\\x1b[31mred\\x7f\tend');
// 60,000 characters: the first kShownChars and the length.
const long = 'x'.repeat(60000);
assert.equal(shown(long), `${'x'.repeat(kShownChars)}... (60000 chars)`);
assert.equal(shown('y'.repeat(kShownChars)), 'y'.repeat(kShownChars));

// Elements in a stand-in for the browser's document: what el(), nameEl() and options() set.
globalThis.Node = class Node {
  constructor(tag) {
    Object.assign(this, { tag, attributes: {}, children: [], className: '' });
  }
  setAttribute(k, v) {
    this.attributes[k] = String(v);
  }
  append(...c) {
    this.children.push(...c);
  }
  replaceChildren(...c) {
    this.children = c;
  }
};
globalThis.document = { createElement: (tag) => new Node(tag) };

const joint = 'left_shoulder_pan_joint_of_the_second_arm_on_the_mobile_base';
const n = nameEl('span', 'joint', joint);
assert.deepEqual([n.tag, n.className, n.attributes.title, n.children], ['span', 'joint', joint, [joint]]);
// A forged name is escaped in the tooltip as in the text; a long one is whole in the tooltip up to kTitleChars.
const forged = nameEl('td', 'name', 'j1\n[launch] all stopped');
assert.equal(forged.attributes.title, 'j1\\x0a[launch] all stopped');
assert.equal(forged.children[0], 'j1\\x0a[launch] all stopped');
const longName = 'a'.repeat(500);
assert.equal(nameEl('span', 'name', longName).attributes.title, longName);
assert.equal(nameEl('span', 'name', longName).children[0], `${'a'.repeat(kShownChars)}... (500 chars)`);
assert.equal(el('span', { title: 'b'.repeat(kTitleChars + 1) }).attributes.title,
  `${'b'.repeat(kTitleChars)}... (${kTitleChars + 1} chars)`);
// Other attributes are set as given (an id, a value: not text shown to the user).
assert.equal(el('input', { value: 'x\ny' }).attributes.value, 'x\ny');
const select = new Node('select');
options(select, ['sim_server', 'c\u001b[2J']);
assert.deepEqual(select.children.map((o) => [o.attributes.value, o.attributes.title, o.children[0]]),
  [['sim_server', 'sim_server', 'sim_server'], ['c\u001b[2J', 'c\\x1b[2J', 'c\\x1b[2J']]);
console.log('dom_test: ok');

// Slider labels that stay distinct in a narrow column: the shared prefix and suffix (at a separator) left off.
assert.deepEqual(distinctLabels(['shoulder_pan_joint', 'shoulder_lift_joint', 'elbow_joint', 'wrist_1_joint']),
  ['shoulder_pan', 'shoulder_lift', 'elbow', 'wrist_1']);
assert.deepEqual(distinctLabels(['ur_shoulder_pan_joint', 'ur_shoulder_lift_joint']), ['pan', 'lift']);
assert.deepEqual(distinctLabels(['joint_1', 'joint_2', 'joint_7']), ['1', '2', '7']);
assert.deepEqual(distinctLabels(['left_wheel', 'right_wheel']), ['left', 'right']);
assert.deepEqual(distinctLabels(['j1', 'j2']), ['j1', 'j2']); // no separator: whole
assert.deepEqual(distinctLabels(['arm/a', 'arm/a_b']), ['a', 'a_b']);
assert.deepEqual(distinctLabels(['x_a', 'x_a']), ['x_a', 'x_a']); // the same name twice: whole
assert.deepEqual(distinctLabels(['only_one_joint']), ['only_one_joint']);
assert.deepEqual(distinctLabels([]), []);
console.log('dom_test: distinctLabels ok');
