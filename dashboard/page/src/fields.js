// A decoded message's numbers as (path, label, value), read through the schema the server sends (lcmtypes/, as
// kFieldInfo): arrays by index in the path, and in the label by the string array the schema says names their rows
// (joint_state_t's position[0] shows as position[j1]) and by the components of a fixed inner dimension
// (link_poses_t's position[1][2] shows as position[rotor].z); nested messages through their own type.
export function numericFields(msg, schema, type, path0 = '', label0 = '', out = []) {
  const info = (schema && schema[type]) || {};
  for (const [key, value] of Object.entries(msg)) {
    const f = info[key] || {};
    const path = path0 ? `${path0}.${key}` : key;
    const label = label0 ? `${label0}.${key}` : key;
    if (typeof value === 'number') {
      out.push({ path, label, value });
    } else if (Array.isArray(value)) {
      const names = f.labels && Array.isArray(msg[f.labels]) && msg[f.labels].length === value.length ? msg[f.labels] : null;
      const comps = f.components ? f.components.split(' ') : [];
      value.forEach((v, k) => {
        const p = `${path}[${k}]`;
        const l = `${label}[${names && typeof names[k] === 'string' && names[k] !== '' ? names[k] : k}]`;
        if (typeof v === 'number') out.push({ path: p, label: l, value: v });
        else if (Array.isArray(v)) v.forEach((x, c) => typeof x === 'number' && out.push({ path: `${p}[${c}]`, label: c < comps.length ? `${l}.${comps[c]}` : `${l}[${c}]`, value: x }));
        else if (v && typeof v === 'object') numericFields(v, schema, f.nested, p, l, out);
      });
    } else if (value && typeof value === 'object') {
      numericFields(value, schema, f.nested, path, label, out);
    }
  }
  return out;
}

// The fields of `type` whose .lcm type is one of `lcmTypes`, in schema order ([] before the schema arrives).
export function fieldsOfType(schema, type, lcmTypes) {
  return Object.entries((schema && schema[type]) || {}).filter(([, f]) => lcmTypes.includes(f.type)).map(([name]) => name);
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
