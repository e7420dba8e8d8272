"""Every analysis from Python gives the same numbers as the CLI's --json on the
examples: both call the same library function on the same model, so the numbers must be
identical (compared bit for bit, see conftest.same)."""
import math
import os

import numpy as np
import pytest

from conftest import example, run_cli, nums, same

RIG = example("rig2018")
KUMAR = example("kumar2011_coupled")
KUMAR_T = example("kumar2011_torsional")
CHEN = example("chen1998_gear_pair")
DUFFING = example("duffing")  # a law of the registry (docs/laws.md)
DUCATI = example("ducati_timing_geartrain")


@pytest.mark.parametrize("path,args,kw", [
    (KUMAR, [], {}),
    (KUMAR_T, [], {}),
    (CHEN, [], {}),
    (RIG, ["--speed", "3000rpm", "--modes", "12"], {"speed": "3000rpm", "modes": 12}),
    (CHEN, ["--damped", "--set", "meshes.mesh.stiffness=5e7"], {"kind": "damped"}),
])
def test_modal(geardyn, path, args, kw):
    j = run_cli("modal", path, *args)
    sets = [a for k, a in enumerate(args) if k and args[k - 1] == "--set"]
    m = geardyn.load(path, sets=sets)
    r = m.modal(**kw)
    assert r.nmodes == len(j["modes"]) and r.ndof == j["dofs"] and r.damped == j["damped"]
    assert same(r.speed, j["speed_rad_s"])
    jm = j["modes"]
    for key, col in [("omega_n_rad_s", "omega_n"), ("frequency_hz", "frequency_hz"),
                     ("omega_d_rad_s", "omega_d"), ("damping_ratio", "damping_ratio"),
                     ("log_decrement", "log_decrement"), ("eigenvalue_real", "lambda_re"),
                     ("eigenvalue_imag", "lambda_im")]:
        assert same(getattr(r, col), nums([x[key] for x in jm])), key
    assert r.whirl == [x["whirl"] for x in jm]
    assert r.dominant_motion_names == [x["dominant_motion"] for x in jm]
    comps = m.system.components
    for k, x in enumerate(jm):
        assert bool(r.rigid_body[k]) == x["rigid_body"] and bool(r.unstable[k]) == x["unstable"]
        assert same(r.energy_share[k], nums(x["energy_share"].values()))
        assert same(r.energy_by_component[:, k], nums(x["energy_by_component"].values()))
        assert list(x["energy_by_component"]) == comps
    df = r.to_pandas()
    assert same(df["damped_frequency_hz"], nums([x["damped_frequency_hz"] for x in jm]))


@pytest.mark.parametrize("path,speeds", [(KUMAR, "0:3000rpm:4"), (CHEN, "0:6000rpm:7")])
def test_campbell(geardyn, path, speeds):
    j = run_cli("campbell", path, "--speeds", speeds, "--orders", "2,0.5")
    r = geardyn.load(path).campbell(speeds, orders=[2, 0.5])
    assert same(r.speeds, j["speeds_rad_s"]) and same(r.speeds_rpm, j["speeds_rpm"])
    assert r.ntracks == len(j["modes"])
    for t, jt in enumerate(j["modes"]):
        assert r.tracks[t]["id"] == jt["id"] and r.tracks[t]["whirl"] == jt["whirl"]
        assert r.tracks[t]["dominant_motion"] == jt["dominant_motion"]
        assert same(r.frequency_hz[t], nums(jt["frequency_hz"]))
        assert same(r.natural_frequency_hz[t], nums(jt["natural_frequency_hz"]))
        assert same(r.damping_ratio[t], nums(jt["damping_ratio"]))
        assert same(r.log_decrement[t], nums(jt["log_decrement"]))
    assert len(r.critical_speeds) == len(j["critical_speeds"]) > 0
    for c, jc in zip(r.critical_speeds, j["critical_speeds"]):
        assert c["mode"] == jc["mode"] and c["order"] == jc["order"]
        assert same([c["order_value"], c["speed_rpm"], c["frequency_hz"]],
                    [jc["order_value"], jc["speed_rpm"], jc["frequency_hz"]])
    assert same(r.instability_onset * 30 / math.pi, nums([j["instability_onset_rpm"]])[0])
    assert len(r.to_pandas()) == int(np.sum(r.exists))


def _check_series(res, j):
    ser = res.series()
    assert len(ser) == len(j["outputs"])
    for (name, q, h), jo in zip(ser, j["outputs"]):
        assert name == jo["name"] and q == jo["quantity"]
        assert same(res.freqs, jo["frequency_rad_s"])
        assert same(h.real, nums(jo["real"])) and same(h.imag, nums(jo["imag"]))
        assert same(np.hypot(h.real, h.imag), nums(jo["magnitude"]))


@pytest.mark.parametrize("path,args,kw", [
    (KUMAR, ["--input", "torque:motor", "--output", "mesh:mesh", "--output", "gear.rz",
             "--freq", "100:26000:20"],
     dict(input="torque:motor", outputs=["mesh:mesh", "gear.rz"], freqs="100:26000:20")),
    (KUMAR, ["--input", "torque:motor", "--output", "pinion.y", "--freq", "100:26000:9",
             "--method", "modal", "--type", "mobility"],
     dict(input="torque:motor", outputs=["pinion.y"], freqs="100:26000:9", method="modal",
          quantity="mobility")),
    (CHEN, ["--input", "gear_a.xy", "--output", "gear_b.xy", "--freq", "10:6000:15",
            "--speed", "3000rpm"],
     dict(input="gear_a.xy", outputs=["gear_b.xy"], freqs="10:6000:15", speed="3000rpm")),
    (CHEN, ["--input", "gear_a.x", "--output", "bearing:support_b.y", "--freq", "1Hz:1000Hz:7"],
     dict(input="gear_a.x", outputs="bearing:support_b.y", freqs="1Hz:1000Hz:7")),
])
def test_frf(geardyn, path, args, kw):
    j = run_cli("frf", path, *args)
    r = geardyn.load(path).frf(**kw)
    assert same(r.speed, j["speed_rad_s"]) and r.method == j["method"]
    if r.method == "modal":
        assert r.modes_summed == j["modes_summed"]
    _check_series(r, j)
    assert len(r.to_pandas()) == len(j["outputs"]) * r.nfreq


@pytest.mark.parametrize("path,args,kw", [
    (CHEN, [], {}),
    (KUMAR, ["--output", "pinion.y", "--output", "orbit:gear", "--output", "mesh:mesh"],
     {"outputs": ["pinion.y", "orbit:gear", "mesh:mesh"]}),
])
def test_unbalance(geardyn, path, args, kw):
    j = run_cli("unbalance", path, "--speeds", "100:6000:8", *args)
    r = geardyn.load(path).unbalance("100:6000:8", **kw)
    assert same([h["order"] for h in r.harmonics], [h["order"] for h in j["harmonics"]])
    X = r.response
    k = 0
    for h in range(r.nharmonics):
        for o, name in enumerate(r.outputs):
            jo = j["outputs"][k]
            k += 1
            assert jo["name"] == name and same(jo["harmonic_order"], r.harmonics[h]["order"])
            assert same(r.speeds, jo["speed_rad_s"])
            assert same(X[h, o].real, nums(jo["real"])) and same(X[h, o].imag, nums(jo["imag"]))
    assert k == len(j["outputs"]) > 0
    ob = r.orbits
    k = 0
    for h in range(r.nharmonics):
        for b, node in enumerate(r.orbit_nodes):
            jb = j["orbits"][k]
            k += 1
            assert jb["node"] == node
            assert same(ob[h, b]["major"], nums(jb["major"]))
            assert same(ob[h, b]["minor"], nums(jb["minor"]))
            assert same(np.degrees(ob[h, b]["angle"]), nums(jb["angle_deg"]))
    assert k == len(j["orbits"]) > 0
    assert len(r.to_pandas()) == r.nharmonics * r.noutputs * r.nspeeds


@pytest.mark.parametrize("path,args,kw", [
    (DUCATI, ["--revolutions", "0.2"], {"revolutions": 0.2}),
    (KUMAR_T, ["--duration", "20ms", "--speed", "1000rpm", "--record",
               "mesh:mesh:deflection,ratio:motor/load", "--record", "gear.rz:speed"],
     {"duration": "20ms", "speed": "1000rpm",
      "records": ["mesh:mesh:deflection,ratio:motor/load", "gear.rz:speed"]}),
    # its default records (the law's first) and a law record by name
    (DUFFING, ["--duration", "40"], {"duration": 40}),
    (DUFFING, ["--duration", "40", "--record", "law:cubic:deflection,m.x:vel"],
     {"duration": 40, "records": "law:cubic:deflection,m.x:vel"}),
])
def test_transient(geardyn, path, args, kw):
    j = run_cli("transient", path, "--quiet", *args)
    r = geardyn.load(path).transient(**kw)
    assert same([r.speed, r.t_end, r.record_from, r.output_interval],
                [j["speed_rad_s"], j["t_end_s"], j["record_from_s"], j["output_interval_s"]])
    assert r.nout == j["samples"] and r.free_dofs == j["free_dofs"]
    # both default to auto, and state the same choice (lti on the linear Kumar model)
    assert r.method_note == j["method"] and r.method_note.startswith("auto: ")
    assert r.method_note.startswith("auto: lti") == (path == KUMAR_T)
    assert (r.steps, r.rhs_evals, r.events) == (j["steps"], j["rhs_evaluations"], j["events"])
    assert r.names == [x["name"] for x in j["records"]]
    assert r.units == [x["unit"] for x in j["records"]]
    st = r.stats
    for k, x in enumerate(j["records"]):
        for f in ("min", "max", "mean", "rms", "peak_to_peak", "std"):
            assert same(st[k][f], nums([x[f]])[0]), (x["name"], f)
    assert r.meshes == [x["name"] for x in j["meshes"]]
    for c, x in zip(r.contacts, j["meshes"]):
        assert (c["contact_losses"], c["coast_impacts"], c["drive_impacts"]) == \
            (x["contact_losses"], x["coast_impacts"], x["drive_impacts"])
        assert same([c["separated_time"], c["drive_time"]], [x["separated_time_s"],
                                                             x["drive_time_s"]])
    df = r.to_pandas()
    assert df.shape == (r.nout, r.nrecords) and same(df.iloc[:, 0], r.values[0])


MATHIEU = os.path.join(os.path.dirname(os.path.dirname(CHEN)), "tests", "plot",
                       "mathieu_pair.yaml")


@pytest.mark.parametrize("path,args,kw", [
    # the Chen pair with its damper: stable throughout, two records
    (CHEN, ["--speeds", "600:1400:5", "--harmonics", "5", "--record", "gear_a.x,mesh:mesh:force"],
     {"speeds": "600:1400:5", "harmonics": 5, "records": "gear_a.x,mesh:mesh:force"}),
    # a damped Mathieu pair across its tongue, both directions: unstable points and four
    # period doublings
    (MATHIEU, ["--speeds", "680:730:11", "--harmonics", "4", "--both-directions"],
     {"speeds": "680:730:11", "harmonics": 4, "both_directions": True}),
    # a polynomial spring law: its record and its Jacobian terms in Newton
    (DUFFING, ["--speeds", "1:1:1", "--harmonics", "15", "--record", "m.x,law:cubic"],
     {"speeds": "1:1:1", "harmonics": 15, "records": "m.x,law:cubic"}),
    # shooting: the orbit from the transient integrator, records sampled as HB's
    (CHEN, ["--speeds", "900:1000:2", "--harmonics", "10", "--method", "shooting",
            "--record", "gear_a.x"],
     {"speeds": "900:1000:2", "harmonics": 10, "solver": "shooting", "records": "gear_a.x"}),
    # the defaults (no harmonics, no solver): the CLI's --harmonics auto --method auto
    (CHEN, ["--speeds", "900:1000:2", "--record", "gear_a.x"],
     {"speeds": "900:1000:2", "records": "gear_a.x"}),
    # continuation in the load frequency, downwards through the Duffing hysteresis loop
    (DUFFING, ["--frequency", "1.6:0.5:12", "--harmonics", "7", "--record", "m.x"],
     {"frequency": "1.6:0.5:12", "harmonics": 7, "records": "m.x"}),
])
def test_periodic(geardyn, path, args, kw):
    j = run_cli("periodic", path, *args)
    r = geardyn.load(path).periodic(**kw)
    jp = j["points"]
    assert r.solver == j["method"] == ("shooting" if "--method" in args else "harmonic_balance")
    assert r.npoints == len(jp) and r.steps == j["continuation_steps"]
    assert same(r.speed, nums([p["speed_rad_s"] for p in jp]))
    assert same(r.parameter, nums([p.get("parameter") for p in jp]))
    assert list(r.direction) == [p["direction"] for p in jp]
    assert list(r.converged) == [int(p["converged"]) for p in jp]
    assert list(r.stable) == [-1 if p["stable"] is None else int(p["stable"]) for p in jp]
    assert list(r.harmonics) == [p["harmonics"] for p in jp]
    assert list(r.iterations) == [p["iterations"] for p in jp]
    for key, col in [("floquet_multiplier_max_abs", "mu_max"), ("residual", "residual"),
                     ("omega_rad_s", "omega")]:
        assert same(getattr(r, col), nums([p[key] for p in jp])), key
    for i, p in enumerate(jp):
        mu = r.multipliers(i)
        assert same(mu.real, nums(p["floquet_re"])) and same(mu.imag, nums(p["floquet_im"]))
        assert list(p["records"]) == r.names
        for k, name in enumerate(r.names):
            x = p["records"][name]
            assert same([r.mean[i, k], r.rms[i, k], r.peak_to_peak[i, k]],
                        [x["mean"], x["rms"], x["peak_to_peak"]]), name
            assert same(r.amplitudes[i, k], nums(x["amplitudes"]))
            assert same(r.phases_deg[i, k], nums(x["phases_deg"]))
    jb = j["bifurcations"]
    assert [b["type"] for b in r.bifurcations] == [b["type"] for b in jb]
    for b, x in zip(r.bifurcations, jb):
        assert b["direction"] == x["direction"]
        assert same([b["speed"], b["parameter"], b["multiplier"].real, b["multiplier"].imag],
                    nums([x["speed_rad_s"], x["parameter"], x["multiplier_re"],
                          x["multiplier_im"]]))
    if path == MATHIEU:  # the tongue: 4 unstable points each way, 2 period doublings each
        assert (r.stable == 0).sum() == 8 and len(jb) == 4
    df = r.to_pandas()
    assert len(df) == r.npoints * len(r.names)
    assert same(df["peak_to_peak"], r.peak_to_peak.ravel())
    assert same(df["speed_rad_s"], np.repeat(r.speed, len(r.names)))


@pytest.mark.parametrize("name,args,kw", [
    ("helical_pair1", [], {}),
    ("helical_pair2", ["--method", "iso6336", "--points", "64"],
     {"method": "iso6336", "points": 64}),
])
def test_mesh_stiffness(geardyn, name, args, kw):
    j = run_cli("mesh-stiffness", example(name), *args)
    r = geardyn.mesh_stiffness(example(name), **kw)
    assert r.mesh == j["mesh"] and r.method == j["method"] and list(r.teeth) == j["teeth"]
    assert same(r.angle_rad, j["angle_rad"]) and same(r.stiffness, j["stiffness"])
    assert list(r.pairs_in_contact) == j["pairs_in_contact"]
    assert same(r.load_share, np.array(j["load_share"]))
    for k in ("contact_ratio_transverse", "contact_ratio_face", "contact_ratio_total",
              "mesh_period_rad", "body_stiffness"):
        assert same(getattr(r, k), j[k]), k
    for k in ("mean", "max", "min", "peak_to_peak"):
        assert same(getattr(r, k), j["stiffness_" + k]), k
    assert same([h["amplitude"] for h in r.harmonics], [h["amplitude"] for h in j["harmonics"]])
    assert len(r.to_pandas()) == r.n


@pytest.mark.parametrize("path,speed", [(RIG, "3000rpm"), (CHEN, "0")])
def test_matrices(geardyn, path, speed, tmp_path):
    import json
    import subprocess
    from conftest import BUILD, ROOT
    subprocess.run([BUILD + "/geardyn", "matrices", path, "--format", "json", "--speed", speed,
                    "--out", str(tmp_path / "m")], check=True, cwd=ROOT, capture_output=True)
    j = json.load(open(tmp_path / "m" / "matrices.json"))
    mats = geardyn.load(path).matrices(speed)
    assert mats.dofs == ["%s.%s" % (d["node"], d["dof"]) for d in j["dofs"]]
    for name in "MKCG":
        csc = getattr(mats, name)
        # scipy keeps the C library's arrays (no copy)
        assert csc.nnz == 0 or not (csc.data.flags.owndata or csc.indices.flags.owndata
                                    or csc.indptr.flags.owndata), name
        a, jm = csc.tocoo(), j[name]
        assert a.shape == (jm["size"], jm["size"]) and a.nnz == jm["nnz"]
        assert list(a.row + 1) == jm["rows"] and list(a.col + 1) == jm["cols"], name
        assert same(a.data, jm["values"]), name


def test_transient_error_estimate_and_no_estimate(geardyn):
    """bdf's error estimate (a second run at rtol / 10) bit for bit the CLI's, and
    estimate=False as --no-estimate: no estimate (-1), the same records."""
    args = ("--revolutions", "0.5", "--record", "mesh:m01:force")
    j = run_cli("transient", DUCATI, *args)
    jn = run_cli("transient", DUCATI, *args, "--no-estimate")
    m = geardyn.load(DUCATI)
    r = m.transient(revolutions=0.5, records="mesh:m01:force")
    rn = m.transient(revolutions=0.5, records="mesh:m01:force", estimate=False)
    assert same(r.error_estimate, j["error_estimate"]) and 0 < r.error_estimate < 1
    assert rn.error_estimate == -1 and "error_estimate" not in jn
    assert same(rn.stats[0]["rms"], nums([jn["records"][0]["rms"]])[0])
    assert same(r.stats[0]["rms"], rn.stats[0]["rms"])
