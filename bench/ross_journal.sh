#!/bin/sh
# The plain journal bearing of examples/jeffcott_journal.yaml (D 50 mm, L 20 mm, c 50 um,
# 0.02 Pa s, 98.1 N: half of the 20 kg rotor's weight) side by side with ROSS
# (petrobras/ross, its current fluid-film engine: ross.bearings.fixed_geometry.
# FixedGeometryBearing with one 359.9 deg land centred at 270 deg, an axial groove at the
# top; isoviscous: thermal_type None) on the same film: geardyn's gd_reynolds_journal_land
# with the same land (leading edge at 90.05 deg, 359.9 deg, the groove at 0 gauge pressure
# as ROSS's flooded groove) and the Reynolds cavitation condition (docs/bearings.md, "ROSS
# side by side"). Per speed: eccentricity, attitude and the eight coefficients of both,
# and ROSS's static stiffness from its own film forces (the load moved by +-FD_LOAD N in
# x and y, K = (dq/dW)^-1 from four more ROSS equilibria), which is what geardyn's
# coefficients are (central differences of the film force); then the threshold speed of
# a rigid 20 kg rotor on two such bearings (a root of m s^2 + 2 C s + 2 K crossing into
# the right half plane, interpolated between the speeds) on each side's coefficients.
#
# ROSS is not a dependency of geardyn: give its source tree (the `fetch` of
# github:petrobras/ross, `git archive HEAD ross`). It needs numpy, scipy, numba and pint
# (Debian: python3-numba, python3-pint); the modules it imports for plots and magnetic
# bearings (control, matplotlib, ccp, ...) are stubbed, as the bearing never calls them.
#
# usage: bench/ross_journal.sh ROSS_SRC [BUILD_DIR] [RPM_LIST] [ROSS_GRID] [OUR_GRID] [FD_LOAD]
#   defaults: build, "1000 2000 5000 10000 11000 11500 12000", "80x40" (elements around x
#   along), "80x39" (intervals on the land x interior points along: the same nodes),
#   1.0 (N; 0: no static stiffness from ROSS's equilibria)
# CPU (2026-12-02, an idle core): one ROSS equilibrium about 3 s at 80 x 40 and 15 s at
# 160 x 80 (after numba's first compilation, about 15 s; FD_LOAD > 0 makes it five per
# speed); geardyn 0.25 s (80 x 39) to 2 s (160 x 79) per speed.
set -e
ROSS=${1:?give the ROSS source tree}
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${2:-$SRC/build}
RPMS=${3:-1000 2000 5000 10000 11000 11500 12000}
RG=${4:-80x40}
OG=${5:-80x39}
FD=${6:-1.0}
[ -f "$BUILD/libgeardyn.so" ] || { echo "no libgeardyn.so in $BUILD: build first" >&2; exit 2; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
cat >"$TMP/ours.c" <<'CEOF'
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "geardyn/geardyn.h"
#include "geardyn/reynolds.h"
/* argv: ntheta nz rpm...: eps attitude kxx kxy kyx kyy cxx cxy cyx cyy per line, on ROSS's
   land (leading edge 270 - 359.9 / 2 deg, 359.9 deg) */
int main(int argc, char **argv)
{
    gd_sfd_params p = {0};
    p.viscosity = 0.02;
    p.radius = 0.025;
    p.length = 0.02;
    p.clearance = 50e-6;
    gd_reynolds_grid g;
    gd_reynolds_grid_init(&g);
    g.ntheta = atoi(argv[1]);
    g.nz = atoi(argv[2]);
    g.cavitation = GD_FILM_REYNOLDS;
    gd_journal_land land = {(270 - 0.5 * 359.9) * M_PI / 180, 359.9 * M_PI / 180, 0};
    for (int k = 3; k < argc; k++) {
        double w = atof(argv[k]) * M_PI / 30, eps, att, K[4], C[4];
        gd_error err;
        if (gd_reynolds_journal_land(&p, &g, &land, 98.1, w, &eps, &att, K, C, &err)) {
            fprintf(stderr, "%s\n", err.message);
            return 1;
        }
        printf("%s %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g\n", argv[k], eps, att, K[0],
               K[1], K[2], K[3], C[0], C[1], C[2], C[3]);
    }
    return 0;
}
CEOF
cc -O2 -std=c11 -D_XOPEN_SOURCE=700 -I"$SRC/include" -I"$BUILD/include" "$TMP/ours.c" -L"$BUILD" -lgeardyn -Wl,-rpath,"$BUILD" -lm -o "$TMP/ours"
cat >"$TMP/ross.py" <<'PEOF'
"""argv: ross_src nx nz rpm...: the same line per speed from ROSS's PlainJournal"""
import sys, types, warnings
from unittest.mock import MagicMock
sys.path.insert(0, sys.argv[1])
warnings.simplefilter("ignore")
for _ in range(40):  # stub the modules ROSS imports for what the bearing never calls
    try:
        from ross.bearings.fixed_geometry import FixedGeometryBearing
        break
    except ModuleNotFoundError as e:
        for k in [k for k in sys.modules if k == "ross" or k.startswith("ross.")]:
            del sys.modules[k]
        parts = e.name.split(".")
        for i in range(1, len(parts) + 1):
            sys.modules.setdefault(".".join(parts[:i]), MagicMock())
import numpy as np
mu = 0.02
oil = {"liquid_viscosity1": mu, "temperature1": 300.0, "liquid_viscosity2": mu,
       "temperature2": 400.0, "liquid_density": 870.0, "liquid_specific_heat": 1950.0,
       "liquid_thermal_conductivity": 0.13, "vapour_viscosity": 9e-6, "vapour_density": 0.029,
       "vapour_specific_heat": 1000.0, "vapour_thermal_conductivity": 0.026,
       "saturation_pressure": 1e5}
nx, nz, fd = int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
W = 98.1
def bearing(rpm, fx, fy):
    return FixedGeometryBearing(
        0, frequency=[rpm * np.pi / 30], journal_diameter=0.05, radial_clearance=50e-6,
        pad_thickness=0.0125, pivot_angle=[np.radians(270.0)], pad_arc=[np.radians(359.9)],
        pad_axial_length=[0.02], preload=[0.0], offset=[0.5], lubricant=oil,
        oil_supply_temperature=320.0, oil_flow_v=1e-2, fxs_load=fx, fys_load=fy,
        thermal_type=None, total_ex_film=nx, total_ez_film=nz, total_ey_film=10,
        total_ey_pad=10, reference_temperature=320.0, initial_position=(0.1, -0.1))
def position(b):
    out = b._results.outputs[0]
    return np.array([out["xj_cb"][0], out["yj_cb"][0]]) * 50e-6
for arg in sys.argv[5:]:
    rpm = float(arg)
    b = bearing(rpm, 0, -W)
    out = b._results.outputs[0]
    k = [float(getattr(b, n)[0]) for n in ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")]
    ks = [float("nan")] * 4
    if fd > 0:  # the film force F(q) balances the load L: dq = K^-1 dL
        cols = [(position(bearing(rpm, fd * ex, -W + fd * ey)) -
                 position(bearing(rpm, -fd * ex, -W - fd * ey))) / (2 * fd)
                for ex, ey in ((1, 0), (0, 1))]
        ks = list(np.linalg.inv(np.column_stack(cols)).flatten())
    print(arg, *("%.9g" % v for v in [out["eccentricity"][0], out["attitude"][0]] + k + ks),
          flush=True)
PEOF
cat >"$TMP/table.py" <<'PEOF'
"""the side-by-side table and each side's threshold speed"""
import sys
import numpy as np
def rows(path):
    return {float(l.split()[0]): [float(v) for v in l.split()[1:]] for l in open(path) if l.strip()}
ours, ross = rows(sys.argv[1]), rows(sys.argv[2])
names = ["eps", "attitude", "kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy"]
print("| rpm | | " + " | ".join(names) + " |")
print("|---" * (len(names) + 2) + "|")
worst = {}
fdworst = {}
for rpm in sorted(ours):
    if rpm not in ross:
        continue
    o, r = ours[rpm], ross[rpm]
    print("| %g | ROSS | " % rpm + " | ".join("%.5g" % v for v in r[:10]) + " |")
    print("| %g | geardyn | " % rpm + " | ".join("%.5g" % v for v in o) + " |")
    kbig, cbig = max(abs(v) for v in r[2:6]), max(abs(v) for v in r[6:10])
    d = [abs(o[i] - r[i]) / abs(r[i]) for i in range(len(names))]
    print("| %g | rel. diff. | " % rpm + " | ".join("%.2f %%" % (100 * v) for v in d) + " |")
    if len(r) > 10 and r[10] == r[10]:
        ks = r[10:14]
        print("| %g | ROSS K from its equilibria | | | " % rpm + " | ".join("%.5g" % v for v in ks) +
              " | | | | |")
        print("| %g | geardyn vs that | | | " % rpm + " | ".join(
            "%.2f %%" % (100 * abs(o[2 + i] - ks[i]) / abs(ks[i])) for i in range(4)) + " | | | | |")
        fdworst[rpm] = max(abs(o[2 + i] - ks[i]) for i in range(4)) / max(abs(v) for v in ks)
    for i in range(2, 10):
        big = kbig if i < 6 else cbig
        worst[rpm] = max(worst.get(rpm, 0), abs(o[i] - r[i]) / big)
for rpm in sorted(worst):
    print("%g rpm: largest coefficient difference %.2f %% of the largest of its kind" % (rpm, 100 * worst[rpm]))
    if rpm in fdworst:
        print("%g rpm: geardyn's K against ROSS's K from its own equilibria: %.2f %% of the largest"
              % (rpm, 100 * fdworst[rpm]))
def growth(row):
    """the largest real part of the roots of m s^2 + 2 C s + 2 K (20 kg, two bearings)"""
    K = 2 * np.array(row[2:6]).reshape(2, 2)
    C = 2 * np.array(row[6:10]).reshape(2, 2)
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-K / 20.0, -C / 20.0]])
    return max(np.linalg.eigvals(A).real)
hybrid = {rpm: r[:2] + r[10:14] + r[6:10] for rpm, r in ross.items() if len(r) > 10 and r[10] == r[10]}
sides = [("geardyn", ours), ("ROSS", ross)]
if len(hybrid) == len(ross):
    sides.append(("ROSS (K from its equilibria, its C)", hybrid))
for name, side in sides:
    sp = sorted(side)
    g = [growth(side[r]) for r in sp]
    onset = None
    for i in range(1, len(sp)):
        if g[i - 1] < 0 <= g[i]:
            onset = sp[i - 1] + (sp[i] - sp[i - 1]) * -g[i - 1] / (g[i] - g[i - 1])
    print("%s: threshold speed of the 20 kg rotor on two bearings %s" % (
        name, "%.0f rpm (interpolated between the speeds)" % onset if onset else
        "not within the speeds"))
PEOF
echo "ROSS ($RG elements), geardyn ($OG intervals x interior points), the same land, Reynolds cavitation, 98.1 N, speeds: $RPMS"
"$TMP/ours" $(echo "$OG" | tr x ' ') $RPMS >"$TMP/ours.txt"
/usr/bin/python3 "$TMP/ross.py" "$ROSS" $(echo "$RG" | tr x ' ') "$FD" $RPMS >"$TMP/ross.txt"
/usr/bin/python3 "$TMP/table.py" "$TMP/ours.txt" "$TMP/ross.txt"
