#!/usr/bin/env python3
"""Report import cycles between the modules of a Rust crate's `src/` (default: host-sim/src).

Usage: scripts/check-import-cycles.py [SRC_DIR] [--graph]

Exits 0 when the module graph has no cycle, 1 naming every cycle (each strongly
connected component of more than one module, with one concrete loop through it), 2 on
bad arguments. Python 3 standard library only, so it runs in CI without setup.

The graph:
* A module is a source file: `src/a/b.rs` and `src/a/b/mod.rs` are `crate::a::b`,
  `src/lib.rs` is `crate`. `src/bin/` (separate binary crates) is skipped. An inline
  `mod name { ... }` block (e.g. `#[cfg(test)] mod tests`) is a module of its own,
  `crate::a::b::name`, as for rustc: a test module that uses its parent's siblings
  does not make the parent depend on them.
* Edges come from every path in code after comments, strings and char literals are
  removed: `use` trees (`use crate::a::{b, c::D};`), `crate::a::b` paths written
  inline, `super::` / `self::` paths, and relative `use child::X` paths naming a child
  module of the current one. Paths into other crates are ignored.
* A path resolves to the longest prefix that is a module. When the next segment is an
  item that the module re-exports (`pub use child::Item;` or `pub use child::*;`), the
  edge follows the re-export to the defining module, so a `mod.rs` facade does not
  create a false cycle: `use crate::analysis::Stats` is an edge to
  `crate::analysis::stats`, not to `crate::analysis`.
* `mod child;` declarations are not edges, and neither are a module's `pub use`
  re-exports of its own descendants (the facade). Any other use of a descendant by an
  ancestor is an edge (so `gap` using `gap::cells` while `gap::cells` uses
  `super::X` is a cycle).
* Self-edges are dropped.
"""

import os
import re
import sys
from collections import defaultdict

IDENT = r"[A-Za-z_][A-Za-z0-9_]*"


def strip_code(text):
    """Remove comments, string literals and char literals, keeping newlines and braces."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            depth, i = 1, i + 2
            while i < n and depth:
                if text.startswith("/*", i):
                    depth, i = depth + 1, i + 2
                elif text.startswith("*/", i):
                    depth, i = depth - 1, i + 2
                else:
                    if text[i] == "\n":
                        out.append("\n")
                    i += 1
        elif c == "r" and re.match(r'r(#*)"', text[i:i + 10]) and not re.match(r"[A-Za-z0-9_]", text[i - 1:i] or " "):
            m = re.match(r'r(#*)"', text[i:])
            close = '"' + m.group(1)
            j = text.find(close, i + len(m.group(0)))
            j = n if j < 0 else j + len(close)
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j + 1
        elif c == "'":
            # char literal ('a', '\n', '\u{..}') vs lifetime ('a)
            m = re.match(r"'(\\.[^']*|[^'\\])'", text[i:])
            if m:
                out.append("' '")
                i += len(m.group(0))
            else:
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def module_of(path, src):
    rel = os.path.relpath(path, src)[:-3].split(os.sep)
    if rel[-1] == "mod":
        rel = rel[:-1]
    if rel == ["lib"] or rel == ["main"]:
        rel = []
    return tuple(rel)


def split_top(s):
    """Split a use-tree group body on top-level commas."""
    parts, depth, cur = [], 0, []
    for ch in s:
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append("".join(cur))
            cur = []
        else:
            cur.append(ch)
    parts.append("".join(cur))
    return [p.strip() for p in parts if p.strip()]


def expand_use(tree, prefix=()):
    """Expand a use tree into (segments, leaf) paths; leaf is the last segment or '*'."""
    tree = tree.strip()
    tree = re.sub(r"\s+as\s+" + IDENT + r"$", "", tree)
    if tree.startswith("::"):
        tree = tree[2:]
    brace = tree.find("{")
    if brace >= 0:
        head = tree[:brace].rstrip(":").strip()
        segs = prefix + tuple(s for s in head.split("::") if s)
        body = tree[brace + 1:tree.rfind("}")]
        res = []
        for part in split_top(body):
            res.extend(expand_use(part, segs))
        return res
    segs = prefix + tuple(s.strip() for s in tree.split("::") if s.strip())
    if segs and segs[-1] == "self":
        segs = segs[:-1]
    return [segs] if segs else []


class Crate:
    def __init__(self, src):
        self.src = src
        self.files = {}
        for root, dirs, files in os.walk(src):
            rel = os.path.relpath(root, src)
            if rel == "bin" or rel.startswith("bin" + os.sep):
                continue
            for f in files:
                if f.endswith(".rs"):
                    p = os.path.join(root, f)
                    self.files[module_of(p, src)] = p
        self.code = {m: strip_code(open(p, encoding="utf-8").read()) for m, p in self.files.items()}
        self.modules = set(self.files)
        for m in list(self.files):
            for (_s, _e, path) in self.inline_blocks(m):
                self.modules.add(m + path)
                self.files.setdefault(m + path, self.files[m])
        self.uses = {m: list(self.find_uses(m)) for m in self.files if m in self.code}
        # Re-exports: module -> {name: (target path segments, is_glob)}
        self.reexports = defaultdict(dict)
        self.globs = defaultdict(list)
        for m, items in self.uses.items():
            for (_pos, inline, is_pub, segs) in items:
                if not is_pub or inline:
                    continue
                absolute = self.absolute(m, (), segs)
                if absolute is None:
                    continue
                if segs[-1] == "*":
                    self.globs[m].append(absolute[:-1])
                else:
                    self.reexports[m][segs[-1]] = absolute

    def inline_blocks(self, m):
        """List of (start, end, path) of the inline `mod name {` blocks in file module m's
        code; path is the inline module's path below m (nested blocks give longer paths)."""
        code = self.code[m]
        blocks = []
        for mt in re.finditer(r"\bmod\s+(" + IDENT + r")\s*\{", code):
            depth, j = 1, mt.end()
            while j < len(code) and depth:
                if code[j] == "{":
                    depth += 1
                elif code[j] == "}":
                    depth -= 1
                j += 1
            blocks.append((mt.start(), j, mt.group(1)))
        return [
            (s, e, tuple(n for (s2, e2, n) in blocks if s2 <= s and e <= e2))
            for (s, e, _n) in blocks
        ]

    def find_uses(self, m):
        """Yield (pos, inline_mod_path, is_pub, segments) for every path in m's code."""
        code = self.code[m]
        blocks = self.inline_blocks(m)

        def inline_at(pos):
            inside = [path for (s, e, path) in blocks if s < pos < e]
            return max(inside, key=len) if inside else ()

        spans = []
        for mt in re.finditer(r"\b(pub(?:\s*\([^)]*\))?\s+)?use\s+([^;]*);", code):
            spans.append((mt.start(), mt.end()))
            inl = inline_at(mt.start())
            for segs in expand_use(mt.group(2)):
                yield (mt.start(), inl, bool(mt.group(1)), segs)
        for mt in re.finditer(r"(?<![A-Za-z0-9_:])((?:crate|super|self)(?:\s*::\s*(?:super|" + IDENT + r"))+)", code):
            if any(s <= mt.start() < e for (s, e) in spans):
                continue
            segs = tuple(x.strip() for x in mt.group(1).split("::"))
            yield (mt.start(), inline_at(mt.start()), False, segs)

    def absolute(self, m, inline, segs):
        """Absolute segment list of a path written in module m (inside inline mods), or None."""
        cur = list(m) + list(inline)
        segs = list(segs)
        if not segs:
            return None
        if segs[0] == "crate":
            return tuple(segs[1:])
        if segs[0] in ("super", "self"):
            while segs and segs[0] in ("super", "self"):
                if segs[0] == "super":
                    if not cur:
                        return None
                    cur.pop()
                segs.pop(0)
            return tuple(cur) + tuple(segs)
        # relative: a child module of the current (file) module
        if tuple(cur) + (segs[0],) in self.modules or (not inline and tuple(m) + (segs[0],) in self.modules):
            return tuple(cur) + tuple(segs)
        return None

    def resolve(self, absolute, seen=None):
        """Module that defines the item at an absolute path (following re-exports)."""
        seen = seen or set()
        k = len(absolute)
        while k > 0 and tuple(absolute[:k]) not in self.modules:
            k -= 1
        mod = tuple(absolute[:k])
        rest = absolute[k:]
        if not rest or rest[0] == "*" or (mod, rest[0]) in seen:
            return mod
        seen.add((mod, rest[0]))
        target = self.reexports[mod].get(rest[0])
        if target is not None:
            return self.resolve(target + tuple(rest[1:]), seen)
        for g in self.globs[mod]:
            gm = self.resolve(g, seen)
            if rest[0] in self.defined_names(gm):
                return self.resolve(gm + tuple(rest), seen)
        return mod

    def defined_names(self, m):
        code = self.code.get(m, "")
        return set(re.findall(r"\b(?:fn|struct|enum|trait|type|const|static|mod|union)\s+(" + IDENT + r")", code)) | set(self.reexports[m])

    def graph(self):
        edges = defaultdict(dict)  # src -> dst -> first line
        for f in self.uses:
            code = self.code[f]
            for (pos, inline, is_pub, segs) in self.uses[f]:
                absolute = self.absolute(f, inline, segs)
                if absolute is None:
                    continue
                m = f + inline
                dst = self.resolve(absolute)
                if dst == m:
                    continue
                if is_pub and dst[:len(m)] == m:
                    continue  # a facade's re-export of its own descendant
                line = code.count("\n", 0, pos) + 1
                edges[m].setdefault(dst, line)
        return edges


def sccs(nodes, edges):
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, {}):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            out.append(comp)

    sys.setrecursionlimit(10000)
    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return out


def loop_in(comp, edges):
    """One concrete cycle through a strongly connected component (BFS back to the start)."""
    comp = set(comp)
    start = min(comp)
    prev = {start: None}
    queue = [start]
    while queue:
        v = queue.pop(0)
        for w in sorted(edges.get(v, {})):
            if w not in comp:
                continue
            if w == start:
                path = [v]
                while prev[path[-1]] is not None:
                    path.append(prev[path[-1]])
                return list(reversed(path)) + [start]
            if w not in prev:
                prev[w] = v
                queue.append(w)
    return [start]


def name(m):
    return "crate" + "".join("::" + s for s in m)


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    if len(args) > 1 or any(a not in ("--graph",) for a in argv if a.startswith("--")):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    src = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "host-sim", "src")
    if not os.path.isdir(src):
        print(f"error: {src} is not a directory", file=sys.stderr)
        return 2
    crate = Crate(src)
    edges = crate.graph()
    if "--graph" in argv:
        for m in sorted(edges):
            for d in sorted(edges[m]):
                print(f"{name(m)} -> {name(d)}  ({crate.files[m]}:{edges[m][d]})")
    cycles = sorted((sorted(c) for c in sccs(crate.modules, edges) if len(c) > 1), key=lambda c: c[0])
    if not cycles:
        print(f"no import cycle among {len(crate.modules)} modules of {os.path.normpath(src)}")
        return 0
    for comp in cycles:
        print(f"import cycle among {len(comp)} modules: {', '.join(name(m) for m in comp)}")
        path = loop_in(comp, edges)
        for a, b in zip(path, path[1:]):
            print(f"    {name(a)} -> {name(b)}  ({os.path.relpath(crate.files[a])}:{edges[a][b]})")
    print(f"{len(cycles)} import cycle(s)", file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
