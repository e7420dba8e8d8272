"""transient(condense=...) is `geardyn transient --condense` (docs/transient.md, "Condensed
transient"; issue 37): the same condensed problem, so the same numbers, bit for bit
(conftest.same), on the input gear and idler with backlash, drag and a governor spring of
tests/transient/condensed_pair.yaml; and with a prescribed DOF (examples/rattle_pair.yaml's
input gear: the structure clamped there, its motion a forcing)."""
import os

import pytest

from conftest import ROOT, run_cli, nums, same

PAIR = os.path.join(ROOT, "tests", "transient", "condensed_pair.yaml")
PRESCRIBED = os.path.join(ROOT, "examples", "rattle_pair.yaml")


# a 3-DOF model: auto (10.1 kHz) and all keep its 3 modes, 2 kHz and 9000 rad/s
# (1.43 kHz) discard the highest (3.8 kHz) into the static correction
@pytest.mark.parametrize("cli,py", [("auto", "auto"), ("all", "all"), ("2kHz", "2kHz"),
                                    ("9000", 9000.0)])
def test_condensed_against_the_cli(geardyn, cli, py):
    args = ["--duration", "30ms", "--record", "mesh:m12:force,g2.rz:speed"]
    j = run_cli("transient", PAIR, "--quiet", "--condense", cli, *args)
    r = geardyn.load(PAIR).transient(duration="30ms", records="mesh:m12:force,g2.rz:speed",
                                     condense=py)
    assert r.method_note == j["method"]
    assert r.nout == j["samples"] and r.free_dofs == j["free_dofs"]
    assert (r.steps, r.rhs_evals, r.events) == (j["steps"], j["rhs_evaluations"], j["events"])
    assert r.names == [x["name"] for x in j["records"]]
    for k, x in enumerate(j["records"]):
        for f in ("min", "max", "mean", "rms", "peak_to_peak", "std"):
            assert same(r.stats[k][f], nums([x[f]])[0]), (x["name"], f)
    for c, x in zip(r.contacts, j["meshes"]):
        assert (c["contact_losses"], c["coast_impacts"], c["drive_impacts"]) == \
            (x["contact_losses"], x["coast_impacts"], x["drive_impacts"])
    jc = j["condensed"]
    for key in ("states", "law_dofs", "modes_kept", "modes_discarded"):
        assert r.condensed[key] == jc[key], key
    for key in ("cutoff_hz", "excitation_hz", "contact_hz", "truncation_estimate"):
        assert same(r.condensed[key], jc[key]), key
    assert r.condensed["modes_discarded"] == (1 if cli in ("2kHz", "9000") else 0)
    assert (r.condensed["cutoff_hz"] == 0) == (cli == "all")


def test_condensed_close_to_the_full_model(geardyn):
    """Every mode kept: the full model's response (the condensation is exact; the two
    integrations of this rattling pair differ by their error control and event times:
    1.8e-5 of the idler's speed, measured)."""
    m = geardyn.load(PAIR)
    full = m.transient(duration="30ms", records="g2.rz:speed", rtol=1e-9)
    cond = m.transient(duration="30ms", records="g2.rz:speed", rtol=1e-9, condense="all")
    assert full.condensed is None and cond.condensed["states"] > 0
    a, b = full.values[0], cond.values[0]
    assert abs(a - b).max() < 1e-4 * abs(a).max()


@pytest.mark.parametrize("bad", ["fast", "-3kHz", 0, float("inf")])
def test_condense_bad_value(geardyn, bad):
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.load(PAIR).transient(duration="30ms", condense=bad)
    assert e.value.field == "condense"


SHAFT = os.path.join(ROOT, "tests", "transient", "condensed_shaft.yaml")


def test_default_condenses_where_it_pays_as_the_cli(geardyn):
    """The CLI's default (docs/transient.md): the 103-DOF shaft model is condensed by the
    cut-off rule without being asked, bit for bit the CLI's; condense="off" and the 3-DOF
    pair keep the full model."""
    args = ["--duration", "5ms", "--record", "mesh:m12:force"]
    j = run_cli("transient", SHAFT, "--quiet", *args)
    m = geardyn.load(SHAFT)
    r = m.transient(duration="5ms", records="mesh:m12:force")
    assert r.condensed is not None and r.condensed["states"] == j["condensed"]["states"]
    assert (r.steps, r.rhs_evals, r.events) == (j["steps"], j["rhs_evaluations"], j["events"])
    for f in ("rms", "peak_to_peak"):
        assert same(r.stats[0][f], nums([j["records"][0][f]])[0]), f
    assert m.transient(duration="5ms", records="mesh:m12:force", condense="off").condensed is None
    assert geardyn.load(PAIR).transient(duration="5ms").condensed is None


def test_prescribed_dof_against_the_cli(geardyn):
    j = run_cli("transient", PRESCRIBED, "--quiet", "--condense", "all", "--duration", "50ms",
                "--record", "mesh:m12:force")
    r = geardyn.load(PRESCRIBED).transient(duration="50ms", records="mesh:m12:force",
                                           condense="all")
    assert r.method_note == j["method"] and "condensed" in r.method_note
    assert r.free_dofs == j["free_dofs"] == 1
    assert (r.steps, r.rhs_evals, r.events) == (j["steps"], j["rhs_evaluations"], j["events"])
    for f in ("min", "max", "mean", "rms", "peak_to_peak", "std"):
        assert same(r.stats[0][f], nums([j["records"][0][f]])[0]), f
