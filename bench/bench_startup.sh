#!/usr/bin/env bash
# Start-up and small problems (issue 35 item 2): the wall time of a whole process, best
# of N runs, for `geardyn --version`, `check` and `modal` of small models, against
# /bin/true measured the same way in the same run (the floor: fork, exec and the
# timer), and Python's `import geardyn` against `import numpy` (which it imports on
# first use only). Prints each time, its excess over the floor and the ratio to it.
# The shared libraries each process maps are counted too (ldd): the dynamic loader is
# most of a small run, so the instructions of `geardyn --version` are counted too
# (valgrind callgrind: the same on any machine, whatever else runs), and each run's CPU
# time (user + system, best of N, as bench_ross.sh times geardyn) and minor page faults
# (fewest of N): the kernel's share of a small run (exec, mapping, first touch of each
# page) that instructions do not see. One thread (OPENBLAS_NUM_THREADS=1,
# OMP_NUM_THREADS=1), as the project's other benchmarks.
# With a second build folder (e.g. one of an older commit), its program is timed too,
# the runs of the two interleaved (the machine may be shared), and the ratio printed.
# usage: bench_startup.sh [BUILD] [N] [OTHER_BUILD]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
N=${2:-40}
OTHER=${3:-}
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
# geardyn carries the library unless built with GD_STATIC_CLI=OFF (CMakeLists.txt)
mapped() { # BUILD
    local n
    n=$(ldd "$1/geardyn" | wc -l)
    if ldd "$1/geardyn" | grep -q 'libgeardyn\.so'; then
        echo "geardyn $n (with libgeardyn.so), libgeardyn.so $(ldd "$1/libgeardyn.so" | wc -l)"
    else
        echo "geardyn $n (the library inside it), libgeardyn.so $(ldd "$1/libgeardyn.so" 2>/dev/null | wc -l)"
    fi
}
echo "libraries mapped: $(mapped "$B")"
[ -z "$OTHER" ] || echo "libraries mapped ($OTHER): $(mapped "$OTHER")"
/usr/bin/python3 - "$B" "$N" "$OTHER" <<'PY'
import os, subprocess, sys, time
B, N, OTHER = sys.argv[1], int(sys.argv[2]), sys.argv[3]

CPU = {}  # command -> [best CPU time (user + system), fewest minor page faults]
def once(cmd, env=None):
    """wall time of one run; its CPU time and page faults kept in CPU"""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
    _, st, ru = os.wait4(p.pid, 0)
    t = time.perf_counter() - t0
    if st:
        raise SystemExit("failed: " + " ".join(cmd))
    c = CPU.setdefault(tuple(cmd), [float("inf"), 1 << 60])
    c[0] = min(c[0], ru.ru_utime + ru.ru_stime)
    c[1] = min(c[1], ru.ru_minflt)
    return t

def best(cmd, env=None):
    return min(once(cmd, env) for _ in range(N))

def cpu(cmd):
    c = CPU[tuple(cmd)]
    return "CPU %5.2f ms, %4d page faults" % (c[0] * 1e3, c[1])

floor = best(["/bin/true"])
print("floor /bin/true: %.2f ms (best of %d); %s" % (floor * 1e3, N, cpu(["/bin/true"])))
gd = os.path.join(B, "geardyn")
def best2(a, b):
    """best of N of each, interleaved"""
    ta = tb = float("inf")
    for _ in range(N):
        for cmd, which in ((a, 0), (b, 1)):
            t = once(cmd)
            if which == 0:
                ta = min(ta, t)
            else:
                tb = min(tb, t)
    return ta, tb

RUNS = [
    ("geardyn --version", ["--version"]),
    ("geardyn check examples/kumar2011_coupled.yaml (8 DOFs)", ["check", "examples/kumar2011_coupled.yaml"]),
    ("geardyn modal examples/kumar2011_coupled.yaml (8 DOFs)", ["modal", "examples/kumar2011_coupled.yaml"]),
    ("geardyn modal bench/models/ross_example42.yaml --speed 3000rpm --modes 12 (42 DOFs)", ["modal", "bench/models/ross_example42.yaml", "--speed", "3000rpm", "--modes", "12"]),
    ("geardyn modal examples/rig2018.yaml --speed 3000rpm (170 DOFs)", ["modal", "examples/rig2018.yaml", "--speed", "3000rpm"]),
    ("geardyn modal bench/models/rig366.yaml --speed 3000rpm --modes 12 (366 DOFs)", ["modal", "bench/models/rig366.yaml", "--speed", "3000rpm", "--modes", "12"]),
]
for label, args in RUNS:
    if OTHER:
        t, t2 = best2([gd] + args, [os.path.join(OTHER, "geardyn")] + args)
        print("%-80s %7.2f ms  (floor + %6.2f ms, %5.1fx the floor); %s: %7.2f ms, %.2fx this" % (
            label, t * 1e3, (t - floor) * 1e3, t / floor, OTHER, t2 * 1e3, t2 / t))
        print("%-80s %s; %s: %s" % ("", cpu([gd] + args), OTHER, cpu([os.path.join(OTHER, "geardyn")] + args)))
    else:
        t = best([gd] + args)
        print("%-80s %7.2f ms  (floor + %6.2f ms, %5.1fx the floor); %s" % (
            label, t * 1e3, (t - floor) * 1e3, t / floor, cpu([gd] + args)))

# The instructions of each run (valgrind's callgrind, when installed): the same count on
# any machine and under any load (a wall time on a shared machine is not); for --version
# and the 8-DOF runs nearly all of them the dynamic loader's binding of symbols.
def instructions(cmd):
    try:
        out = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null"] + cmd,
                             capture_output=True, text=True)
    except OSError:
        return None
    for line in out.stderr.splitlines():
        if "Collected :" in line:
            return int(line.split()[-1])
    return None
nt = instructions(["/bin/true"])
if nt:
    print("instructions (callgrind): /bin/true %.2f million" % (nt / 1e6))
    for label, args in RUNS:
        ni = instructions([gd] + args)
        line = "  %-76s %8.2f million" % (label, ni / 1e6)
        no = instructions([os.path.join(OTHER, "geardyn")] + args) if OTHER else None
        if no:
            line += "; %s: %8.2f million, %.1fx this" % (OTHER, no / 1e6, no / ni)
        print(line)

# Python: the import alone, timed inside the interpreter (best of N processes)
env = dict(os.environ, PYTHONPATH="python", GEARDYN_BUILD=B)
def import_time(stmt):
    code = "import time; t = time.perf_counter(); %s; print(time.perf_counter() - t)" % stmt
    t = float("inf")
    for _ in range(N // 4 or 1):
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
        if out.returncode:
            return None, out.stderr.strip().splitlines()[-1] if out.stderr else "failed"
        t = min(t, float(out.stdout))
    return t, ""
tn, _ = import_time("import numpy")
tg, why = import_time("import geardyn")
if tg is None:
    print("python import geardyn: not measured (%s; run 'make python')" % why)
else:
    print("python import numpy:   %7.2f ms" % (tn * 1e3))
    print("python import geardyn: %7.2f ms  (numpy is imported on the first result array, python/geardyn/_numpy.py)" % (tg * 1e3))
PY
