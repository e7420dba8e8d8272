#!/usr/bin/env bash
# Multi-frequency harmonic balance (issue 33 item 6) on the co-prime gearbox
# (examples/gearbox_coprime.yaml: teeth 23/67 and 19/71, both TVMS from geometry): the
# whole curve with default options (auto method, auto order, stability) over 600..3000 rpm, 25 speeds,
# its CPU time, and every point's dynamic mesh forces (standard deviation and peak-to-peak
# of both meshes) against a long transient at the same speed (700 mesh cycles of settling,
# then two common periods of 67 cycles, rtol 1e-9, 512 samples per cycle), the transient's CPU time as the floor
# measured in the same run. Prints the largest deviation per record, and checks the
# transient's numbers at 900 and 1700 rpm against those stored in
# tests/periodic/test_multifreq.c (REF: mean, std, p2p per mesh) to 0.1 %.
# usage: bench_multifreq.sh BUILD [COUNT [FROM TO]]   (FROM, TO in rpm; default 600 3000)
set -euo pipefail
status=0
cd "$(dirname "$0")/.."
B=${1:-build}
N=${2:-25}
LO=${3:-600}
HI=${4:-3000}
M=examples/gearbox_coprime.yaml
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "-- $M: periodic with default options, $LO..$HI rpm, $N speeds"
OPENBLAS_NUM_THREADS=1 "$B/geardyn" periodic "$M" --speeds "${LO}rpm:${HI}rpm:$N" \
    --record mesh:stage1 --record mesh:stage2 --json 2>"$tmp/err" >"$tmp/qp.json"
grep -o '[0-9.]* s CPU' "$tmp/err" | head -1 | sed 's/^/   whole curve: /'
python3 - "$tmp/qp.json" "$B" "$M" <<'PY' || status=1
import json, math, subprocess, sys, time, resource
d = json.load(open(sys.argv[1]))
B, M = sys.argv[2], sys.argv[3]
print("   method:", d["method"], "|", d.get("method_choice", ""))
worst = [0.0] * 4
# the long-transient references stored in tests/periodic/test_multifreq.c (REF)
stored = {900: [(255.02, 19.943, 283.94), (719.44, 26.023, 291.88)],
          1700: [(255.02, 42.541, 426.67), (719.44, 89.255, 652.69)]}
bad = 0
tcpu = 0.0
for p in d["points"]:
    rpm = p["speed_rad_s"] * 30 / math.pi
    Tm = 2 * math.pi / (23 * p["speed_rad_s"])
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    out = subprocess.run([B + "/geardyn", "transient", M, "--speed", "%.9grad/s" % p["speed_rad_s"],
                          "--duration", "%.9gs" % ((700 + 134) * Tm), "--from", "%.9gs" % (700 * Tm),
                          "--output-interval", "%.9gs" % (Tm / 512), "--rtol", "1e-9",
                          "--record", "mesh:stage1", "--record", "mesh:stage2"],
                         capture_output=True, text=True, check=True).stdout
    tcpu += resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - r0
    tr = {}
    for line in out.splitlines():
        f = line.split()
        if f and f[0].startswith("mesh:") and len(f) >= 7:
            mn, mx, mean, rms, p2p = map(float, f[2:7])
            tr[f[0].split(":")[1]] = (math.sqrt(max(0.0, rms * rms - mean * mean)), p2p, mean)
    if round(rpm) in stored:
        for i, name in enumerate(["stage1", "stage2"]):
            ref = stored[round(rpm)][i]
            got = (tr[name][2], tr[name][0], tr[name][1])
            ok = all(abs(g - r) <= 1e-3 * abs(r) for g, r in zip(got, ref))
            bad += not ok
            print("   stored reference %d rpm %s: mean/std/p2p %s, recomputed %s: %s" % (
                round(rpm), name, ref, tuple("%.5g" % g for g in got), "ok" if ok else "DIFFERS"))
    row = []
    for i, name in enumerate(["stage1", "stage2"]):
        rec = p["records"]["mesh:%s:force" % name]
        std = math.sqrt(max(0.0, rec["rms"] ** 2 - rec["mean"] ** 2))
        es = abs(std - tr[name][0]) / tr[name][0]
        ep = abs(rec["peak_to_peak"] - tr[name][1]) / tr[name][1]
        worst[2 * i] = max(worst[2 * i], es)
        worst[2 * i + 1] = max(worst[2 * i + 1], ep)
        row.append("%s std %.4g/%.4g (%.1f%%) p2p %.4g/%.4g (%.1f%%)" % (
            name, std, tr[name][0], 100 * es, rec["peak_to_peak"], tr[name][1], 100 * ep))
    print("   %6.0f rpm H %3d  %s" % (rpm, p["harmonics"], "  ".join(row)))
print("   largest deviation from the transient: stage1 std %.2f %%, p2p %.2f %%; stage2 std "
      "%.2f %%, p2p %.2f %%" % tuple(100 * w for w in worst))
print("   transients (the floor): %.1f s CPU for %d speeds" % (tcpu, len(d["points"])))
sys.exit(1 if bad else 0)
PY
F=examples/gearbox_coprime_full.yaml
echo "-- $F (FE shafts, 138 DOFs: the condensed torus): periodic with default options, 3 speeds"
OPENBLAS_NUM_THREADS=1 /usr/bin/time -f "   whole curve: %U+%S s CPU, %M kB" "$B/geardyn" periodic "$F" \
    --speeds 900rpm:2600rpm:3 --record mesh:stage1 --record mesh:stage2 2>&1 >"$tmp/full.txt" |
    grep -E "CPU|kB" || true
grep -E "^ +[+-] " "$tmp/full.txt" | sed 's/^/  /'
exit $status
