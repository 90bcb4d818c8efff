// Elements built from text, never from HTML: channel, controller and joint names come from the bus, where anyone
// may publish anything.
export function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k.startsWith('on')) e[k] = v;
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c instanceof Node ? c : String(c));
  return e;
}

export function options(select, values) {
  select.replaceChildren(...values.map((v) => el('option', {}, v)));
}
