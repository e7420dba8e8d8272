"""The model's laws (rolling bearings from geometry) linearised about the static
equilibrium in Python as in the CLI (`--operating-point static`, the default;
docs/bearings.md): modal, campbell, frf and unbalance. Python linearised them at q = 0,
where a ball bearing with clearance holds nothing, so rig2018_geometry's modes were
rigid-body (0 Hz) where `geardyn modal` gives 123.02 Hz."""
import pytest

from conftest import example, run_cli, nums, same

GEOMETRIC = example("rig2018_geometry")


def test_modal_as_the_cli(geardyn):
    j = run_cli("modal", GEOMETRIC, "--modes", "4")
    r = geardyn.load(GEOMETRIC).modal(modes=4)
    assert same(r.frequency_hz, nums([x["frequency_hz"] for x in j["modes"]]))
    assert r.frequency_hz[1] == pytest.approx(123.02, abs=0.01)
    # with --torque: the same state as the CLI's
    j = run_cli("modal", GEOMETRIC, "--modes", "4", "--torque", "50")
    r = geardyn.load(GEOMETRIC).modal(modes=4, torque="50 N*m")
    assert same(r.frequency_hz, nums([x["frequency_hz"] for x in j["modes"]]))
    # q = 0, asked for: the clearance holds nothing (as --operating-point zero)
    j = run_cli("modal", GEOMETRIC, "--modes", "4", "--operating-point", "zero")
    r = geardyn.load(GEOMETRIC).modal(modes=4, operating_point="zero")
    assert same(r.frequency_hz, nums([x["frequency_hz"] for x in j["modes"]]))
    assert list(r.frequency_hz) == [0.0, 0.0, 0.0, 0.0]


def test_sweeps_as_the_cli(geardyn):
    m = geardyn.load(GEOMETRIC)
    j = run_cli("campbell", GEOMETRIC, "--speeds", "0:3000rpm:2", "--modes", "3")
    c = m.campbell("0:3000rpm:2", modes=3)
    for k, t in enumerate(j["modes"]):
        assert same(c.frequency_hz[k], nums(t["frequency_hz"]))
    assert c.frequency_hz[0][0] == pytest.approx(123.02, abs=0.01)
    j = run_cli("frf", GEOMETRIC, "--input", "gear48.x", "--output", "gear48.x",
                "--freq", "100:1000:3")
    f = m.frf("gear48.x", "gear48.x", "100:1000:3")
    assert same(abs(f.H[0][0]), nums(j["outputs"][0]["magnitude"]))


def test_bad_operating_point_is_named(geardyn):
    m = geardyn.load(GEOMETRIC)
    with pytest.raises(geardyn.ModelError) as e:
        m.modal(operating_point="rest")
    assert e.value.field == "operating_point"


def test_campbell_default_mode_count_as_the_cli(geardyn):
    """campbell() without modes tracks the CLI's default count (the rig: 31 modes up to
    1.25 x its 48x mesh order at 6000 rpm), not 12."""
    rig = example("rig2018")
    j = run_cli("campbell", rig, "--speeds", "0:6000rpm:3")
    c = geardyn.load(rig).campbell("0:6000rpm:3")
    assert c.ntracks == len(j["modes"]) == 31
    for k, t in enumerate(j["modes"]):
        assert same(c.frequency_hz[k], nums(t["frequency_hz"]))
