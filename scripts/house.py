#!/usr/bin/env python3
"""The house's measures, from the source alone: import circles between modules (the directories
under src/) and between files, imports against the layers, the functions longer than 120 lines
and the files with more than 550 lines of non-test code. A file imports another when it names
a path (`crate::`, `super::`, `self::`, a child module's) that resolves to it, in a `use` or in
the code, followed through re-exports (`pub use`) to the file that defines the name. Exits 1
when it finds anything.
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

def expand(tree):
    """The paths a `use` tree names: `a::{b, c::{d, e}}` gives a::b, a::c::d, a::c::e."""
    tree = re.sub(r"\s+", "", re.sub(r"\s+as\s+\w+", "", tree))
    m = re.match(r"^([\w:]*?)(::)?\{(.*)\}$", tree)
    if not m:
        return [tree]
    head, inner = m.group(1), m.group(3)
    parts, depth, cur = [], 0, ""
    for ch in inner:
        depth += ch == "{"
        depth -= ch == "}"
        if ch == "," and depth == 0:
            parts.append(cur); cur = ""
        else:
            cur += ch
    parts.append(cur)
    out = []
    for p in filter(None, parts):
        for t in expand(p):
            out.append(head + "::" + t if head and t != "self" else head or t)
    return out

def absolute(mod, path):
    """`path` as written in module `mod`, from the crate's root, or None for a path outside
    the crate (`slideline::` in the binary's files is the crate)."""
    here = mod.split("::") if mod not in ("", "lib", "main") else []
    parts = path.split("::")
    if parts[0] in ("crate", "slideline"):
        return parts[1:]
    if parts[0] == "self":
        return here + parts[1:]
    if parts[0] == "super":
        base = here[:]
        while parts and parts[0] == "super":
            base = base[:-1]
            parts = parts[1:]
        return base + parts
    # a bare path: a child module of this one (`use results::X` in io/mod.rs)
    if "::".join(here + parts[:1]) in files:
        return here + parts
    return None

def resolve(parts, seen=()):
    """The file module that the path `parts` names: its longest file-module prefix, followed
    through that module's re-exports (`pub use`) of the next name (the crate root's first)."""
    if parts and ("", parts[0]) in reexports and ("", parts[0]) not in seen:
        return resolve(reexports[("", parts[0])] + parts[1:], seen + (("", parts[0]),))
    for k in range(len(parts), 0, -1):
        name = "::".join(parts[:k])
        if name in files:
            rest = parts[k:]
            if rest and (name, rest[0]) in reexports and (name, rest[0]) not in seen:
                return resolve(reexports[(name, rest[0])] + rest[1:], seen + ((name, rest[0]),))
            return name
    return None

USE = re.compile(r"^\s*(pub(\([^)]*\))?\s+)?use\s+([^;]+);", re.M)
codes = {mod: code_of(open(path).read()) for mod, path in files.items()}
# the re-exports: (module, name) -> the path it stands for
reexports = {}
for mod, code in codes.items():
    for m in USE.finditer(code):
        if not m.group(1):
            continue
        for p in expand(m.group(3)):
            a = absolute(mod, p)
            if a:
                reexports[("" if mod in ("lib", "main") else mod, p.split("::")[-1])] = a

edges = defaultdict(set)
for mod, code in codes.items():
    paths = []
    for m in USE.finditer(code):
        paths += expand(m.group(3))
    body = USE.sub("", code)
    paths += re.findall(r"\b((?:crate|super|self|slideline)(?:::\w+)+)", body)
    for p in paths:
        a = absolute(mod, p)
        r = resolve(a) if a else None
        if r is not None and r != mod and not mod.startswith(r + "::") and r != "":
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
    ["petsc", "decomposition"],
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

LONGEST_FUNCTION, LARGEST_FILE = 120, 550
print(f"functions above {LONGEST_FUNCTION} lines:")
long = []
for mod, path in sorted(files.items()):
    lines = code_of(open(path).read()).split("\n")
    for i, line in enumerate(lines):
        m = re.match(r"^(\s*)(pub(\([^)]*\))? )?(const )?(unsafe )?(extern \"C\" )?fn (\w+)", line)
        if m and not line.rstrip().endswith(";"):
            indent = len(m.group(1))
            for j in range(i + 1, len(lines)):
                if lines[j].startswith(" " * indent + "}") and len(lines[j]) - len(lines[j].lstrip()) == indent:
                    if j - i + 1 > LONGEST_FUNCTION:
                        long.append(f"  {os.path.relpath(path, src)}: {m.group(7)} {j - i + 1}")
                    break
print("\n".join(long) or "  none")
print(f"files above {LARGEST_FILE} lines before their tests:")
def lines_before_tests(path):
    """Every line before the test module, comments and blank lines too."""
    lines = open(path).read().split("\n")
    return next((i for i, l in enumerate(lines) if l.strip() == "#[cfg(test)]"), len(lines))
big = [(lines_before_tests(p), os.path.relpath(p, src)) for p in files.values()]
print("\n".join(f"  {p}: {n}" for n, p in sorted(big, reverse=True) if n > LARGEST_FILE) or "  none")
found = cycles(modules) or upward or unplaced or cycles(edges) or long or any(n > LARGEST_FILE for n, _ in big)
sys.exit(1 if found else 0)
