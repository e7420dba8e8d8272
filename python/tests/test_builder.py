"""A model built from Python dicts through the C builder API equals the same model read
from its YAML file: same system matrices and modes, bit for bit."""
import numpy as np

from conftest import example

KUMAR = {
    "dofs": ["x", "y", "rz"],
    "shafts": [{"name": "input", "nodes": [{"name": "motor"}, {"name": "pinion"}]},
               {"name": "output", "nodes": [{"name": "gear"}, {"name": "load"}]}],
    "disks": [{"name": "motor", "node": "motor", "polar_inertia": 0.0115},
              {"name": "pinion", "node": "pinion", "mass": 1.84, "polar_inertia": 0.001821},
              {"name": "gear", "node": "gear", "mass": 0.92, "polar_inertia": 0.001016},
              {"name": "load", "node": "load", "polar_inertia": 0.00575}],
    "bearings": [{"name": "pinion_bearing", "node": "pinion", "k": "2.75e9 N/m"},
                 {"name": "gear_bearing", "node": "gear", "k": 2.75e9}],
    "springs": [{"name": "input_shaft", "node": "motor", "to": "pinion", "dof": "rz",
                 "stiffness": "115 N*m/rad"},
                {"name": "output_shaft", "node": "gear", "to": "load", "dof": "rz",
                 "stiffness": 115}],
    "meshes": [{"name": "mesh", "driver": "pinion", "driven": "gear",
                "base_radius": [0.0445, 0.047], "pressure_angle": 0, "line_of_centres": 0,
                "stiffness": 2e8, "coupling": "lateral-torsional"}],
    "unbalances": [{"name": "pinion_unbalance", "node": "pinion", "amount": "0.0003 kg*m"},
                   {"name": "gear_unbalance", "node": "gear", "amount": 0.00028}],
}


def _same_matrices(a, b):
    for x, y in zip(a[:4], b[:4]):
        assert (x != y).nnz == 0 and x.nnz == y.nnz
    assert a.dofs == b.dofs


def test_dict_equals_file(geardyn):
    built = geardyn.build(KUMAR)
    read = geardyn.load(example("kumar2011_coupled"))
    _same_matrices(built.matrices(), read.matrices())
    assert np.array_equal(built.modal().omega_n, read.modal().omega_n)
    a, b = built.unbalance("100:6000:5"), read.unbalance("100:6000:5")
    assert np.array_equal(a.response, b.response)


def test_flexible_shafts_and_set_on_dict(geardyn):
    steel = {"density": 7850, "E": "206 GPa", "poisson": 0.3}
    spec = {
        "materials": {"steel": steel},
        "shafts": [{"name": "s1", "material": "steel", "elements_per_section": 4,
                    "sections": [{"length": 0.25, "outer_diameter": "25.4 mm"},
                                 {"length": 0.25, "outer_diameter": "25.4 mm"}],
                    "nodes": [{"name": "b1", "at": 0}, {"name": "g1", "at": 0.25},
                              {"name": "b2", "at": 0.5}]}],
        "disks": [{"name": "d", "node": "g1", "mass": 2.0, "polar_inertia": 0.01}],
        "bearings": [{"name": "B1", "node": "b1", "k": 1e7, "k_torsion": 1e3},
                     {"name": "B2", "node": "b2", "k": 1e7}],
        "speed": "3000 rpm",
    }
    m = geardyn.build(spec)
    assert abs(m.speed - 100 * np.pi) < 1e-12 and len(m.nodes) == 9
    f0 = m.modal(speed=0, modes=4).omega_n
    yaml = ("materials: {steel: {density: 7850, E: 206 GPa, poisson: 0.3}}\n"
            "shafts:\n  - {name: s1, material: steel, elements_per_section: 4,\n"
            "     sections: [{length: 0.25, outer_diameter: 25.4 mm},"
            " {length: 0.25, outer_diameter: 25.4 mm}],\n"
            "     nodes: [{name: b1, at: 0}, {name: g1, at: 0.25}, {name: b2, at: 0.5}]}\n"
            "disks: [{name: d, node: g1, mass: 2.0, polar_inertia: 0.01}]\n"
            "bearings: [{name: B1, node: b1, k: 1e7, k_torsion: 1e3},"
            " {name: B2, node: b2, k: 1e7}]\nspeed: 3000 rpm\n")
    y = geardyn.loads(yaml)
    _same_matrices(m.matrices(m.speed), y.matrices(y.speed))
    # `set` on a dict model edits a copy of the dict and rebuilds; the file model's
    # override of the same path gives the same model
    m.set("bearings.*.k", 2e7)
    y.set("bearings.*.k", 2e7)
    _same_matrices(m.matrices(), y.matrices())
    assert m.modal(speed=0, modes=4).omega_n.sum() > f0.sum() * 1.01
    assert spec["bearings"][0]["k"] == 1e7  # the caller's dict is untouched


def test_example_script_tables():
    """python/examples/kumar_tables.py (run by `make demo`) prints both tables."""
    import os
    import subprocess
    import sys
    from conftest import ROOT
    out = subprocess.run([sys.executable, "python/examples/kumar_tables.py", "--table-only"],
                         cwd=ROOT, check=True, capture_output=True, text=True,
                         env=dict(os.environ, PYTHONPATH="python")).stdout
    assert "Table 3.1" in out and "Table 3.2" in out
    assert "23288.5" in out and "25542.7" in out  # the mesh modes of the two tables
