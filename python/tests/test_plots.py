"""result.plot(): a plotly figure of every result whose curves are the result's own
numbers; the notebook display, repr and dir of a result."""
import math
import os

import numpy as np
import pytest

from conftest import ROOT, example

plotly = pytest.importorskip("plotly")  # Debian: python3-plotly (scripts/install-deps.sh)

MATHIEU = os.path.join(ROOT, "tests", "plot", "mathieu_pair.yaml")


def test_campbell_figure_is_the_result(geardyn):
    r = geardyn.load(example("kumar2011_coupled")).campbell("0:3000rpm:7")
    fig = r.plot(max_frequency=120)
    assert isinstance(fig, plotly.graph_objects.Figure)
    modes = [t for t in fig.data if t.name.startswith("mode ")]
    # the Kumar pair: 2 of its 7 tracks below 120 Hz
    assert len(modes) == 2
    for t, tr in zip(modes, [tr for tr in r.tracks][:2]):
        k = r.tracks.index(tr)
        assert np.array_equal(np.asarray(t.x), r.speeds_rpm)
        assert np.array_equal(np.asarray(t.y), r.frequency_hz[k])
    names = [t.name for t in fig.data]
    assert "1x input" in names and "critical speeds" in names
    assert list(fig.layout.yaxis.range) == [0, 120]


def test_every_result_plots(geardyn):
    chen = geardyn.load(example("chen1998_gear_pair"))
    m = chen.modal()
    fig = m.plot()
    f = np.concatenate([np.asarray(t.y) for t in fig.data])
    assert sorted(f) == sorted(np.asarray(m.frequency_hz))
    frf = geardyn.load(example("kumar2011_coupled")).frf(
        input="torque:motor", outputs=["mesh:mesh", "pinion.y"], freqs="100:26000:20")
    fig = frf.plot()
    mag = [t for t in fig.data if t.name == "mesh:mesh"][0]
    assert np.allclose(np.asarray(mag.x), frf.freqs / (2 * math.pi), rtol=0, atol=0)
    assert np.array_equal(np.asarray(mag.y), np.abs(frf.H[0, 0]))
    u = chen.unbalance("100:6000:8")
    fig = u.plot()
    assert len([t for t in fig.data if t.showlegend is not False]) == u.noutputs
    k = geardyn.mesh_stiffness(example("rig2018_pair"))
    fig = k.plot()
    kt = [t for t in fig.data if t.name == "k (normal plane)"][0]
    assert np.array_equal(np.asarray(kt.y), k.stiffness)
    assert {t.name for t in fig.data} >= {"1 pair in contact", "2 pairs in contact"}
    tr = geardyn.load(example("ducati_timing_geartrain")).transient(revolutions=0.2)
    fig = tr.plot()
    assert len(fig.data) == tr.nrecords
    assert np.array_equal(np.asarray(fig.data[0].y), tr.values[0])
    p = geardyn.load(MATHIEU).periodic(speeds="680:730:5", harmonics=4)
    fig = p.plot()
    assert len(fig.data) == p.nrecords
    assert np.array_equal(np.asarray(fig.data[0].y), p.peak_to_peak[:, 0], equal_nan=True)


def test_notebook_repr_dir(geardyn):
    r = geardyn.load(example("kumar2011_coupled")).modal()
    html = r._repr_html_()
    assert "Plotly.newPlot" in html and "<script src" not in html  # plotly.js inlined
    text = repr(r)
    assert text.startswith("<geardyn.ModalResult ") and "frequency_hz" in text
    d = dir(r)
    assert "plot" in d and "frequency_hz" in d and "to_pandas" in d
    assert not [n for n in d if n.startswith("_")]
