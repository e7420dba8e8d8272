"""geardyn.contact_analysis and geardyn.harris_map against `geardyn mesh-stiffness ... --load
/ --load-range ... --json` of the same build: the same library calls on the same input,
so the same doubles (conftest.same: cJSON's print tolerance only)."""
import numpy as np
import pytest

from conftest import example, run_cli, same

RELIEF = "meshes.mesh.geometry.driver.modifications.tip_relief.amount"


@pytest.mark.parametrize("name,args,kw", [
    # the file's load (100 N m) and relief
    ("rig2018_pair_relief", [], {}),
    # another load and a smaller driver relief, through --set
    ("rig2018_pair_relief", ["--load", "50 N m", "--set", RELIEF + "=5 um"],
     {"load": "50 N m", "sets": {RELIEF: "5 um"}}),
    # a helical pair, misaligned: K_Hbeta > 1
    ("helical_pair1", ["--load", "200 N m", "--misalignment", "10 um", "--slices", "20",
                       "--points", "64"],
     # "10 um" as the CLI parses it (10 * 1e-6 is one rounding unit off 10e-6)
     {"load": 200, "misalignment": "10 um", "slices": 20, "points": 64}),
])
def test_contact_analysis(geardyn, name, args, kw):
    j = run_cli("mesh-stiffness", example(name), *args)
    r = geardyn.contact_analysis(example(name), **kw)
    assert j["analysis"] == "contact_analysis"
    assert r.mesh == j["mesh"] and r.method == j["method"] and r.slices == j["slices"]
    for k, jk in (("torque", "torque_N_m"), ("force", "normal_force_N"),
                  ("misalignment", "misalignment_m"), ("mesh_period_rad", "mesh_period_rad"),
                  ("ste_mean", "ste_mean"), ("ste_peak_to_peak", "ste_peak_to_peak"),
                  ("stiffness_mean", "stiffness_mean"), ("stiffness_min", "stiffness_min"),
                  ("stiffness_max", "stiffness_max"),
                  ("face_load_factor_cycle", "face_load_factor"),
                  ("body_stiffness", "body_stiffness"), ("slice_width", "slice_width_m")):
        assert same(getattr(r, k), j[jk]), k
    assert r.flagged == j["flagged_positions"]
    for k in ("angle_rad", "ste", "ste_unloaded", "stiffness"):
        assert same(getattr(r, k), j[k]), k
    assert same(r.face_load_factor, j["face_load_factor_at"])
    assert list(r.pairs_in_contact) == j["pairs_in_contact"] and list(r.flags) == j["flags"]
    assert same(r.pair_load, np.array(j["pair_load"]))
    assert same(r.line_load, np.array(j["line_load"]))
    assert same(r.line_load_mean, j["line_load_mean"])
    # the pairs carry the normal load at every position (the contact problem's balance;
    # 1e-9 relative: the solve's rounding)
    assert np.allclose(r.pair_load.sum(axis=1), r.force, rtol=1e-9, atol=0)
    # the line loads integrate to it too
    assert np.allclose(r.line_load.sum(axis=1) * r.slice_width, r.force, rtol=1e-9, atol=0)
    assert len(r.to_pandas()) == r.n
    if name == "helical_pair1":
        assert r.face_load_factor_cycle > 1.2  # 1.33: 10 um tilts the load to one face end


def test_harris_map(geardyn):
    path = example("rig2018_pair_relief")
    j = run_cli("mesh-stiffness", path, "--load-range", "20Nm:200Nm:10")
    m = geardyn.harris_map(path, np.linspace(20, 200, 10))
    assert j["analysis"] == "harris_map" and m.nloads == 10
    assert same(m.torque, j["torque_N_m"])
    for k in ("ste_peak_to_peak", "ste_mean", "stiffness_mean", "face_load_factor"):
        assert same(getattr(m, k), j[k]), k
    assert list(m.flagged) == j["flagged_positions"]
    assert same(m.ste, np.array(j["ste"])) and same(m.ste_unloaded, j["ste_unloaded"])
    # the relief is sized for 100 N m: the smallest peak-to-peak TE is there (Harris map)
    assert m.torque[int(np.argmin(m.ste_peak_to_peak))] == 100
    # one load of the map is the contact analysis at that load
    r = geardyn.contact_analysis(path, load="100 N m")
    assert same(m.ste_peak_to_peak[4], r.ste_peak_to_peak)
    assert same(m.ste[4], r.ste[:r.points])
    assert len(m.to_pandas()) == 10


def test_contact_errors(geardyn):
    # no `stiffness: {from: contact_analysis}` in the file and no load given
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.contact_analysis(example("helical_pair1"))
    assert e.value.field == "load"
    with pytest.raises(geardyn.ModelError):
        geardyn.contact_analysis(example("rig2018_pair_relief"), load="fast")
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.harris_map(example("rig2018_pair_relief"), [50, -10])
    # a relief past a tenth of the module is refused where the file is read
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.contact_analysis(example("rig2018_pair_relief"), sets={RELIEF: "300 um"})
    assert "tip_relief.amount" in e.value.field


def test_contact_figures(geardyn):
    plotly = pytest.importorskip("plotly")
    path = example("rig2018_pair_relief")
    r = geardyn.contact_analysis(path)
    fig = r.plot()
    assert isinstance(fig, plotly.graph_objects.Figure)
    # the loaded and no-load TE in um over the driver angle in degrees
    assert np.allclose(np.asarray(fig.data[0].x), np.degrees(r.angle_rad), rtol=1e-15)
    assert np.allclose(np.asarray(fig.data[0].y), r.ste * 1e6, rtol=1e-15)
    assert np.allclose(np.asarray(fig.data[1].y), r.ste_unloaded * 1e6, rtol=1e-15)
    m = geardyn.harris_map(path, [50, 100, 150])
    fig = m.plot()
    assert np.array_equal(np.asarray(fig.data[0].x), m.torque)
    assert np.allclose(np.asarray(fig.data[0].y), m.ste_peak_to_peak * 1e6, rtol=1e-15)
    assert "nloads=3" in repr(m) and "ste_peak_to_peak" in dir(m)
