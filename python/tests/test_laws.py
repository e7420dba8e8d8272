"""Laws of your own in Python (geardyn.Law, docs/laws.md): the Duffing oscillator's cubic
spring written as a callback equals the built-in polynomial_spring law of
examples/duffing.yaml, in harmonic balance and in time integration; errors in the
callbacks and in the law's description reach the caller."""
import numpy as np
import pytest

from conftest import example

DUFFING = example("duffing")


def cubic(t, q, v):
    f = np.array([-0.1 * q[0] ** 3 - 0.05 * v[0]])
    return f, np.array([-0.3 * q[0] ** 2]), np.array([-0.05])


def user_law(geardyn):
    return geardyn.Law("mine", ["m.x"], cubic, terms=[([1.0], [1.0])], records={"force": "N"},
                       record=lambda k, t, q, v: 0.1 * q[0] ** 3 + 0.05 * v[0])


def without_builtin(geardyn):
    m = geardyn.load(DUFFING)
    m.set("laws.cubic.k3", 0.0)
    m.set("laws.cubic.damping", 0.0)
    return m


def test_python_law_equals_builtin_in_harmonic_balance(geardyn):
    a = without_builtin(geardyn).periodic("1:1:1", harmonics=15, laws=[user_law(geardyn)],
                                           records="m.x,law:mine")
    b = geardyn.load(DUFFING).periodic("1:1:1", harmonics=15, records="m.x,law:cubic")
    assert a.names == ["m.x:disp", "law:mine:force"]
    assert np.allclose(a.peak_to_peak, b.peak_to_peak, rtol=1e-12, atol=0)
    assert np.allclose(a.amplitudes, b.amplitudes, rtol=0, atol=1e-12)
    assert a.peak_to_peak[0, 0] > 0.8


def test_python_law_equals_builtin_in_time(geardyn):
    a = without_builtin(geardyn).transient(duration=60, rtol=1e-10, laws=[user_law(geardyn)],
                                            records="m.x")
    b = geardyn.load(DUFFING).transient(duration=60, rtol=1e-10, records="m.x")
    # the same equations; the step sizes differ at rounding, so the samples agree to the
    # integrator's tolerance
    assert np.max(np.abs(a.values - b.values)) < 1e-7 * np.max(np.abs(b.values))


def test_two_dof_python_law(geardyn):
    # a 1 N/m spring between the x of the Chen pair's two gears as a two-DOF user law:
    # the law sees both DOFs, in order, and its record comes back
    seen = []

    def spring(t, q, v):
        seen.append(len(q))
        d = q[0] - q[1]
        return np.array([-d, d]), np.array([-1.0]), np.array([0.0])
    law = geardyn.Law("link", ["gear_a.x", "gear_b.x"], spring,
                      terms=[([1.0, -1.0], [1.0, -1.0])], records={"force": "N"},
                      record=lambda k, t, q, v: q[0] - q[1])
    r = geardyn.load(example("chen1998_gear_pair")).transient(
        duration="2 ms", speed="500 rad/s", laws=[law], records="law:link")
    assert seen and set(seen) == {2}
    assert r.names == ["law:link:force"] and np.all(np.isfinite(r.values))


def test_callback_errors_and_bad_descriptions_reach_the_caller(geardyn):
    def boom(t, q, v):
        raise ValueError("boom")
    law = geardyn.Law("bad", ["m.x"], boom, terms=[([1.0], [1.0])])
    with pytest.raises(ValueError, match="boom"):
        geardyn.load(DUFFING).transient(duration=1, laws=[law])
    with pytest.raises(geardyn.ModelError, match="not NODE.DOF"):
        geardyn.load(DUFFING).transient(duration=1, laws=[geardyn.Law(
            "x", ["nowhere.x"], cubic, terms=[([1.0], [1.0])])])
    with pytest.raises(geardyn.ModelError, match="not an active DOF"):
        geardyn.load(DUFFING).transient(duration=1, laws=[geardyn.Law(
            "y", ["m.y"], cubic, terms=[([1.0], [1.0])])])
    with pytest.raises(geardyn.ModelError, match="one entry per DOF"):
        geardyn.Law("z", ["m.x"], cubic, terms=[([1.0, 0.0], [1.0])])
