#!/usr/bin/env bash
# ROSS side by side (issue 35): modal and the default transient of the two benchmark
# rotors, geardyn as a whole process (start-up, model file and output included) against
# ROSS in its own Python process after `import ross` (bench/ross_side_by_side.py), CPU
# time (user + system; the machine may be shared), best of N.
#   ross42: ROSS's rotor_example() = bench/models/ross_example42.yaml (42 DOFs)
#   rig366: bench/models/rig366(_unbalance).yaml = the same rig as a ROSS MultiRotor
# Modal: 12 modes at 3000 rpm. Transient: unbalance from rest, 0.1 s every 1e-4 s, the
# record at the unbalanced disk (disk0.x, gear48.x); error = largest difference over the
# 1001 samples / peak, against the linear method at rtol 1e-10 (geardyn's own reference:
# CVODE BDF at rtol 1e-9 agrees with it to 8.6e-9 on rig366 since the (8,8) increment
# form, docs/transient.md; the (4,4) form was 4.1e-6 off); ROSS's Newmark and its
# default (scipy's lsim) against the same reference (on rig366 only a difference: ROSS's
# MultiRotor has no mesh damping, so its transient is of a slightly different model;
# issue 23 measured ROSS's Newmark there at 1.7 s, error 1.6e-2, on the same matrices).
# ROSS is not a dependency: ROSS_PATH must hold ROSS 2.3's source (its `ross` package),
# which needs Debian's python3-numpy, -scipy, -pandas, -plotly, -numba, -pint, -toml,
# -prettytable, -xlrd; bench/ross_stubs stands in for methodtools, ccp and control (not
# packaged; not used by these rotors). Without ROSS the geardyn side still runs.
# usage: bench_ross.sh BUILD [N]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
N=${2:-10}
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
PY=/usr/bin/python3
if [ -n "${ROSS_PATH:-}" ] && PYTHONPATH="$ROSS_PATH:bench/ross_stubs" "$PY" -c "import ross" 2>/dev/null; then
    PYTHONPATH="$ROSS_PATH:bench/ross_stubs" "$PY" bench/ross_side_by_side.py "$tmp" 5 2>/dev/null \
        | grep -v '^Running' | tee "$tmp/ross.txt"
else
    echo "ROSS not importable (set ROSS_PATH to ROSS 2.3's source): geardyn side only"
    : > "$tmp/ross.txt"
fi
"$PY" - "$B" "$N" "$tmp" <<'PY'
import os, re, subprocess, sys
import numpy as np
B, N, tmp = sys.argv[1], int(sys.argv[2]), sys.argv[3]
gd = os.path.join(B, "geardyn")

FAULTS = {}  # the fewest minor page faults of each command's runs
def cpu(args, n=N):
    best = float("inf")
    for _ in range(n):
        p = subprocess.Popen([gd] + args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        _, st, ru = os.wait4(p.pid, 0)
        if st:
            raise SystemExit("failed: geardyn " + " ".join(args))
        best = min(best, ru.ru_utime + ru.ru_stime)
        k = " ".join(args)
        FAULTS[k] = min(FAULTS.get(k, 1 << 60), ru.ru_minflt)
    return best

ross = open(os.path.join(tmp, "ross.txt")).read()
def ross_time(pat):
    m = re.search(pat + r": ([0-9.]+) s CPU", ross)
    return float(m.group(1)) if m else None

floor = cpu(["--version"])
print("floor: geardyn --version %.2f ms CPU (best of %d), %d page faults" % (
    floor * 1e3, N, FAULTS["--version"]))
cases = [("ross42", "bench/models/ross_example42.yaml", "bench/models/ross_example42.yaml", "disk0.x"),
         ("rig366", "bench/models/rig366.yaml", "bench/models/rig366_unbalance.yaml", "gear48.x")]
for name, mmodel, tmodel, rec in cases:
    margs = ["modal", mmodel, "--speed", "3000rpm", "--modes", "12"]
    t = cpu(margs)
    r = ross_time(name + r" modal 12 modes at 3000 rpm")
    print("%s modal 12 modes: geardyn %.2f ms CPU (whole process, %d page faults)%s" % (
        name, t * 1e3, FAULTS[" ".join(margs)],
        "; ROSS %.2f ms: %.1fx ROSS" % (r * 1e3, r / t) if r else ""))
    base = [tmodel, "--speed", "3000rpm", "--duration", "0.1", "--from", "0",
            "--output-interval", "0.1ms", "--record", rec, "--quiet"]
    ref = os.path.join(tmp, name + "_ref")
    subprocess.run([gd, "transient"] + base + ["--rtol", "1e-10", "--out", ref], check=True,
                   stdout=subprocess.DEVNULL)
    x = np.genfromtxt(os.path.join(ref, "records.csv"), delimiter=",", skip_header=1)[:, 1]
    pk = np.max(np.abs(x))
    rn = ross_time(name + r" time response 0.1 s, 1001 samples, newmark")
    rl = ross_time(name + r" time response 0.1 s, 1001 samples, default")
    for m in ("newmark", "default"):
        f = os.path.join(tmp, "%s_%s.txt" % (name, m))
        if os.path.exists(f):
            y = np.loadtxt(f)[:, 1]
            # ROSS's MultiRotor has no mesh damping (geardyn's rig: 1.8e3 N s/m): on
            # rig366 the difference is the model's, not the integrator's
            print("  ROSS %s: %.3f s CPU, %s %.2g" % (
                m, rn if m == "newmark" else rl,
                "error" if name == "ross42" else "difference (no mesh damping in ROSS)",
                np.max(np.abs(y - x)) / pk))
    for rtol in ("default", "1e-4"):
        extra = [] if rtol == "default" else ["--rtol", rtol]
        out = os.path.join(tmp, "%s_%s" % (name, rtol))
        j = subprocess.run([gd, "transient"] + base + extra + ["--json"], check=True,
                           capture_output=True, text=True).stdout
        est = re.search(r'"error_estimate":\s*([0-9.eE+-]+)', j)
        subprocess.run([gd, "transient"] + base + extra + ["--out", out], check=True,
                       stdout=subprocess.DEVNULL)
        y = np.genfromtxt(os.path.join(out, "records.csv"), delimiter=",", skip_header=1)[:, 1]
        err = np.max(np.abs(y - x)) / pk
        t = cpu(["transient"] + base + extra, max(3, N // 3))
        e = float(est.group(1)) if est else float("nan")
        print("  geardyn transient rtol %s: %.4f s CPU (whole process), error %.2g, printed "
              "estimate %.2g (%.2fx the error)%s%s" % (
                  rtol, t, err, e, e / err,
                  "; %.1fx ROSS Newmark" % (rn / t) if rn else "",
                  ", %.2fx ROSS lsim" % (rl / t) if rl else ""))
PY
