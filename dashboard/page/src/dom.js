// Text as the page shows it, as the programs log it (rt/log.hpp clip): control characters as \xNN, so that a name
// from the bus cannot break or forge a line, and past `max` (kShownChars) clipped with its length stated, so that a
// 60 KB name does not bloat a table. A tooltip holds more (kTitleChars): the whole of any name a robot has.
export const kShownChars = 200;
export const kTitleChars = 2000;
export function shown(text, max = kShownChars) {
  const s = String(text);
  const escape = (t) => t.replace(/[\u0000-\u0008\u000a-\u001f\u007f]/g,
    (c) => `\\x${c.charCodeAt(0).toString(16).padStart(2, '0')}`);
  return s.length <= max ? escape(s) : `${escape(s.slice(0, max))}... (${s.length} chars)`;
}

// Elements built from text, never from HTML: channel, controller and joint names come from the bus, where anyone
// may publish anything. A title (the tooltip of a name the layout may cut) is shown() as the text is.
export function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k.startsWith('on')) e[k] = v;
    else e.setAttribute(k, k === 'title' ? shown(v, kTitleChars) : v);
  }
  for (const c of children) e.append(c instanceof Node ? c : shown(c));
  return e;
}

// A name in a box that may be narrower than it: cut with an ellipsis by the style sheet, whole in its tooltip.
export function nameEl(tag, cls, text) {
  return el(tag, { class: cls, title: text }, text);
}

// An option per value, shown as shown() has it; its value stays the whole text.
export function options(select, values) {
  select.replaceChildren(...values.map((v) => el('option', { value: v, title: v }, v)));
}
