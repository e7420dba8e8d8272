"""Test data from Python (docs/testing.md): the same numbers as `geardyn testmodal` and
`geardyn correlate` (one library call on the same files), and LSCF on FRFs of a known
two-mode truth written as FRF CSVs here."""
import math
import os

import numpy as np

from conftest import ROOT, run_cli, nums, same

RIG = os.path.join(ROOT, "examples", "rig2018.yaml")
COUPLED = os.path.join(ROOT, "examples", "mmt2018_coupled_modes.csv")


def test_correlate_matches_cli(geardyn):
    j = run_cli("correlate", RIG, COUPLED)
    c = geardyn.correlate(geardyn.load(RIG), COUPLED)
    pairs = j["correlation"]["pairs"]
    assert same(c.model_hz, nums([p["model_hz"] for p in pairs]))
    assert same(c.difference_pct, nums([p["difference_pct"] for p in pairs]))
    # [MMT2018] Table 5, mode 1: 121.9 Hz measured, FE 126.45 (geardyn 126.53), 3.59 %
    assert math.isclose(c.model_hz[0], 126.45, rel_tol=0.0025)
    assert abs(c.difference_pct[0] - 3.59) < 0.26


def test_update_matches_cli(geardyn):
    key = "bearings.A1.k,bearings.A2.k"
    j = run_cli("correlate", RIG, COUPLED, "--update", key + "=2e7:5e8")
    u = geardyn.update(RIG, COUPLED, {key: (2e7, 5e8)})
    p = j["update"]["parameters"][0]
    assert same(u.value, [p["updated"]])
    assert same(u.sigma, [p["std_dev"]])
    assert u.after["rms_pct"] < u.before["rms_pct"]


def test_testmodal_on_a_known_truth(geardyn, tmp_path):
    # receptances of two modes (120 Hz 1 %, 310 Hz 2 %) at three points, one reference
    f = np.arange(1, 2049) * 0.25
    w = 2 * np.pi * f
    truth = [(120.0, 0.01, np.array([1.0, 0.6, -0.4])), (310.0, 0.02, np.array([0.5, -0.8, 1.0]))]
    paths = []
    for p in range(3):
        H = sum(phi[p] * phi[0] / ((2 * np.pi * fr) ** 2 - w ** 2 + 2j * z * 2 * np.pi * fr * w)
                for fr, z, phi in truth)
        path = tmp_path / ("h%d.csv" % p)
        with open(path, "w") as fh:
            fh.write("# geardyn frf\n# response: %d +y\n# reference: 1 +y\n# units: m/N\n"
                     "frequency_hz,re,im\n" % (p + 1))
            for k in range(len(f)):
                fh.write("%.17g,%.17g,%.17g\n" % (f[k], H[k].real, H[k].imag))
        paths.append(str(path))
    r = geardyn.testmodal(paths)
    assert len(r.frequency_hz) == 2
    for (fr, z, phi), fe, ze, k in zip(truth, r.frequency_hz, r.damping_ratio, range(2)):
        # noise-free: the fit is exact to rounding far below these tolerances
        assert math.isclose(fe, fr, rel_tol=1e-6)
        assert math.isclose(ze, z, rel_tol=1e-4)
        shape = r.residues[:, k]
        mac = abs(np.vdot(shape, phi)) ** 2 / (np.vdot(shape, shape).real * phi @ phi)
        assert mac > 0.99999
    j = run_cli("testmodal", *paths)
    assert same(r.frequency_hz, nums([m["frequency_hz"] for m in j["modes"]]))
    assert len(r.pole_order) == len(j["stabilisation"])
