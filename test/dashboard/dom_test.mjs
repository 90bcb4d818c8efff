// The page shows text from the bus as the programs log it (dashboard/page/src/dom.js shown()): control characters
// escaped, and a long name clipped with its length stated. Run by ctest with node: node dom_test.mjs <path of dom.js>.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

const src = readFileSync(process.argv[2], 'utf8');
const { shown, kShownChars } = await import(`data:text/javascript,${encodeURIComponent(src)}`);

assert.equal(shown('j2_controller'), 'j2_controller');
assert.equal(shown(42), '42');
// A forged line and a terminal escape arrive as text, on one line; a tab stays.
assert.equal(shown('ok\n[controller_manager] info: forged'), 'ok\\x0a[controller_manager] info: forged');
assert.equal(shown('\u001b[2J\u001b[31mred\u007f\tend'), '\\x1b[2J\\x1b[31mred\\x7f\tend');
// 60,000 characters: the first kShownChars and the length.
const long = 'x'.repeat(60000);
assert.equal(shown(long), `${'x'.repeat(kShownChars)}... (60000 chars)`);
assert.equal(shown('y'.repeat(kShownChars)), 'y'.repeat(kShownChars));
console.log('dom_test: ok');
