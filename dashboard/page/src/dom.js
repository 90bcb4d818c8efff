// Text as the page shows it, as the programs log it (rt/log.hpp clip): control characters as \xNN, so that a name
// from the bus cannot break or forge a line, and past kShownChars clipped with its length stated, so that a 60 KB
// name does not bloat a table.
export const kShownChars = 200;
export function shown(text) {
  const s = String(text);
  const escape = (t) => t.replace(/[\u0000-\u0008\u000a-\u001f\u007f]/g,
    (c) => `\\x${c.charCodeAt(0).toString(16).padStart(2, '0')}`);
  return s.length <= kShownChars ? escape(s) : `${escape(s.slice(0, kShownChars))}... (${s.length} chars)`;
}

// Elements built from text, never from HTML: channel, controller and joint names come from the bus, where anyone
// may publish anything.
export function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k.startsWith('on')) e[k] = v;
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c instanceof Node ? c : shown(c));
  return e;
}

// An option per value, shown as shown() has it; its value stays the whole text.
export function options(select, values) {
  select.replaceChildren(...values.map((v) => el('option', { value: v }, v)));
}
