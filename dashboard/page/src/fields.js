// A decoded message's numbers as (path, label, value): arrays by index, and labelled by name when the message has
// a name list of the same length (joint_states' position[0] shows as position[j1]).
export function numericFields(msg, path0 = '', label0 = '', out = []) {
  const names = [msg.name, msg.joints, msg.item, msg.joint_names].find((a) => Array.isArray(a));
  for (const [key, value] of Object.entries(msg)) {
    const path = path0 ? `${path0}.${key}` : key;
    const label = label0 ? `${label0}.${key}` : key;
    if (typeof value === 'number') {
      out.push({ path, label, value });
    } else if (Array.isArray(value)) {
      value.forEach((v, k) => {
        const named = names && names.length === value.length && typeof names[k] === 'string' ? names[k] : k;
        const p = `${path}[${k}]`;
        const l = `${label}[${named}]`;
        if (typeof v === 'number') out.push({ path: p, label: l, value: v });
        else if (Array.isArray(v)) v.forEach((x, c) => typeof x === 'number' && out.push({ path: `${p}[${c}]`, label: `${l}[${c}]`, value: x }));
        else if (v && typeof v === 'object') numericFields(v, p, l, out);
      });
    } else if (value && typeof value === 'object') {
      numericFields(value, path, label, out);
    }
  }
  return out;
}

// The value at a path written by numericFields ("position[1]", "points[0].positions[2]").
export function valueAt(msg, path) {
  let v = msg;
  for (const part of path.split('.')) {
    const m = part.match(/^(\w+)((?:\[\d+\])*)$/);
    if (!m || v == null) return undefined;
    v = v[m[1]];
    for (const idx of m[2].matchAll(/\[(\d+)\]/g)) {
      if (v == null) return undefined;
      v = v[Number(idx[1])];
    }
  }
  return typeof v === 'number' ? v : undefined;
}
