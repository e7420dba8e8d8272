#!/usr/bin/env python3
"""Counts the tree's dependency circles and the CLI's option-handling lines, and fails on
a circle that is not in the committed baseline (tests/structure/circles_baseline.txt).

usage: count_structure.py BUILD_DIR [--write-baseline]

A *circle* is a strongly connected component of two or more files (or folders) in the
graph "file A uses a function or object defined in file B" (the structure review,
../shared/reviews/architecture-2026-11.md: "shared helpers that live in a dispatcher
file"). For C the graph is read off the compiled objects (nm: A's undefined global
symbols that B defines), so it sees exactly the links the linker makes: the library
(src/), the CLI (cli/, with the MPI build's objects when present). For the Python
package (python/geardyn/) it is the import graph, imports inside functions included.
Circles are counted inside folders (the files of one folder) and across folders (the
folders, joined by any file edge between them).

*Option-handling lines* are the lines of cli/*.c that declare or parse command-line
options: each `struct option` table, each getopt_long loop (from its `while` to the
closing brace) and each usage text (a `USAGE` string constant); in the table form
(cli/options.h) each option table (`gd_cli_opt NAME[]`) and command (`gd_cli_command
NAME`) with its help text, the `#define F(m) offsetof` shorthand, and each call of
gd_cli_parse with the line after it (its return); and the shared parser itself
(cli/options.c and cli/options.h, their lines of code: neither blank nor comment).

Prints both counts and the circles; exit 1 when a circle is not in the baseline (the
baseline names each circle by its sorted members, so a circle that grows also fails).
"""
import os
import re
import subprocess
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
BASELINE = os.path.join(ROOT, "tests", "structure", "circles_baseline.txt")


def object_files(build):
    """source path (relative to ROOT) -> list of object files compiled from it"""
    objs = {}
    cm = os.path.join(build, "CMakeFiles")
    for target in ("geardyn_objects.dir", "geardyn_cli.dir", "geardyn_mpi.dir"):
        top = os.path.join(cm, target)
        for dirpath, _, files in os.walk(top):
            for f in files:
                if f.endswith(".c.o"):
                    rel = os.path.relpath(os.path.join(dirpath, f), top)[: -len(".o")]
                    if rel.startswith(("src" + os.sep, "cli" + os.sep)):
                        objs.setdefault(rel, []).append(os.path.join(dirpath, f))
    return objs


def c_edges(build):
    objs = object_files(build)
    if not objs:
        sys.exit("count_structure: no objects under %s/CMakeFiles (build first)" % build)
    defined = {src: set() for src in objs}
    used = {src: set() for src in objs}
    source_of = {p: src for src, paths in objs.items() for p in paths}
    # one nm over every object: "file: [address] type name" per symbol
    out = subprocess.run(["nm", "-A"] + sorted(source_of), capture_output=True, text=True,
                         check=True).stdout
    for line in out.splitlines():
        path, _, rest = line.partition(":")
        parts = rest.split()
        src = source_of.get(path)
        if src is None:
            continue
        if len(parts) == 3 and parts[1] in "TDBRCGSV":
            defined[src].add(parts[2])
        elif len(parts) == 2 and parts[0] == "U":
            used[src].add(parts[1])
    owner = {}
    for src, syms in defined.items():
        for s in syms:
            owner.setdefault(s, set()).add(src)
    edges = {src: set() for src in objs}
    for src, syms in used.items():
        for s in syms:
            for o in owner.get(s, ()):
                if o != src:
                    edges[src].add(o)
    return edges


IMPORT_RE = re.compile(r"^\s*(?:from\s+(\.+\w*|geardyn(?:\.\w+)?)\s+import\s+([\w, ()]+)|"
                       r"import\s+geardyn\.(\w+))")


def python_edges():
    pkg = os.path.join(ROOT, "python", "geardyn")
    edges = {}
    if not os.path.isdir(pkg):
        return edges
    mods = {f[:-3] for f in os.listdir(pkg) if f.endswith(".py")}
    for m in mods:
        src = os.path.join("python", "geardyn", m + ".py")
        edges[src] = set()
        with open(os.path.join(ROOT, src), encoding="utf-8") as fh:
            for line in fh:
                mt = IMPORT_RE.match(line)
                if not mt:
                    continue
                targets = []
                if mt.group(3):
                    targets.append(mt.group(3))
                else:
                    base = mt.group(1).lstrip(".").replace("geardyn", "", 1).lstrip(".")
                    if base:
                        targets.append(base)
                    else:  # from . import a, b
                        targets += [t.strip("() ") for t in mt.group(2).split(",")]
                for t in targets:
                    if t in mods and t != m:
                        edges[src].add(os.path.join("python", "geardyn", t + ".py"))
    return edges


def sccs(nodes, edges):
    """Tarjan's strongly connected components (iterative), those of 2 or more nodes."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]
    for root in sorted(nodes):
        if root in index:
            continue
        work = [(root, iter(sorted(edges.get(root, ()))))]
        index[root] = low[root] = counter[0]
        counter[0] += 1
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in nodes:
                    continue
                if w not in index:
                    index[w] = low[w] = counter[0]
                    counter[0] += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(edges.get(w, ())))))
                    advanced = True
                    break
                if w in on:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return sorted(out)


def circles(edges):
    inside = []
    folders = sorted({os.path.dirname(f) for f in edges})
    for folder in folders:
        members = {f for f in edges if os.path.dirname(f) == folder}
        inside += sccs(members, {f: edges[f] & members for f in members})
    fedges = {}
    for f, targets in edges.items():
        for t in targets:
            a, b = os.path.dirname(f), os.path.dirname(t)
            if a != b:
                fedges.setdefault(a, set()).add(b)
    across = sccs(set(folders), fedges)
    return inside, across


INFRA = ("options.c", "options.h")  # the table-driven parser, counted by its lines of code


def code_lines(lines):
    """lines that are neither blank nor inside or wholly a comment"""
    n, in_comment = 0, False
    for ln in lines:
        t = ln.strip()
        if in_comment:
            in_comment = "*/" not in t
            rest = t.split("*/", 1)[1].strip() if "*/" in t else ""
            n += bool(rest)
            continue
        if t.startswith("/*"):
            in_comment = "*/" not in t
            n += bool(t.split("*/", 1)[1].strip()) if "*/" in t else 0
            continue
        n += bool(t) and not t.startswith("//")
    return n


BLOCK_RE = re.compile(r"struct option\s+\w+\[\]\s*=|while\s*\(\s*\(?\w+\s*=\s*getopt_long|"
                      r"\bgd_cli_opt\s+\w+\[\]\s*=|\bgd_cli_command\s+\w+\s*=")


def option_lines():
    total, per = 0, {}
    cli = os.path.join(ROOT, "cli")
    for name in sorted(os.listdir(cli)):
        if not name.endswith(".c") and name not in INFRA:
            continue
        with open(os.path.join(cli, name), encoding="utf-8") as fh:
            lines = fh.read().split("\n")
        if name in INFRA:
            per[name] = code_lines(lines)
            total += per[name]
            continue
        mark = [False] * len(lines)
        i = 0
        while i < len(lines):
            ln = lines[i]
            if BLOCK_RE.search(ln):
                depth, j, opened = 0, i, False
                while j < len(lines):
                    depth += lines[j].count("{") - lines[j].count("}")
                    opened = opened or "{" in lines[j]
                    mark[j] = True
                    if opened and depth <= 0:
                        break
                    j += 1
                i = j + 1
                continue
            if re.search(r"\bUSAGE\w*\s*(\[\s*\])?\s*=", ln):
                j = i
                while j < len(lines):
                    mark[j] = True
                    if lines[j].rstrip().endswith(";"):
                        break
                    j += 1
                i = j + 1
                continue
            if re.match(r"#define F\(m\) offsetof", ln):
                mark[i] = True
            elif re.search(r"\bgd_cli_parse\(", ln):
                j = i
                while j + 1 < len(lines) and not lines[j].rstrip().endswith(";"):
                    mark[j] = True
                    j += 1
                mark[j] = True
                if j + 1 < len(lines):
                    mark[j + 1] = True  # its return
                i = j + 2
                continue
            i += 1
        n = sum(mark)
        if n:
            per[name] = n
        total += n
    return total, per


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    build = sys.argv[1]
    edges = c_edges(build)
    edges.update(python_edges())
    inside, across = circles(edges)
    total, per = option_lines()
    names = ["inside " + " ".join(c) for c in inside] + ["across " + " ".join(c) for c in across]
    print("include circles: %d inside folders, %d across folders" % (len(inside), len(across)))
    for n in names:
        print("  " + n)
    print("CLI option-handling lines: %d in %d files (%s)" %
          (total, len(per), ", ".join("%s %d" % kv for kv in sorted(per.items()))))
    if "--write-baseline" in sys.argv:
        with open(BASELINE, "w", encoding="utf-8") as fh:
            fh.write("# Dependency circles known on the day the check came in (count_structure.py);\n"
                     "# remove a line when its circle is broken, never add one.\n")
            for n in names:
                fh.write(n + "\n")
        return 0
    known = set()
    if os.path.exists(BASELINE):
        with open(BASELINE, encoding="utf-8") as fh:
            known = {ln.strip() for ln in fh if ln.strip() and not ln.startswith("#")}
    new = [n for n in names if n not in known]
    if new:
        print("NEW circles (not in %s): break them, do not add them:" %
              os.path.relpath(BASELINE, ROOT))
        for n in new:
            print("  " + n)
        return 1
    gone = sorted(known - set(names))
    if gone:
        print("broken since the baseline (remove these lines from the baseline):")
        for n in gone:
            print("  " + n)
    return 0


if __name__ == "__main__":
    sys.exit(main())
