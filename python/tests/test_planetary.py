"""Planetary sets from Python (docs/python.md, "Planetary sets"; docs/planetary.md): a set
built from a dict equals the same set loaded from YAML bit for bit, and every analysis on
the examples with sets gives the CLI's numbers bit for bit (conftest.same): modal with the
mode classes, static load sharing, Campbell over carrier speed, the set's kinematics."""
import copy
import math

import numpy as np
import pytest

from conftest import example, run_cli, nums, same

LP = example("planetary_lin_parker")
CP = example("planetary_cooley_parker")
PHASING = example("planetary_phasing")

# examples/planetary_lin_parker.yaml as a dict
LP_DICT = {
    "title": "Lin & Parker (1999) planetary gear, N = 4",
    "dofs": ["x", "y", "rz"],
    "shafts": [{"name": "sun_shaft", "nodes": [{"name": "sun"}]},
               {"name": "ring_body", "nodes": [{"name": "ring"}]},
               {"name": "carrier_shaft", "nodes": [{"name": "carrier"}]}],
    "planetary_sets": [{
        "name": "lp", "held": "ring",
        "sun": {"node": "sun", "mass": 0.4, "inertia": 5.840991e-4, "k_support": 1e8},
        "ring": {"node": "ring", "mass": 2.35, "inertia": 0.05671875, "k_support": 1e8,
                 "k_torsion": 1.890625e7},
        "carrier": {"node": "carrier", "mass": 5.43, "inertia": 0.0491535824, "k_support": 1e8},
        "planets": {"count": 4, "mass": 0.66, "inertia": 1.534163725e-3,
                    "bearing_stiffness": 1e8},
        "base_radius": {"sun": "38.7 mm", "ring": "137.5 mm", "planet": "50.15 mm"},
        "carrier_radius": "88.4 mm", "pressure_angle": "24.6 deg", "mesh_stiffness": 5e8}],
}
PIN = "planetary_sets.lp.planets.pin_errors=[20 um, 0, 0, 0]"


def _same_matrices(a, b):
    ma, mb = a.matrices(), b.matrices()
    assert ma.dofs == mb.dofs
    for name in "MKCG":
        x, y = getattr(ma, name).tocoo(), getattr(mb, name).tocoo()
        assert list(x.row) == list(y.row) and list(x.col) == list(y.col), name
        assert np.array_equal(x.data, y.data), name


def test_dict_equals_the_file(geardyn):
    """The builder path (gd_model_add_planetary) and the file reader give one model."""
    a, b = geardyn.build(LP_DICT), geardyn.load(LP)
    assert a.planetary_sets == b.planetary_sets == ["lp"]
    assert a.nodes == b.nodes and "lp.p4" in a.nodes
    _same_matrices(a, b)
    # unequal angles and pin errors, the same through both paths
    d = copy.deepcopy(LP_DICT)
    d["planetary_sets"][0]["planets"].update(
        {"angles": [0, "80 deg", "170 deg", "265 deg"], "pin_errors": ["20 um", 0, 0, 0]})
    f = geardyn.load(LP, sets=["planetary_sets.lp.planets.angles=[0, 80 deg, 170 deg, 265 deg]",
                               PIN])
    _same_matrices(geardyn.build(d), f)
    ra = geardyn.build(d).static(torque=100, input="sun", hold="carrier").planetary[0]
    rb = f.static(torque=100, input="sun", hold="carrier").planetary[0]
    assert ra["load_sharing_factor"] == rb["load_sharing_factor"]
    assert np.array_equal(ra["sun_mesh_force"], rb["sun_mesh_force"])


def test_modal_classes_against_the_cli(geardyn):
    """`geardyn modal examples/planetary_lin_parker.yaml --json`: every frequency and
    class, bit for bit; Table 2's counts (rotational 6, translational 12, planet 3)."""
    j = run_cli("modal", LP)
    r = geardyn.load(LP).modal()
    jm = j["modes"]
    assert r.nmodes == len(jm) == 21
    assert same(r.frequency_hz, nums([x["frequency_hz"] for x in jm]))
    assert same(r.omega_n, nums([x["omega_n_rad_s"] for x in jm]))
    assert r.classes == [x["class"] for x in jm]
    assert r.planetary_classes == {"lp": [x["planetary_classes"]["lp"] for x in jm]}
    counts = {c: r.classes.count(c) for c in set(r.classes)}
    assert counts == {"rotational": 6, "translational": 12, "planet": 3}
    assert list(r.to_pandas()["class"]) == r.classes
    # a set built in code: the same modes, and with unequal spacing the mixed classes
    rd = geardyn.build(LP_DICT).modal()
    assert np.array_equal(rd.frequency_hz, r.frequency_hz) and rd.classes == r.classes
    d = copy.deepcopy(LP_DICT)
    d["planetary_sets"][0]["planets"]["angles"] = [0, "80 deg", "170 deg", "265 deg"]
    ru = geardyn.build(d).modal()
    assert ru.classes.count("planet") == 3 and ru.classes.count("mixed") == 17
    planet = ru.frequency_hz[[c == "planet" for c in ru.classes]]
    assert np.allclose(planet, r.frequency_hz[[c == "planet" for c in r.classes]], rtol=1e-9)


def test_static_load_sharing_against_the_cli(geardyn):
    """docs/planetary.md's pin-error case: K_gamma 1.38, planet 1 274 N."""
    j = run_cli("static", LP, "--torque", "100N*m", "--input", "sun", "--hold", "carrier",
                "--set", PIN)
    r = geardyn.load(LP, sets=[PIN]).static(torque="100 N*m", input="sun", hold="carrier")
    (p,), (jp,) = r.planetary, j["planetary_sets"]
    assert p["name"] == jp["name"] == "lp"
    assert same(p["load_sharing_factor"], jp["load_sharing_factor"])
    for key in ("sun_mesh_force", "ring_mesh_force", "bearing_force"):
        assert same(p[key], nums(jp[key + "_N"])), key
    assert abs(p["load_sharing_factor"] - 1.38) < 0.005 and abs(p["sun_mesh_force"][0] - 274) < 1
    # a perfect set shares equally: T / (N r_s)
    q = geardyn.load(LP).static(torque=100, input="sun", hold="carrier").planetary[0]
    assert np.allclose(q["sun_mesh_force"], 100 / (4 * 0.0387), rtol=1e-9)
    assert abs(q["load_sharing_factor"] - 1) < 1e-9


def test_campbell_over_carrier_speed_against_the_cli(geardyn):
    """Cooley & Parker's set, the carrier the reference shaft: the gyroscopic splitting
    of the translational pairs, every track bit for bit."""
    speeds = "0:5000rpm:3"
    j = run_cli("campbell", CP, "--speeds", speeds)
    r = geardyn.load(CP).campbell(speeds)
    assert r.ntracks == len(j["modes"])
    for t, jt in enumerate(j["modes"]):
        assert same(r.frequency_hz[t], nums(jt["frequency_hz"]))
        assert same(r.damping_ratio[t], nums(jt["damping_ratio"]))
    # at rest the lowest translational pair is one frequency (265.7 Hz); at 5000 rpm of
    # the carrier it splits (200.8 and 287.0 Hz, docs/planetary.md)
    m0 = geardyn.load(CP).modal(speed=0)
    m1 = geardyn.load(CP).modal(speed="5000 rpm")
    pair0 = sorted(f for f, c in zip(m0.frequency_hz, m0.classes) if c == "translational")[:2]
    assert abs(pair0[0] - pair0[1]) < 1e-6 * pair0[0] and abs(pair0[0] - 265.7) < 0.1
    f1 = m1.frequency_hz
    assert np.min(np.abs(f1 - 200.8)) < 0.1 and np.min(np.abs(f1 - 287.0)) < 0.1


def test_frf_and_kinematics_against_the_cli(geardyn):
    """A loaded model with a set in the FRF (sun torque to planet 1) and the set's
    kinematics against `geardyn check --json`."""
    args = ["--input", "torque:sun", "--output", "lp.p1.x", "--output", "carrier.rz",
            "--freq", "500Hz:8500Hz:9"]
    j = run_cli("frf", PHASING, *args)
    r = geardyn.load(PHASING).frf("torque:sun", ["lp.p1.x", "carrier.rz"], "500Hz:8500Hz:9")
    for (name, _q, h), jo in zip(r.series(), j["outputs"]):
        assert name == jo["name"]
        assert same(h.real, nums(jo["real"])) and same(h.imag, nums(jo["imag"]))
    jc = run_cli("check", PHASING)["planetary_sets"][0]
    k = geardyn.load(PHASING).planetary("lp")
    assert k["planets"] == ["lp.p%d" % (n + 1) for n in range(jc["planets"])]
    assert same(np.degrees(k["angles"]), nums(jc["angles_deg"]))
    assert k["held"] == jc["held"] and k["equally_spaced"] == jc["equally_spaced"]
    kin = k["kinematics"]
    for member in ("sun", "ring", "carrier"):
        assert same(kin["speed"][member], jc["speed_per_input"][member]), member
    assert same(kin["planet_speed"], jc["speed_per_input"]["planets"])
    assert same(kin["assembly"], nums(jc["assembly"])) and kin["assembles"] == jc["assembles"]
    assert same(k["mesh_stiffness"]["sun"], jc["meshes"][0]["stiffness"])


def test_dict_errors_name_the_field(geardyn):
    d = copy.deepcopy(LP_DICT)
    d["planetary_sets"][0]["planets"]["pin_errors"] = [0, 0]
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.build(d)
    assert e.value.field == "planetary_sets[0].planets.pin_errors"
    d = copy.deepcopy(LP_DICT)
    d["planetary_sets"][0]["geometry"] = {"module": "3 mm"}
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.build(d)
    assert e.value.field == "planetary_sets[0].geometry"
    d = copy.deepcopy(LP_DICT)
    d["planetary_sets"][0]["held"] = "moon"
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.build(d)
    assert e.value.field == "planetary_sets[0].held"
    # the library's own checks, located at the spec's path: planets too close
    d = copy.deepcopy(LP_DICT)
    d["planetary_sets"][0]["planets"]["angles"] = [0, "200 deg", "100 deg", "300 deg"]
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.build(d)
    assert e.value.field.startswith("planetary_sets[0].planets")
    with pytest.raises(geardyn.ModelError):
        geardyn.load(LP).planetary("nope")


@pytest.mark.parametrize("harmonic,excited", [(1, "translational"), (2, "planet"),
                                              (4, "rotational")])
def test_phased_mesh_excitation_against_the_cli(geardyn, harmonic, excited):
    """`frf --input planetary:lp:sun_mesh:L` ([Parker2000], docs/planetary.md "Planet
    phasing"): bit for bit, and Z_s = 21, N = 4 selects the class: L = 1 translational
    (the sun does not turn), 2 planet (the sun still), 4 rotational (the sun does not
    translate)."""
    inp = "planetary:lp:sun_mesh:%d" % harmonic
    outs = ["sun.x", "sun.rz", "lp.p1.x"]
    j = run_cli("frf", PHASING, "--input", inp, "--output", "sun.x", "--output", "sun.rz",
                "--output", "lp.p1.x", "--freq", "500Hz:8500Hz:5")
    r = geardyn.load(PHASING).frf(inp, outs, "500Hz:8500Hz:5")
    ser = r.series()
    assert len(ser) == len(j["outputs"]) == 3
    for (name, _q, h), jo in zip(ser, j["outputs"]):
        assert name == jo["name"]
        assert same(h.real, nums(jo["real"])) and same(h.imag, nums(jo["imag"]))
    sx, srz, p1 = (abs(h) for _n, _q, h in ser)
    rs = 0.0387  # the sun's rotation as a length r_s theta
    if excited == "translational":
        assert (rs * srz).max() < 1e-9 * sx.max()
    elif excited == "planet":
        assert max(sx.max(), (rs * srz).max()) < 1e-9 * p1.max()
    else:
        assert sx.max() < 1e-9 * (rs * srz).max()
    with pytest.raises(geardyn.ModelError):
        geardyn.load(PHASING).frf("planetary:lp:moon_mesh:1", outs, "500Hz:8500Hz:5")


def test_transient_with_planetary_mesh_laws_against_the_cli(geardyn):
    """The sets' meshes as laws (TVMS and backlash from the geometry) in time integration:
    the meshes numbered after the gear meshes ("st.sun_mesh1" ...: gd_model_mesh_name),
    the default records and a record by name, bit for bit."""
    path = example("planetary_mesh_laws")
    for args, kw in (([], {}), (["--record", "mesh:st.sun_mesh1:force,mesh:st.ring_mesh3"],
                                {"records": "mesh:st.sun_mesh1:force,mesh:st.ring_mesh3"})):
        j = run_cli("transient", path, "--quiet", "--duration", "5ms", *args)
        r = geardyn.load(path).transient(duration="5ms", **kw)
        assert r.names == [x["name"] for x in j["records"]]
        assert r.meshes == [x["name"] for x in j["meshes"]] and len(r.meshes) == 6
        assert (r.steps, r.rhs_evals, r.events) == (j["steps"], j["rhs_evaluations"],
                                                    j["events"])
        for k, x in enumerate(j["records"]):
            for f in ("min", "max", "mean", "rms", "peak_to_peak"):
                assert same(r.stats[k][f], nums([x[f]])[0]), (x["name"], f)
