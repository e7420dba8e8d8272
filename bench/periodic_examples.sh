#!/usr/bin/env bash
# geardyn periodic with default options on the examples that have laws, and on every
# example with a non-smooth law (backlash, contact, a unilateral spring) also
# --method shooting (issue 33, acceptance: "every point converged or explained";
# "the default run's stability verdicts and bifurcations equal --method shooting's").
# Prints one table row per case: the method auto chose, points converged / failed (a
# failed point must carry a reason), verdicts equal to shooting's, bifurcations (type
# and location to BIF_TOL relative) equal to shooting's, and the CPU of each run
# (/usr/bin/time user + system: noisy on a shared machine, not a timed test), and whether
# RUNS identical default runs gave byte-identical JSON (issue 33: "Five identical runs
# give identical outputs"; every budget and choice is decided from counted work).
#
# usage: bench/periodic_examples.sh [BUILD] [all]      (from the repository root)
#   BUILD (default build): where geardyn is; "all" also runs the cases marked slow
#   (minutes each: the 754-state seed-002 train, the Ducati train, the wind turbine).
# environment: OUT (default /tmp/periodic_examples), BIF_TOL (default 1e-4), ONLY (a
#   regular expression: only the cases whose name matches), RUNS (default 5: the default
#   run repeated that many times in all and compared byte for byte; 1 skips it), TIMEOUT
#   (seconds of wall time per run, none by default: a run stopped by it is reported as
#   such; on a loaded machine a process gets a fraction of a core, so the CPU column
#   says how far it got)
set -uo pipefail

BUILD=${1:-build}
ALL=${2:-}
GEARDYN=$BUILD/geardyn
OUT=${OUT:-/tmp/periodic_examples}
BIF_TOL=${BIF_TOL:-1e-4}
RUNS=${RUNS:-5}
TIMEOUT=${TIMEOUT:-}
export OPENBLAS_NUM_THREADS=1
[ -x "$GEARDYN" ] || { echo "periodic_examples.sh: $GEARDYN not built (make)" >&2; exit 2; }
mkdir -p "$OUT"

# name | model | range and options | compare with shooting (1: a non-smooth law) | slow
CASES=(
    "nlvib_ex03|examples/nlvib_ex03.yaml|--frequency 0.8:0.6:11|1|0"
    "impact_oscillator|examples/impact_oscillator.yaml|--frequency 7500:11000:8|1|0"
    "rattle_pair|examples/rattle_pair.yaml|--speeds 600rpm:1000rpm:3|1|0"
    "rattle_idle|examples/rattle_idle.yaml|--speeds 600rpm:1000rpm:3|1|0"
    "planetary_mesh_laws|examples/planetary_mesh_laws.yaml|--speeds 1500rpm:1500rpm:1|1|0"
    "duffing (up)|examples/duffing.yaml|--frequency 0.5:1.6:12|0|0"
    "duffing (down)|examples/duffing.yaml|--frequency 1.6:0.5:12|0|0"
    "chen1998_gear_pair|examples/chen1998_gear_pair.yaml|--speeds 900:1100:3|0|0"
    "gearbox_coprime|examples/gearbox_coprime.yaml|--speeds 600rpm:3000rpm:3|0|0"
    "manual_5speed|examples/manual_5speed.yaml|--speeds 800rpm:800rpm:1|1|1"
    "gearbox_neutral_rattle|examples/gearbox_neutral_rattle.yaml|--speeds 800rpm:800rpm:1|1|1"
    "ducati_timing_geartrain|examples/ducati_timing_geartrain.yaml|--speeds 10000rpm:10000rpm:1|1|1"
    "helical_two_stage (seed 002)|examples/helical_two_stage.yaml|--speeds 2000rpm:3000rpm:3|0|1"
    "wind_turbine_gearbox|examples/wind_turbine_gearbox.yaml|--speeds 22rpm:22rpm:1|0|1"
)

run() { # tag model args... -> OUT/tag.json, OUT/tag.err, OUT/tag.time
    local tag=$1
    shift
    local cap=()
    [ -n "$TIMEOUT" ] && cap=(timeout "$TIMEOUT")
    /usr/bin/time -f "%U %S" -o "$OUT/$tag.time" "${cap[@]}" "$GEARDYN" periodic "$@" --json \
        --quiet >"$OUT/$tag.json" 2>"$OUT/$tag.err"
    echo $? >"$OUT/$tag.rc"
}

echo "| case | options | auto chose | converged / failed (explained) | verdicts = shooting | bifurcations = shooting | $RUNS runs identical | CPU default / shooting |"
echo "|---|---|---|---|---|---|---|---|"
i=0
for c in "${CASES[@]}"; do
    IFS='|' read -r name model args cmp slow <<<"$c"
    i=$((i + 1))
    [ "$slow" = 1 ] && [ "$ALL" != all ] && continue
    [ -n "${ONLY:-}" ] && ! [[ $name =~ $ONLY ]] && continue
    # shellcheck disable=SC2086
    run "d$i" "$model" $args
    same=-
    if [ "$RUNS" -gt 1 ]; then
        same="yes"
        for k in $(seq 2 "$RUNS"); do
            # shellcheck disable=SC2086
            run "d$i.$k" "$model" $args
            cmp -s "$OUT/d$i.json" "$OUT/d$i.$k.json" &&
                cmp -s "$OUT/d$i.rc" "$OUT/d$i.$k.rc" || same="NO (run $k differs)"
        done
    fi
    if [ "$cmp" = 1 ]; then
        # shellcheck disable=SC2086
        run "s$i" "$model" $args --method shooting
    fi
    python3 - "$OUT" "$i" "$cmp" "$BIF_TOL" "$name" "$args" "$same" "$TIMEOUT" <<'EOF'
import json, sys
out, i, cmp, tol, name, args, ident, cap = sys.argv[1], sys.argv[2], sys.argv[3] == "1", float(sys.argv[4]), sys.argv[5], sys.argv[6], sys.argv[7], sys.argv[8]
def load(tag):
    try:
        return json.load(open(f"{out}/{tag}.json"))
    except Exception:
        return None
def cpu(tag):
    try:
        u, s = open(f"{out}/{tag}.time").read().split()[-2:]
        return f"{float(u) + float(s):.2f} s"
    except Exception:
        return "-"
def rc(tag):
    try:
        return int(open(f"{out}/{tag}.rc").read())
    except Exception:
        return -1
d = load(f"d{i}")
if d is None and rc(f"d{i}") == 124:
    print(f"| {name} | `{args}` | - | stopped by TIMEOUT after {cap} s wall, no answer | - | - | {ident} | {cpu('d'+str(i))} |")
    sys.exit(0)
if d is None:
    err = open(f"{out}/d{i}.err").read().strip().splitlines()
    print(f"| {name} | `{args}` | - | refused: {err[-1][:120] if err else '?'} | - | - | {ident} | {cpu('d'+str(i))} |")
    sys.exit(0)
pts = d["points"]
conv = sum(1 for p in pts if p["converged"])
fail = [p for p in pts if not p["converged"]]
expl = sum(1 for p in fail if p.get("reason"))
choice = d.get("method_choice", "")
chose = choice.split(":")[0].split(" (")[0] if choice else d.get("method", "?")
verd = bifs = "-"
if cmp:
    s = load(f"s{i}")
    if s is None:
        verd = bifs = "shooting run failed"
    else:
        sp = s["points"]
        key = lambda p: (p["direction"], round(p["parameter"] if p["speed_rad_s"] == 0 else p["speed_rad_s"], 9))
        sv = {}
        for p in sp:
            sv.setdefault(key(p), []).append(p)
        same = n = 0
        for p in pts:
            q = sv.get(key(p))
            if not q or not p["converged"] or not q[0]["converged"]:
                continue
            q = q.pop(0) if len(q) > 1 else q[0]
            n += 1
            same += p.get("stable") == q.get("stable")
        verd = f"{same} of {n}"
        def loc(b):
            return b["parameter"] if b["speed_rad_s"] == 0 else b["speed_rad_s"]
        bd = sorted((b["type"], loc(b)) for b in d.get("bifurcations") or [])
        bs = sorted((b["type"], loc(b)) for b in s.get("bifurcations") or [])
        ok = len(bd) == len(bs) and all(a[0] == b[0] and abs(a[1] - b[1]) <= tol * abs(b[1]) for a, b in zip(bd, bs))
        bifs = ("yes" if ok else "NO") + f" ({len(bd)} / {len(bs)})"
print(f"| {name} | `{args}` | {chose} | {conv} / {len(fail)} ({expl}) | {verd} | {bifs} | {ident} | {cpu('d'+str(i))} / {cpu('s'+str(i)) if cmp else '-'} |")
EOF
done
