"""A run-up through a speed profile from Python (docs/transient.md, "Run-up through a
speed profile"): the same order-tracked waterfall as `geardyn transient --speed-ramp
--waterfall --json` (bit for bit: one library function on one model), a table with the
ramp's corners giving the ramp's numbers, and the refusals."""
import os

import numpy as np
import pytest

import geardyn
from conftest import ROOT, run_cli, nums, same

ROTOR = os.path.join(ROOT, "tests", "transient", "runup_rotor.yaml")
ARGS = dict(duration=1.0, records=["gear48.x"], method="galpha", step=1e-4,
            output_interval=1e-4, waterfall="gear48.x", revs_per_block=8)


def test_ramp_waterfall_equals_the_cli():
    r = geardyn.load(ROTOR).transient(speed_ramp=("5000 rpm", "8000 rpm"), **ARGS)
    w = r.waterfall
    o = run_cli("transient", ROTOR, "--speed-ramp", "5000:8000rpm", "--duration", "1s",
                "--record", "gear48.x", "--waterfall", "gear48.x", "--revs-per-block", "8",
                "--method", "galpha", "--step", "1e-4", "--output-interval", "1e-4")
    cw = o["waterfall"]
    assert w.order_labels == [x["label"] for x in cw["orders"]]
    assert same(w.speeds, [s["speed_rad_s"] for s in cw["spectra"]])
    assert same(w.order_amplitude[0], nums(cw["orders"][0]["amplitude"]))
    assert r.method_note.startswith("galpha")
    assert r.record_from == 0.0
    # the 1x peak: the rotor's first forward critical speed is 6649.8 rpm (campbell); at
    # 3000 rpm/s it comes about 3 % late (docs/transient.md, "Resolution")
    pk = w.speeds_rpm[np.argmax(w.order_amplitude[0])]
    assert 6649.8 < pk < 1.05 * 6649.8
    # the figure draws those numbers: the order cuts are the waterfall's, the unit the
    # record's
    fig = w.plot()
    cuts = [tr for tr in fig.data if tr.type == "scatter" and tr.mode == "lines+markers"]
    assert [tr.name for tr in cuts] == w.order_labels
    assert np.array_equal(np.asarray(cuts[0].y, dtype=float), w.order_amplitude[0],
                          equal_nan=True)
    assert np.array_equal(np.asarray(cuts[0].x, dtype=float), w.speeds_rpm)
    assert w.unit == "m" and "(m)" in fig.layout.yaxis2.title.text


def test_table_gives_the_ramp():
    m = geardyn.load(ROTOR)
    a = m.transient(speed_ramp=("5000 rpm", "8000 rpm"), **ARGS)
    b = m.transient(speed_table=([0.0, 1.0], np.array([5000.0, 8000.0]) * np.pi / 30), **ARGS)
    assert np.allclose(a.waterfall.order_amplitude, b.waterfall.order_amplitude,
                       rtol=1e-9, atol=0)


def test_refusals():
    m = geardyn.load(ROTOR)
    with pytest.raises(geardyn.ModelError, match="needs duration"):
        m.transient(speed_ramp=(0, 100))
    with pytest.raises(geardyn.ModelError, match="waterfall= needs"):
        m.transient(duration=0.1, waterfall="gear48.x")
    with pytest.raises(geardyn.ModelError, match="constant speed"):
        m.transient(duration=0.1, speed_ramp=(0, 100), method="lti")
