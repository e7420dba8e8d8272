"""Errors are raised as geardyn.ModelError with the C library's file, line, field and
hint, for files, text, overrides, options and models built from dicts."""
import pytest

from conftest import example

BAD = """title: bad bearing
dofs: [x, y, rz]
shafts:
  - name: s
    nodes: [{name: a}]
disks:
  - {name: d, node: a, mass: 1, polar_inertia: 0.01}
bearings:
  - {name: b, node: a, kxx: -5}
"""


def test_bad_text_names_line_and_field(geardyn):
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.loads(BAD, name="bad.yaml")
    err = e.value
    assert err.file == "bad.yaml" and err.line == 9, (err.file, err.line)
    assert "kxx" in err.field and err.hint and err.message
    assert str(err).startswith("bad.yaml:9:")


def test_bad_file_line(geardyn, tmp_path):
    p = tmp_path / "m.yaml"
    p.write_text(BAD.replace("kxx: -5", "kxx: 5, kxyz: 1"))
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.load(p)
    assert e.value.line == 9 and e.value.file == str(p) and "kxyz" in str(e.value)


def test_missing_file(geardyn):
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.load(example("missing"))
    assert e.value.status == "i/o error" or "missing" in str(e.value)


def test_bad_override_path_and_value(geardyn):
    m = geardyn.load(example("kumar2011_coupled"))
    with pytest.raises(geardyn.ModelError) as e:
        m.set("meshes.nope.stiffness", 3e8)
    assert e.value.file.startswith("--set") and "mesh" in e.value.hint
    with pytest.raises(geardyn.ModelError) as e:
        m.set("meshes.mesh.stiffness", -1)
    assert "stiffness" in e.value.field
    # a failed set leaves the model as it was
    assert m.modal().omega_n[3] == geardyn.load(example("kumar2011_coupled")).modal().omega_n[3]


def test_bad_options(geardyn):
    m = geardyn.load(example("kumar2011_coupled"))
    with pytest.raises(geardyn.ModelError, match="unknown node 'nope'"):
        m.frf("nope.x", "gear.x", [1.0, 2.0])
    with pytest.raises(geardyn.ModelError, match="not active"):
        m.frf("motor.x", "gear.x", [1.0])
    with pytest.raises(geardyn.ModelError, match="FROM:TO:COUNT"):
        m.campbell("0:100")
    with pytest.raises(geardyn.ModelError) as e:
        m.modal(speed="fast")
    assert e.value.field == "speed"
    with pytest.raises(geardyn.ModelError, match="unknown mesh quantity"):
        m.transient(duration=0.01, records="mesh:mesh:torque")
    # periodic: a total angle has no periodic steady state; options checked as the CLI
    with pytest.raises(geardyn.ModelError, match="no periodic steady state"):
        m.periodic("100:200:2", records="gear.rz:angle")
    with pytest.raises(geardyn.ModelError, match="unknown method"):
        m.periodic("100:200:2", method="newton")
    with pytest.raises(geardyn.ModelError, match="unknown solver") as e:
        m.periodic("100:200:2", solver="collocation")
    assert e.value.field == "solver"
    with pytest.raises(geardyn.ModelError, match="CPU seconds"):
        m.periodic("100:200:2", solver="shooting", shoot_budget=0)
    with pytest.raises(geardyn.ModelError, match="CPU seconds") as e:
        m.periodic("100:200:2", floquet_budget=-1)
    assert e.value.field == "floquet_budget"
    with pytest.raises(geardyn.ModelError, match="cannot resolve"):
        m.periodic("100:200:2", harmonics=10, samples=8)
    # the library's bound (2^31 - 1 samples asked for about 100 GB), issue 23
    with pytest.raises(geardyn.ModelError, match="1048576") as e:
        m.periodic("100:200:2", harmonics=10, samples=2**31 - 1)
    assert e.value.field == "samples"


def test_builder_errors(geardyn):
    spec = {"shafts": [{"name": "s", "nodes": [{"name": "a"}]}],
            "disks": [{"node": "a", "mass": 1}],
            "bearings": [{"node": "a", "kxx": -1}]}
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.build(spec, name="rig.py")
    assert e.value.field == "bearings[0].kxx" and e.value.file == "rig.py" and e.value.line == 0
    spec["bearings"] = [{"node": "a", "kx": 1}]
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.build(spec)
    assert e.value.field == "bearings[0].kx" and "kxx" in e.value.hint
    spec["bearings"] = [{"node": "b", "k": 1e6}]
    with pytest.raises(geardyn.ModelError) as e:
        geardyn.build(spec)
    assert "b" in e.value.message and e.value.field.startswith("bearings[0]")


def test_probe_syntax_from_the_element_table(geardyn):
    # the prefixes (mesh:, bearing:) and the names in the hints come from the element
    # kinds' probe vocabulary and the system's components, not from a hand list
    m = geardyn.load(example("chen1998_gear_pair"))
    with pytest.raises(geardyn.ModelError, match="unknown bearing 'Z9'") as e:
        m.frf("gear_a.x", "bearing:Z9.x", [1.0])
    assert e.value.hint == "bearings: support_a, support_b", e.value.hint
    with pytest.raises(geardyn.ModelError, match="unknown mesh 'gear'") as e:
        m.frf("gear_a.x", "mesh:gear", [1.0])
    assert e.value.hint == "meshes: mesh", e.value.hint
    with pytest.raises(geardyn.ModelError, match="is not bearing:NAME.DIR"):
        m.frf("gear_a.x", "bearing:support_a", [1.0])
    with pytest.raises(geardyn.ModelError, match="unknown direction 'w'"):
        m.frf("gear_a.x", "bearing:support_a.w", [1.0])
    r = m.frf("gear_a.x", ["bearing:support_b.y", "mesh:mesh"], [10.0])
    assert r.H.shape[0] == 2
