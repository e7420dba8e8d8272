#!/usr/bin/env python3
"""Every `geardyn ...` command line shown to a user runs (issue 35 item 6): the command
lines of the examples' headers (examples/**/*.yaml: `# Run:  geardyn ...`, indented
`#   geardyn ...` lines and `geardyn ...` in backticks, `\\` continuing a line) and of the
docs' code blocks (docs/*.md: lines starting `geardyn ` or `$ geardyn `, `\\` continuing),
each run with the build's program from a scratch folder holding copies of the source
tree's examples/, tests/ and bench/ (so a `--out`, a `--plot` or a study's folder lands
in the scratch folder), and
must exit 0 within TIMEOUT seconds.

Not run, and listed: a synopsis (a placeholder such as MODEL, FILE, DIR, WHAT, FROM:TO:COUNT
in capitals, `...`, or `A|B`); a line naming a model file that is not in the tree
(rig.yaml, gearbox.yaml: the docs' examples of messages about the user's own files); a
line marked slow, by `# slow` after the command (in a code block) or `(slow)` (in a
header): the marker documents that the command takes minutes; `geardyn SUBCOMMAND` alone
(a command named in prose). A line marked `# exit 2` shows an input error: it must exit 2. Optional arguments in
square brackets (`[--helix-angle "15 deg"]`) are dropped.

Also the docs' headings: none repeated within a file, no bold run-in heading doubled.

usage: check_doc_commands.py GEARDYN [TIMEOUT]
"""
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
PLACEHOLDER = re.compile(r"\b[A-Z][A-Z_]{2,}\b|\.\.\.|\w\|\w")


def joined(lines):
    """lines with a trailing backslash joined to the next"""
    out, cur = [], ""
    for line in lines:
        if line.rstrip().endswith("\\"):
            cur += line.rstrip()[:-1] + " "
        else:
            out.append(cur + line)
            cur = ""
    if cur:
        out.append(cur)
    return out


def from_yaml(path):
    head = []
    for line in open(path, encoding="utf-8"):
        if not line.startswith("#"):
            break
        head.append(line[1:].rstrip("\n"))
    cmds = []
    for line in joined(head):
        s = line.strip()
        s = re.sub(r"^Run:\s*", "", s)
        if s.startswith("geardyn "):
            cmds.append(s)
    # `geardyn ...` in backticks, possibly across lines
    text = " ".join(h.strip() for h in head)
    cmds += [m.group(1) for m in re.finditer(r"`(geardyn [a-z][^`]*)`", text)]
    return cmds


def from_md(path):
    cmds, inblock, block = [], False, []
    for line in open(path, encoding="utf-8"):
        if line.startswith("```"):
            if inblock:
                for b in joined(block):
                    s = b.strip()
                    if s.startswith("$ "):
                        s = s[2:]
                    if s.startswith("geardyn ") and not s.startswith("geardyn study:"):
                        cmds.append(s)
            inblock, block = not inblock, []
            continue
        if inblock:
            block.append(line.rstrip("\n"))
    return cmds


def classify(cmd):
    """(args or None, why it is not run; or the exit code it must give, 0 or 2)"""
    if re.search(r"#\s*slow\b|\(slow\)", cmd):
        return None, "marked slow"
    want = 2 if re.search(r"#\s*exit 2\b", cmd) else 0
    cmd = re.sub(r"\s+#.*$", "", cmd)  # a comment after the command
    cmd = re.sub(r"\s+\[-[^\]]*\]", "", cmd)  # optional arguments: [--opt ...]
    try:
        args = shlex.split(cmd)
    except ValueError:
        return None, "not a shell line"
    if PLACEHOLDER.search(" ".join(args[1:])):
        return None, "synopsis"
    if len(args) < 3:
        return None, "a command named in prose"
    for a in args[2:]:
        if re.search(r"\.(yaml|yml|csv|uff|unv)$", a) and not a.startswith("-") and \
                not os.path.exists(os.path.join(ROOT, a)):
            return None, "names a file not in the tree (%s)" % a
    return args[1:], want


def repeated_headings():
    """docs/*.md: a heading given twice in one file, or a bold run-in heading doubled
    (`**Tracking.****Tracking.**`, issue 35)"""
    bad = []
    for p in sorted(glob.glob(os.path.join(ROOT, "docs", "*.md"))):
        seen, inblock = set(), False
        for n, line in enumerate(open(p, encoding="utf-8"), 1):
            if line.startswith("```"):
                inblock = not inblock
            if inblock:
                continue
            if re.match(r"#{1,6} ", line):
                h = line.strip()
                if h in seen:
                    bad.append("%s:%d: heading repeated: %s" % (os.path.relpath(p, ROOT), n, h))
                seen.add(h)
            m = re.search(r"\*\*([^*]+)\*\*\s*\*\*\1\*\*", line)
            if m:
                bad.append("%s:%d: heading doubled: %s" % (os.path.relpath(p, ROOT), n, m.group(0)))
    return bad


def main():
    gd = os.path.abspath(sys.argv[1])
    dup = repeated_headings()
    for b in dup:
        print("FAIL  " + b)
    timeout = float(sys.argv[2]) if len(sys.argv) > 2 else 120
    found = []
    for p in sorted(glob.glob(os.path.join(ROOT, "examples", "**", "*.yaml"), recursive=True)):
        found += [(os.path.relpath(p, ROOT), c) for c in from_yaml(p)]
    for p in sorted(glob.glob(os.path.join(ROOT, "docs", "*.md"))):
        found += [(os.path.relpath(p, ROOT), c) for c in from_md(p)]
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    bad = ran = 0
    with tempfile.TemporaryDirectory() as tmp:
        # copies, not links: a study writes its folder beside its file
        for d in ("examples", "tests", "bench"):
            shutil.copytree(os.path.join(ROOT, d), os.path.join(tmp, d),
                            ignore=shutil.ignore_patterns("*.out", "__pycache__"))
        for where, cmd in found:
            args, why = classify(cmd)
            want = why if args is not None else 0
            if args is None:
                print("skip  %s: %s  (%s)" % (where, cmd, why))
                continue
            t0 = time.time()
            try:
                r = subprocess.run([gd] + args, cwd=tmp, env=env, capture_output=True,
                                   text=True, timeout=timeout)
                code, err = r.returncode, r.stderr
            except subprocess.TimeoutExpired:
                code, err = "timeout", "over %g s: mark it '# slow' or shorten it" % timeout
            ran += 1
            dt = time.time() - t0
            if code != want:
                bad += 1
                print("FAIL  %s: %s  (exit %s, %.1f s)\n      %s" % (
                    where, cmd, code, dt, (err or "").strip().replace("\n", "\n      ")[:600]))
            else:
                print("ok    %s: %s  (%.1f s)" % (where, cmd, dt))
    print("doc commands: %d run, %d failed, %d not run; %d repeated headings" % (
        ran, bad, len(found) - ran, len(dup)))
    return 1 if bad or dup else 0


sys.exit(main())
