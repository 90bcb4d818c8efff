// The gains panel (dashboard/page/src/gains.js) opens on the first joint whose owner answers with gains: it asks
// sim_server's joints first, then each controller's, in the order listed, and no more than a bounded number.
// Run by ctest with node: node gains_test.mjs <path of gains.js> <path of dom.js> <path of fields.js>.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

const moduleUrl = (text) => `data:text/javascript,${encodeURIComponent(text)}`;
const src = readFileSync(process.argv[2], 'utf8')
  .replace("'./dom.js'", `"${moduleUrl(readFileSync(process.argv[3], 'utf8'))}"`)
  .replace("'./fields.js'", `"${moduleUrl(readFileSync(process.argv[4], 'utf8'))}"`);
const { gainsCandidates } = await import(moduleUrl(src));

assert.deepEqual(gainsCandidates({ sim_server: ['joint1', 'joint2'], joint1_position_controller: ['joint1'],
  arm: ['a', 'b'] }), [['sim_server', 'joint1'], ['sim_server', 'joint2'], ['joint1_position_controller', 'joint1'],
  ['arm', 'a'], ['arm', 'b']]);
assert.deepEqual(gainsCandidates({ sim_server: [] }), []);
// A robot of hundreds of joints is not asked about all of them.
const many = gainsCandidates({ sim_server: Array.from({ length: 500 }, (_, k) => `j${k}`) });
assert.ok(many.length > 0 && many.length < 500, many.length);
assert.deepEqual(many[0], ['sim_server', 'j0']);
console.log('gains.js: ok');
