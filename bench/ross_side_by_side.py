"""ROSS side by side (issue 35): the CPU time of ROSS's modal analysis and time response on
the two benchmark rotors, in ROSS's own Python process after `import ross` (the import
is not counted), for bench/bench_ross.sh to set against `geardyn` run as a whole process.

- ross42: ROSS's own `rotor_example()` (6 Timoshenko elements, 2 disks, 2 bearings,
  7 nodes x 6 DOFs = 42 DOFs); bench/models/ross_example42.yaml is the same rotor.
- rig366: the MMT 2018 rig of bench/models/rig366.yaml built in ROSS as a MultiRotor
  (30 + 29 elements, gears 48/32 at mid-span, k_m 3.9e8 N/m, 61 nodes x 6 = 366 DOFs).

Modal: `run_modal(speed, num_modes=12)` at 3000 rpm, CPU time (time.process_time) of
each call, best of REPEATS. Time response: unbalance from rest for 0.1 s sampled every
1e-4 s (1001 samples), ROSS's Newmark (`method="newmark"`, one step per sample) and its
default (scipy.signal.lsim on the state space), CPU time of one call; the response of
the record is written to OUT_DIR/NAME_METHOD.txt (t, x) for the error against
geardyn's tight reference.
usage: ross_side_by_side.py OUT_DIR [REPEATS] (bench/bench_ross.sh runs it)
ROSS itself is not a dependency of the project: PYTHONPATH must reach it (bench_ross.sh).
"""
import sys
import time

import numpy as np
import ross as rs

# Debian's plotly 5.4 predates `fillpattern` (5.11), which ROSS's gear drawing passes and
# MultiRotor draws the gears to place them: drop it (drawing only, not timed)
_Scatter = rs.gear_element.go.Scatter
rs.gear_element.go.Scatter = lambda *a, fillpattern=None, **k: _Scatter(*a, **k)

out = sys.argv[1]
repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 5
W = 3000 * np.pi / 30


def rig366():
    steel = rs.Material(name="gd_steel", rho=7800, E=2.0e11, Poisson=0.3)
    d = 0.0254

    def shaft(n1, n2):
        return [
            rs.ShaftElement(L=0.25 / n, idl=0.0, odl=d, material=steel, shear_effects=True,
                            rotary_inertia=True, gyroscopic=True)
            for n in (n1, n2) for _ in range(n)
        ]

    def brg(n):
        return rs.BearingElement(n=n, kxx=1e8, cxx=200, kzz=5e7, czz=100)

    g48 = rs.GearElement(n=15, m=1.15, Id=1.3e-3 / 2, Ip=1.3e-3, n_teeth=48,
                         base_diameter=0.096, pr_angle=rs.Q_(20, "deg"))
    g32 = rs.GearElement(n=15, m=0.522, Id=2.5e-4 / 2, Ip=2.5e-4, n_teeth=32,
                         base_diameter=0.064, pr_angle=rs.Q_(20, "deg"))
    r1 = rs.Rotor(shaft(15, 15), [g48], [brg(0), brg(30)])
    r2 = rs.Rotor(shaft(15, 14), [g32], [brg(0), brg(29)])
    return rs.MultiRotor(r1, r2, coupled_nodes=(15, 15), gear_mesh_stiffness=3.9e8,
                         orientation_angle=0.0, position="below")


def cpu(f):
    t0 = time.process_time()
    r = f()
    return time.process_time() - t0, r


# unbalances (node, m e in kg m, phase, speed ratio of the shaft: the driven shaft turns
# at -48/32 of the driving one), as in the geardyn models
rotors = {"ross42": (rs.rotor_example, [(2, 1e-4, 0.0, 1.0)], 2),
          "rig366": (rig366, [(15, 1e-5, 0.0, 1.0), (46, 5e-6, np.pi / 2, -1.5)], 15)}
for name, (make, unb, rec_node) in rotors.items():
    tb, rotor = cpu(make)
    print(f"{name}: {rotor.ndof} DOFs, built in {tb:.3f} s CPU")
    best = min(cpu(lambda: rotor.run_modal(speed=W, num_modes=12))[0] for _ in range(repeats))
    m = rotor.run_modal(speed=W, num_modes=12)
    print(f"{name} modal 12 modes at 3000 rpm: {best:.4f} s CPU (best of {repeats}); "
          f"wn[:6] Hz = {np.round(m.wn[:6] / 2 / np.pi, 2).tolist()}")
    t = np.linspace(0, 0.1, 1001)
    F = np.zeros((t.size, rotor.ndof))
    for node, me, ph, ratio in unb:
        w = ratio * W
        F[:, 6 * node + 0] += me * w**2 * np.cos(w * t + ph)
        F[:, 6 * node + 1] += me * w**2 * np.sin(w * t + ph)
    for method in ("newmark", "default"):
        secs, res = cpu(lambda: rotor.time_response(W, F, t, method=method))
        y = res[1]
        np.savetxt(f"{out}/{name}_{method}.txt", np.column_stack([res[0], y[:, 6 * rec_node]]))
        print(f"{name} time response 0.1 s, 1001 samples, {method}: {secs:.3f} s CPU")
