"""The static analysis from Python: the same numbers as `geardyn static --json` (one
library call on the same model, compared bit for bit), and the rig's torque balance."""
import math

import numpy as np

from conftest import example, run_cli, nums, same

RIG = example("rig2018")
HELICAL = example("helical_two_stage")


def test_static_matches_cli(geardyn):
    for path, args, kw in [(RIG, ["--torque", "20"], {"torque": 20.0}),
                           (HELICAL, [], {}),
                           (RIG, ["--torque", "20N*m", "--no-gravity", "--hold", "brg_n1"],
                            {"torque": "20 N*m", "gravity": False, "hold": "brg_n1"})]:
        j = run_cli("static", path, *args)
        r = geardyn.load(path).static(**kw)
        same(r.force, nums([m["force_N"] for m in j["meshes"]]))
        same(r.f_sh, nums([m["f_sh_m"] for m in j["meshes"]]))
        same(r.tilt_in_plane, nums([m["tilt_in_plane_rad"] for m in j["meshes"]]))
        same(r.bearing_force, np.array([b["force_N"] for b in j["bearings"]], dtype=float))
        same(r.bearing_moment, np.array([b["moment_N_m"] for b in j["bearings"]], dtype=float))
        nodes = r.to_pandas()
        for d in ("x", "y", "rx", "ry", "rz"):
            same(nodes[d].to_numpy(), nums([n[d] for n in j["nodes"]]))
        assert [h[0] for h in r.holds] == [h["node"] for h in j["holds"]]
        same(np.array([h[3] for h in r.holds]), nums([h["reaction"] for h in j["holds"]]))


def test_rig_torque_balance(geardyn):
    r = geardyn.load(RIG).static(torque=20.0, gravity=False)
    assert math.isclose(r.force[0], 20 / 0.048, rel_tol=1e-12)
    assert r.holds[0][:3] == ("brg_n2", "rz", "torque")
    assert math.isclose(abs(r.holds[0][3]), 20 * 32 / 48, rel_tol=1e-9)
    # each bearing carries half the mesh force
    assert np.allclose(np.hypot(r.bearing_force[:, 0], r.bearing_force[:, 1]), 10 / 0.048,
                       rtol=1e-9)


def test_journal_rotor_on_its_laws(geardyn):
    """A rotor held by its journal bearings alone: the laws' records equal the CLI's bit
    for bit, and their vertical forces add up to the 40 kg rotor's weight."""
    path = example("journal_rotor")
    j = run_cli("static", path, "--speed", "1000")
    r = geardyn.load(path).static(speed=1000.0)
    assert list(r.laws) == [law["name"] for law in j["laws"]]
    for law in j["laws"]:
        assert r.laws[law["name"]]["type"] == "journal_bearing"
        for key, value in law["records"].items():
            same(np.array([r.laws[law["name"]][key]]), nums([value]))
    assert math.isclose(sum(v["fy"] for v in r.laws.values()), 40 * 9.81, rel_tol=1e-9)
    # the laws' forces on the DOFs: the weight up, nothing sideways (x forces are ~1e-9 N)
    assert math.isclose(float(np.sum(r.law_forces)), 40 * 9.81, rel_tol=1e-9)


def test_component_kinds_from_the_registry(geardyn):
    """Each strain-energy component's element kind comes from the C element registry."""
    s = geardyn.load(RIG).system
    assert list(zip(s.components, s.component_kinds)) == [
        ("driving", "shaft"), ("driven", "shaft"), ("A1", "bearing"), ("A2", "bearing"),
        ("B1", "bearing"), ("B2", "bearing"), ("mesh", "mesh")]
