#!/usr/bin/env python3
"""Super-harmonic resonances of the [JMSTHelical] Figs. 11-13 curves (figs11_13.sh).

usage: examples/seed002/resonances.py [OUTDIR]      (run from the repository root)

Predicted: input speed n (rpm) where k times a tooth-mesh frequency equals a natural
frequency f of the same model (`geardyn modal --undamped`, mean mesh stiffness, the
input held in torsion at B11 as `periodic` holds it through `prescribed: nominal`),
    mesh 1: k * 52 n / 60 = f,   mesh 2: k * 22 (52 / 72) n / 60 = f,   k = 1, 2, 3,
for the modes that store at least MESH_SHARE of their strain energy in the meshes
(the only ones the TVMS excites). Observed: local maxima of the peak-to-peak of
gear1.x and of the two mesh forces along the curve. Also the largest
difference between the full and the lateral-torsional curves at each helix angle, and
the median and largest peak-to-peak of each curve.
Standard library only.
"""
import csv
import json
import os
import subprocess
import sys

MODEL = "examples/helical_two_stage.yaml"
GEARDYN = os.environ.get("GEARDYN", "./build/geardyn")
MESH_SHARE = 0.01  # modes with < 1 % strain energy in the meshes are not excited
Z1, Z3, RATIO1 = 52, 22, 52.0 / 72.0  # driver teeth of the meshes, stage-1 ratio
RECORDS = ["gear1.x:disp", "mesh:pair1:force", "mesh:pair2:force"]
RPM = 60.0 / (2.0 * 3.141592653589793)


def modes(coupling, helix):
    out = subprocess.run(
        [GEARDYN, "modal", MODEL, "--modes", "40", "--undamped", "--json",
         "--coupling", coupling, "--set", "bearings.B11.k_torsion=1e12",
         "--set", f"meshes.pair1.geometry.helix_angle={helix}deg",
         "--set", f"meshes.pair2.geometry.helix_angle={helix}deg"],
        check=True, capture_output=True, text=True).stdout
    res = []
    for m in json.loads(out)["modes"]:
        e = m["energy_by_component"]
        share = e.get("pair1", 0.0) + e.get("pair2", 0.0)
        if not m["rigid_body"] and share >= MESH_SHARE:
            res.append((m["mode"], m["frequency_hz"], share))
    return res


def curves(path):
    """{record: [(rpm, mean, rms, p2p)]} in speed order."""
    res = {}
    with open(os.path.join(path, "periodic.csv")) as f:
        for row in csv.DictReader(f):
            res.setdefault(row["record"], []).append(
                (float(row["speed_rad_s"]) * RPM, float(row["mean"]),
                 float(row["rms"]), float(row["peak_to_peak"])))
    return res


def stability(path):
    """(stable, unstable, unknown, largest |mu|max, its rpm) over the curve's points."""
    seen = {}
    with open(os.path.join(path, "periodic.csv")) as f:
        for row in csv.DictReader(f):
            seen[(row["point"], row["direction"])] = (
                int(row["stable"]), float(row["floquet_multiplier_max_abs"]),
                float(row["speed_rad_s"]) * RPM)
    counts = [sum(1 for v in seen.values() if v[0] == k) for k in (1, 0, -1)]
    known = [v for v in seen.values() if v[0] >= 0]
    top = max(known, key=lambda v: v[1]) if known else (0, float("nan"), float("nan"))
    return counts + [top[1], top[2]]


def peaks(curve, half=2, rise=1.5):
    """Local maxima over +-half points that stand rise times above the curve's
    smallest value within +-3 half points (a resonance, not a slow trend)."""
    p2p = [c[3] for c in curve]
    out = []
    for i in range(len(p2p)):
        lo, hi = max(0, i - half), min(len(p2p), i + half + 1)
        if p2p[i] < max(p2p[lo:hi]) or p2p[i] <= 0:
            continue
        wl, wh = max(0, i - 3 * half), min(len(p2p), i + 3 * half + 1)
        if p2p[i] >= rise * min(p2p[wl:wh]):
            out.append((curve[i][0], p2p[i]))
    return out


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else "build/seed002"
    for helix in (0, 5, 10, 15, 20):
        a = curves(os.path.join(outdir, f"full_{helix}deg"))
        b = curves(os.path.join(outdir, f"lateral-torsional_{helix}deg"))
        diffs = []
        for r in RECORDS:
            scale = max(abs(c[3]) for c in a[r])
            d = max(abs(x[3] - y[3]) for x, y in zip(a[r], b[r])) / scale
            dm = max(abs(x[1] - y[1]) / max(abs(x[1]), 1e-300) for x, y in zip(a[r], b[r]))
            diffs.append(f"{r} p2p {d:.2e} mean {dm:.2e}")
        print(f"helix {helix:2d} deg, full vs lateral-torsional, max |diff| / max: "
              + "; ".join(diffs))
    print("\nstability (Floquet multipliers of every point): stable / unstable / not computed, "
          "largest |mu|max")
    for coupling in ("full", "lateral-torsional"):
        for helix in (0, 5, 10, 15, 20):
            st = stability(os.path.join(outdir, f"{coupling}_{helix}deg"))
            print(f"{coupling:17s} {helix:2d} deg: {st[0]} / {st[1]} / {st[2]}, "
                  f"{st[3]:.10f} at {st[4]:.0f} rpm")
    print("\nmedian / largest peak-to-peak over the speeds (gear1.x in um, forces in N)")
    for coupling in ("full", "lateral-torsional"):
        for helix in (0, 5, 10, 15, 20):
            c = curves(os.path.join(outdir, f"{coupling}_{helix}deg"))
            cells = []
            for r in RECORDS:
                v = sorted(x[3] * (1e6 if r.startswith("gear") else 1.0) for x in c[r])
                cells.append(f"{r} {v[len(v) // 2]:.3g} / {v[-1]:.3g}")
            print(f"{coupling:17s} {helix:2d} deg: " + "; ".join(cells))
    for coupling in ("full", "lateral-torsional"):
        for helix in (0, 20):
            c = curves(os.path.join(outdir, f"{coupling}_{helix}deg"))
            rpm = [x[0] for x in c[RECORDS[0]]]
            step = (rpm[-1] - rpm[0]) / (len(rpm) - 1)
            obs = {r: peaks(c[r]) for r in RECORDS}
            print(f"\n{coupling}, helix {helix} deg: grid step {step:.1f} rpm; peaks: "
                  + "; ".join(f"{r}: " + " ".join(f"{p[0]:.0f}" for p in obs[r])
                              for r in RECORDS))
            print("mode   f_n(Hz) mesh%  mesh k  predicted(rpm)  observed(rpm)  record")
            for mode, f, share in modes(coupling, helix):
                for mesh, z in ((1, Z1), (2, Z3 * RATIO1)):
                    for k in (1, 2, 3):
                        n = 60.0 * f / (k * z)
                        if not rpm[0] <= n <= rpm[-1]:
                            continue
                        near = [(abs(p[0] - n), p[0], r) for r in RECORDS for p in obs[r]
                                if abs(p[0] - n) <= 1.01 * step]
                        seen = (f"{min(near)[1]:13.0f}  {min(near)[2]}" if near
                                else "            -")
                        print(f"{mode:4d} {f:9.1f} {100 * share:5.1f} {mesh:5d} {k:2d}"
                              f" {n:15.0f}  {seen}")


if __name__ == "__main__":
    main()
