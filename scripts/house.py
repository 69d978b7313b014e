#!/usr/bin/env python3
"""The house's measures, from the source alone: import circles between modules (the directories
under src/) and between files, the functions longer than 150 lines and the files with more than
600 lines of non-test code. A file imports another when it names a path under `crate::`
(a `use` or a path in the code) that resolves to it.
    scripts/house.py [src]"""
import os, re, sys
from collections import defaultdict

src = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "src")
src = os.path.normpath(src)
files = {}
for root, _, names in os.walk(src):
    for n in names:
        if n.endswith(".rs"):
            path = os.path.join(root, n)
            rel = os.path.relpath(path, src)[:-3]
            parts = rel.split(os.sep)
            if parts[-1] == "mod":
                parts = parts[:-1]
            files["::".join(parts)] = path

def code_of(text):
    """The text before the first `#[cfg(test)]` module, comments removed."""
    cut = re.search(r"^#\[cfg\(test\)\]\s*\nmod tests", text, re.M)
    text = text[: cut.start()] if cut else text
    return re.sub(r"//[^\n]*", "", text)

def resolve(path):
    """The longest file module that `path` (a::b::c) names."""
    parts = path.split("::")
    while parts:
        name = "::".join(parts)
        if name in files:
            return name
        parts = parts[:-1]
    return None

edges = defaultdict(set)
for mod, path in files.items():
    code = code_of(open(path).read())
    # use crate::a::{b, c::d}; and crate::a::b paths in code; super:: relative to the module
    for m in re.finditer(r"crate::([\w:]+)(::\{([^;]*?)\})?", code):
        base = m.group(1).rstrip(":")
        targets = [base]
        if m.group(3):
            targets = [base + "::" + t.strip().split(" as ")[0].split("::{")[0] for t in re.split(r",(?![^{]*\})", m.group(3)) if t.strip()]
        for t in targets:
            r = resolve(t)
            if r and r != mod:
                edges[mod].add(r)
    for m in re.finditer(r"\bsuper::([\w:]+)", code):
        parent = mod.split("::")[:-1] if not path.endswith("mod.rs") else mod.split("::")
        parent = parent[:-1] if path.endswith("mod.rs") else parent
        r = resolve("::".join(parent + [m.group(1)]))
        if r and r != mod and not mod.startswith(r + "::"):
            edges[mod].add(r)

def cycles(graph):
    """Strongly connected components with more than one member (Tarjan)."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]
    sys.setrecursionlimit(10000)
    def visit(v):
        index[v] = low[v] = counter[0]; counter[0] += 1; stack.append(v); on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w); low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop(); on.discard(w); comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))
    for v in list(graph):
        if v not in index:
            visit(v)
    return out

top = lambda m: m.split("::")[0]
modules = defaultdict(set)
for a, bs in edges.items():
    for b in bs:
        if top(a) != top(b):
            modules[top(a)].add(top(b))
print("import circles between modules (directories):")
for c in cycles(modules) or [["none"]]:
    print("  " + " <-> ".join(c))
    for a in c:
        for b in sorted(modules[a] & set(c)):
            why = sorted(f"{x} -> {y}" for x, ys in edges.items() if top(x) == a for y in ys if top(y) == b)
            print(f"     {a} -> {b}: {', '.join(why[:6])}{' ...' if len(why) > 6 else ''}")
# the layers (docs/code.md), lowest first: a module imports only from its own layer or below
LAYERS = [
    ["error", "output_path", "ad", "interrupt", "launch"],
    ["fe", "material", "element"],
    ["model"],
    ["contact"],
    ["records", "assessment"],
    ["petsc", "dist"],
    ["io"],
    ["solve", "preprocess"],
    ["bellows", "post", "study", "dba"],
    ["main", "cli", "lib"],
]
level = {m: k for k, layer in enumerate(LAYERS) for m in layer}
print("imports against the layers (docs/code.md):")
upward = sorted(f"{a} -> {b}" for a, bs in modules.items() for b in bs if level.get(a, 99) < level.get(b, 99))
unplaced = sorted({top(m) for m in files} - set(level))
print("\n".join("  " + u for u in upward) or "  none")
if unplaced:
    print("  modules in no layer: " + ", ".join(unplaced))
print("import circles between files:")
for c in cycles(edges):
    print(f"  ({len(c)}) " + ", ".join(c))
if not cycles(edges):
    print("  none")

print("functions above 150 lines:")
long = []
for mod, path in sorted(files.items()):
    lines = code_of(open(path).read()).split("\n")
    for i, line in enumerate(lines):
        m = re.match(r"^(\s*)(pub(\([^)]*\))? )?(const )?(unsafe )?(extern \"C\" )?fn (\w+)", line)
        if m and not line.rstrip().endswith(";"):
            indent = len(m.group(1))
            for j in range(i + 1, len(lines)):
                if lines[j].startswith(" " * indent + "}") and len(lines[j]) - len(lines[j].lstrip()) == indent:
                    if j - i + 1 > 150:
                        long.append(f"  {os.path.relpath(path, src)}: {m.group(7)} {j - i + 1}")
                    break
print("\n".join(long) or "  none")
print("files above 600 lines before their tests:")
def lines_before_tests(path):
    """Every line before the test module, comments and blank lines too."""
    lines = open(path).read().split("\n")
    return next((i for i, l in enumerate(lines) if l.strip() == "#[cfg(test)]"), len(lines))
big = [(lines_before_tests(p), os.path.relpath(p, src)) for p in files.values()]
print("\n".join(f"  {p}: {n}" for n, p in sorted(big, reverse=True) if n > 600) or "  none")
