"""periodic(solver="auto") per value and with a given H (issue 33 item 3; docs/periodic.md,
"Choosing the method"): as `geardyn periodic --method auto`."""
import math

import pytest

from conftest import example

SEED002 = ["meshes.pair1.geometry.helix_angle=0deg", "meshes.pair2.geometry.helix_angle=0deg"]
MESHES = ["mesh:pair1:force", "mesh:pair2:force"]


def test_seed002_downward_per_value(geardyn):
    """A downward sweep 2500 -> 300 rpm: harmonic balance at 2500 rpm (its estimate within
    1 % at H = 591), and at 300 rpm the trend from it (over 1 %) takes reduced shooting
    with no harmonic balance solve; 300 rpm's mesh-2 peak-to-peak within 1 % of the long
    transient (121.673 N). Mutation caught: the old rule (the first value decides the whole
    curve: harmonic balance at both)."""
    m = geardyn.load(example("helical_two_stage"), sets=SEED002, coupling="full")
    w = [2500 * math.pi / 30, 300 * math.pi / 30]
    r = m.periodic(w, records=MESHES, method="sequential", stability=False)
    assert r.methods == ["harmonic_balance", "reduced_shooting"]
    assert "per value" in r.solver_note
    assert "1 by the trend, 0 after" in r.solver_note
    assert "extrapolated from" in r.notes[1] and "over 0.01" in r.notes[1]
    assert r.peak_to_peak[1, 1] == pytest.approx(121.673, rel=0.01)


def test_coprime_given_harmonics_is_the_torus_order(geardyn):
    """harmonics=72 on the co-prime gearbox is the torus' order (the orbit of
    solver="multifreq"), not ordinary harmonic balance of the 67-period common period."""
    m = geardyn.load(example("gearbox_coprime"))
    a = m.periodic("900rpm:900rpm:1", harmonics=72, records=["mesh:stage1:force"],
                   stability=False)
    b = m.periodic("900rpm:900rpm:1", harmonics=72, records=["mesh:stage1:force"],
                   stability=False, solver="multifreq")
    assert a.solver == "multi_frequency_hb"
    assert "read as the torus' order" in a.solver_note
    assert a.peak_to_peak[0, 0] == pytest.approx(b.peak_to_peak[0, 0], rel=1e-12)
