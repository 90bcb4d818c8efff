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

// Short labels for names shown side by side in a narrow column (a controller's joints by its sliders): the prefix and
// suffix all of them share (up to a '_', '/', '-' or '.') left off, so that shoulder_pan_joint and shoulder_lift_joint
// read "shoulder_pan" and "shoulder_lift", ur_joint_1 .. ur_joint_6 "1" .. "6". A name that would be left empty, or a
// single name, stays whole.
export function distinctLabels(names) {
  if (names.length < 2) return [...names];
  const sep = /[_\/.-]/;
  let pre = 0;
  for (let k = 0; names.every((n) => k < n.length && n[k] === names[0][k]); ++k) if (sep.test(names[0][k])) pre = k + 1;
  let suf = 0;
  for (let k = 1; names.every((n) => k <= n.length - pre && n[n.length - k] === names[0][names[0].length - k]); ++k)
    if (sep.test(names[0][names[0].length - k])) suf = k;
  const labels = names.map((n) => n.slice(pre, n.length - suf));
  return labels.every((l) => l.length > 0) && new Set(labels).size === labels.length ? labels : [...names];
}
