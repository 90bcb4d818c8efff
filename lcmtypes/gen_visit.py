#!/usr/bin/env python3
"""Writes lcm_control/visit.hpp: each message's fields in schema order, from the .lcm files.

For every struct T it emits `template <class V> void visit(T& m, V& v)` (and
the const overload), calling on v, per field of the .lcm file:
  v.count(name, n)                      an int32 that sizes arrays
  v.value(name, x)                      a scalar (number, boolean, string)
  v.list(name, vec, count_name)         a one-dimensional variable array
  v.matrix(name, vec_of_vec, count_name, inner)
                                        [count][inner]: a variable array of fixed rows
  v.structs(name, vec, count_name)      a variable array of nested messages
  v.nested(name, msg)                   one nested message
so that tools read and write any message by field path without a hand-written
function per type (tools/lib/fields.cpp, the bus tool). for_each_type(f) calls
f(type_tag<T>{}) for every message type. kFieldInfo lists every field: its
.lcm type, the field that sizes it, the string array of the same size that
names its rows (joint_state_t's `name` for `position`), and what its comment
says: a unit as `// [rad or m] ...`, names for a fixed inner dimension as
`{x y z}` (CSV columns, plot paths and the dashboard's page use them).
"""
import re
import sys

PRIMITIVES = {"int8_t", "int16_t", "int32_t", "int64_t", "float", "double", "boolean", "string", "byte"}


def annotations(path):
    """{field: (unit, components)} from trailing comments: `// [unit] ...`, `{x y z}` naming a fixed inner dimension."""
    out = {}
    for line in open(path):
        m = re.match(r"\s*[\w.]+\s+(\w+)\s*(?:\[[^\]]*\]\s*)*;\s*//(.*)", line)
        if not m:
            continue
        comment = m.group(2).strip()
        unit = re.match(r"\[([^\]]+)\]", comment)
        comps = re.search(r"\{([\w ]+)\}", comment)
        if unit or comps:
            out[m.group(1)] = (unit.group(1) if unit else "", comps.group(1).split() if comps else [])
    return out


def parse(path):
    text = re.sub(r"//[^\n]*", "", open(path).read())
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    m = re.search(r"struct\s+(\w+)\s*\{(.*)\}", text, re.S)
    if not m:
        sys.exit(f"{path}: no struct")
    name, body = m.group(1), m.group(2)
    fields = []
    for decl in body.split(";"):
        decl = " ".join(decl.split())
        if not decl or decl.startswith("const "):
            continue
        fm = re.fullmatch(r"([\w.]+) (\w+)((?:\s*\[\s*\w+\s*\])*)", decl)
        if not fm:
            sys.exit(f"{path}: cannot read the field '{decl}'")
        ftype, fname, dims = fm.group(1), fm.group(2), re.findall(r"\[\s*(\w+)\s*\]", fm.group(3))
        fields.append((ftype.split(".")[-1], fname, dims))
    return name, fields, annotations(path)


def emit(name, fields):
    sizers = {d[0] for _, _, d in fields if d and not d[0].isdigit()}
    lines = [f"template <class M, class V>", f"void visit_{name}(M& m, V& v) {{"]
    for ftype, fname, dims in fields:
        nested = ftype not in PRIMITIVES
        if not dims:
            if fname in sizers:
                lines.append(f'  v.count("{fname}", m.{fname});')
            elif nested:
                lines.append(f'  v.nested("{fname}", m.{fname});')
            else:
                lines.append(f'  v.value("{fname}", m.{fname});')
        elif len(dims) == 1 and not dims[0].isdigit():
            call = "structs" if nested else "list"
            lines.append(f'  v.{call}("{fname}", m.{fname}, "{dims[0]}");')
        elif len(dims) == 2 and not dims[0].isdigit() and dims[1].isdigit() and not nested:
            lines.append(f'  v.matrix("{fname}", m.{fname}, "{dims[0]}", {dims[1]});')
        else:
            sys.exit(f"{name}.{fname}: arrays of shape {dims} are not supported by gen_visit.py; add them here")
    lines.append("}")
    lines.append(f"template <class V> void visit({name}& m, V& v) {{ visit_{name}(m, v); }}")
    lines.append(f"template <class V> void visit(const {name}& m, V& v) {{ visit_{name}(m, v); }}")
    return "\n".join(lines)


def main():
    out, sources = sys.argv[1], sys.argv[2:]
    structs = [parse(p) for p in sorted(sources)]
    includes = "\n".join(f'#include "lcm_control/{n}.hpp"' for n, _, _ in structs)
    decls = "\n".join(f"template <class V> void visit({n}& m, V& v);\n"
                      f"template <class V> void visit(const {n}& m, V& v);" for n, _, _ in structs)
    bodies = "\n\n".join(emit(n, f) for n, f, _ in structs)
    tags = "\n".join(f"  f(type_tag<{n}>{{}});" for n, _, _ in structs)
    info = []
    for n, fields, notes in structs:
        for ftype, fname, dims in fields:
            unit, comps = notes.get(fname, ("", []))
            nested = ftype if ftype not in PRIMITIVES else ""
            count = dims[0] if dims else ""
            labels = ""
            if count and not count.isdigit() and ftype != "string":
                named_by = [f for t, f, d in fields if t == "string" and d and d[0] == count]
                labels = named_by[0] if len(named_by) == 1 else ""
            info.append(f'    {{"{n}", "{fname}", "{ftype}", "{count}", "{labels}", "{unit}", "{nested}", '
                        f'"{" ".join(comps)}"}},')
    bodies += ("\n\n// Every field of every message in schema order: its .lcm type, the field (or fixed size) of its\n"
               "// first dimension, the string array of that size that names its rows, what its comment says (a unit\n"
               "// as `// [unit]`, names for a fixed inner dimension as `{x y z}`), and the message type it nests.\n"
               "struct FieldInfo {\n  const char* type;\n  const char* field;\n  const char* lcm_type;\n"
               "  const char* count;   // \"\" for a scalar\n  const char* labels;  // \"\" when no string array names its rows\n"
               "  const char* unit;\n  const char* nested;\n  const char* components;  // space-separated\n};\n"
               "inline constexpr FieldInfo kFieldInfo[] = {\n" + "\n".join(info) + "\n};")
    bodies += ("\n\ntemplate <class T>\nstruct type_tag {\n  using type = T;\n};\n\n"
               f"template <class F>\nvoid for_each_type(F&& f) {{\n{tags}\n}}")
    text = (f"// Generated by lcmtypes/gen_visit.py from lcmtypes/*.lcm; do not edit.\n"
            f"// visit(msg, visitor): every field in schema order (see gen_visit.py for the visitor's calls).\n"
            f"#pragma once\n\n{includes}\n\nnamespace lcm_control {{\n\n{decls}\n\n{bodies}\n\n}}  // namespace lcm_control\n")
    try:
        if open(out).read() == text:
            return
    except OSError:
        pass
    with open(out, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
