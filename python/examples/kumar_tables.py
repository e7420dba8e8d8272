#!/usr/bin/env python3
"""Kumar & Sundarasiva Rao (IJAEST 4(1), 2011; seeds/000) from Python: Table 3.1
(torsional model, 4 DOF) and Table 3.2 (coupled lateral-torsional model, 8 DOF), the
Table 3.1 mode-shape ratios, the effect of the mesh stiffness, and a Campbell diagram
(the 170-DOF MMT 2018 rig, whose gyroscopic shaft modes split with speed).

usage: PYTHONPATH=python python3 python/examples/kumar_tables.py [--table-only] [--out DIR]
  --table-only  the two tables only (what `make demo` runs)
  --out DIR     also write DIR/campbell.csv, DIR/critical_speeds.csv and, when
                matplotlib is installed, DIR/campbell.png
"""
import argparse
import os

import numpy as np

import geardyn

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
EX = os.path.join(ROOT, "examples")

# The paper's natural frequencies (rad/s), Tables 3.1 and 3.2.
PAPER_31 = [0, 122.32, 309.7, 25727.92]
PAPER_32 = [0, 122.32, 309.70, 23446.05, 38659.61, 40474.36, 54672.94, 57304.6]


def table(title, model, paper):
    r = model.modal()
    df = r.to_pandas()[["omega_n_rad_s", "frequency_hz", "dominant_motion",
                        "dominant_component", "energy_lateral", "energy_torsional"]]
    df.insert(1, "paper_rad_s", paper)
    with np.errstate(divide="ignore", invalid="ignore"):
        df.insert(2, "deviation_%", 100 * (df["omega_n_rad_s"] / df["paper_rad_s"] - 1))
    print("%s (%s, %d DOFs)" % (title, os.path.basename(model.file), r.ndof))
    print(df.to_string(float_format=lambda x: "%.6g" % x))
    print()
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--table-only", action="store_true")
    ap.add_argument("--out")
    a = ap.parse_args()

    torsional = geardyn.load(os.path.join(EX, "kumar2011_torsional.yaml"))
    coupled = geardyn.load(os.path.join(EX, "kumar2011_coupled.yaml"))
    r31 = table("Table 3.1, torsional model", torsional, PAPER_31)
    table("Table 3.2, coupled lateral-torsional model", coupled, PAPER_32)
    if a.table_only:
        return

    # Table 3.1's mode shapes: gear/pinion 0.9468 (opposite sign here: both angles are
    # about +z), motor/pinion -2.0153 and load/pinion -3.7617 in mode 2, 1 : -1.9012 in
    # the mesh mode
    s = torsional.system
    x = r31.shape_re
    idx = {n: s.dof(n, "rz") for n in ("motor", "pinion", "gear", "load")}
    print("Table 3.1 mode-shape ratios (rz, relative to the pinion)")
    for k in range(r31.nmodes):
        p = x[idx["pinion"], k]
        print("  mode %d: " % (k + 1) + "  ".join(
            "%s %+.4f" % (n, x[i, k] / p) for n, i in idx.items() if n != "pinion"))
    print()

    # The mesh mode against the mesh stiffness (`--set meshes.mesh.stiffness=...`)
    print("coupled model: mesh-dominated mode vs mesh stiffness")
    for k in (1e8, 2e8, 4e8):
        m = coupled.copy().set("meshes.mesh.stiffness", k)
        print("  k = %.0e N/m: %.1f rad/s" % (k, m.modal().omega_n[3]))
    print()

    # A Campbell diagram: the rig of MMT 2018 from 0 to 12000 rpm
    rig = geardyn.load(os.path.join(EX, "rig2018.yaml"))
    c = rig.campbell("0:12000rpm:25", modes=8)
    f = c.frequency_hz
    print("Campbell diagram, %s: damped natural frequencies (Hz)" % os.path.basename(rig.file))
    print("%8s " % "rpm" + " ".join("%9s" % ("mode%d" % t["id"]) for t in c.tracks))
    for k in range(0, c.nspeeds, 4):
        print("%8.0f " % c.speeds_rpm[k] + " ".join("%9.2f" % v for v in f[:, k]))
    print("whirl: " + ", ".join("%d %s" % (t["id"], t["whirl"]) for t in c.tracks))
    print("critical speeds (rpm): " + ", ".join(
        "%.0f (mode %d, %s)" % (x["speed_rpm"], x["mode"], x["order"])
        for x in c.critical_speeds[:8]))
    if a.out:
        os.makedirs(a.out, exist_ok=True)
        c.to_pandas().to_csv(os.path.join(a.out, "campbell.csv"), index=False)
        import pandas as pd
        pd.DataFrame(c.critical_speeds).to_csv(os.path.join(a.out, "critical_speeds.csv"),
                                               index=False)
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            print("(matplotlib not installed: %s/campbell.csv holds the diagram)" % a.out)
        else:
            fig, ax = plt.subplots(figsize=(7, 5))
            c.plot(ax)
            ax.set_ylim(0, 1.1 * np.nanmax(f))
            fig.savefig(os.path.join(a.out, "campbell.png"), dpi=120)
            print("wrote %s/campbell.png" % a.out)


if __name__ == "__main__":
    main()
