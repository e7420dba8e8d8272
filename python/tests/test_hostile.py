"""Hostile input of issue 38 through the Python API: Ctrl-C in a law's callback stops
the analysis with KeyboardInterrupt (M1: "Exception ignored from cffi callback" and the
run went on), an exception in a callback is never a silent zero force, a run that cannot
finish is refused (M4), and bad arguments raise ModelError naming the argument (L5:
NaN, negative, fractional and complex values were taken, AttributeError and IndexError
raised)."""
import math
import os
import signal
import threading
import time

import numpy as np
import pytest

from conftest import example

DUFFING = example("duffing")
CHEN = example("chen1998_gear_pair")


def cubic(t, q, v):
    return np.array([-0.1 * q[0] ** 3]), np.array([-0.3 * q[0] ** 2]), np.zeros(1)


def test_ctrl_c_in_a_law_stops_the_analysis(geardyn):
    """The 50th call loops until SIGINT arrives (sent to this process 0.2 s later): the
    loop breaks with KeyboardInterrupt inside the callback, the C side stops at the
    poisoned force and the interrupt reaches the caller. Before, the run went on to its
    end (300 s of Duffing) and returned normally."""
    calls = [0]

    def looping(t, q, v):
        calls[0] += 1
        if calls[0] == 50:
            threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT)).start()
            while True:  # a law that never returns: only Ctrl-C gets out
                pass
        return cubic(t, q, v)

    law = geardyn.Law("looping", ["m.x"], looping, terms=[([1.0], [1.0])])
    m = geardyn.load(DUFFING)
    # Python's own Ctrl-C handler, whatever this process inherited: a shell starts a
    # background job with SIGINT ignored, and Python then installs none (the loop never
    # ended under `.ci/run &`)
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    t0 = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            m.transient(duration=300, laws=[law])
    finally:
        signal.signal(signal.SIGINT, previous)
    assert calls[0] == 50  # Python was not called again after the interrupt
    # bound on the test's time only (the timer is 0.2 s): the run did not go on
    assert time.monotonic() - t0 < 30


@pytest.mark.parametrize("analysis", ["bdf", "galpha", "periodic"])
def test_an_exception_in_a_law_is_never_a_zero_force(geardyn, analysis):
    """The 30th call raises: the analysis raises it, and no call follows it (before, the
    force counted as zero and the run called the law to its end)."""
    calls = [0]

    def failing(t, q, v):
        calls[0] += 1
        if calls[0] == 30:
            raise ValueError("boom")
        return cubic(t, q, v)

    law = geardyn.Law("failing", ["m.x"], failing, terms=[([1.0], [1.0])])
    m = geardyn.load(DUFFING)
    with pytest.raises(ValueError, match="boom"):
        if analysis == "periodic":
            m.periodic("1:1.2:3", harmonics=5, laws=[law])
        else:
            m.transient(duration=300, laws=[law], method=analysis)
    assert calls[0] == 30


def test_a_nan_law_record_has_no_statistics(geardyn):
    """A record that is NaN at some samples: its statistics are NaN (null in JSON), not a
    peak-to-peak of -inf."""
    law = geardyn.Law("gappy", ["m.x"], cubic, terms=[([1.0], [1.0])], records={"f": "N"},
                      record=lambda k, t, q, v: math.nan if t > 5 else q[0])
    m = geardyn.load(DUFFING)
    r = m.transient(duration=10, laws=[law], records="law:gappy:f")
    st = r.stats[0]
    assert all(math.isnan(st[k]) for k in ("min", "max", "mean", "rms", "peak_to_peak"))


def test_runs_that_cannot_finish_are_refused(geardyn):
    """Duffing for 1e30 s ran until killed (no shaft turns: the limit counted
    revolutions only); now 1.9e29 forcing periods, over the step limit."""
    m = geardyn.load(DUFFING)
    with pytest.raises(geardyn.ModelError, match="forcing periods"):
        m.transient(duration=1e30)


def test_duplicate_law_names_are_refused(geardyn):
    m = geardyn.load(DUFFING)  # has a law named cubic
    law = geardyn.Law("cubic", ["m.x"], cubic, terms=[([1.0], [1.0])])
    with pytest.raises(geardyn.ModelError, match="duplicate law name 'cubic'"):
        m.transient(duration=1, laws=[law])
    a = geardyn.Law("twin", ["m.x"], cubic, terms=[([1.0], [1.0])])
    b = geardyn.Law("twin", ["m.x"], cubic, terms=[([1.0], [1.0])])
    with pytest.raises(geardyn.ModelError, match="duplicate law name 'twin'"):
        m.transient(duration=1, laws=[a, b])


@pytest.mark.parametrize("call, field", [
    (lambda g, m: m.modal(speed=float("nan")), "speed"),
    (lambda g, m: m.modal(speed=float("inf")), "speed"),
    (lambda g, m: m.modal(speed=1 + 2j), "speed"),
    (lambda g, m: m.modal(speed=np.complex128(1 + 0j)), "speed"),
    (lambda g, m: m.modal(modes=-1), "modes"),
    (lambda g, m: m.modal(modes=2.5), "modes"),
    (lambda g, m: m.campbell("0:1000rpm:3", threads=-2), "threads"),
    (lambda g, m: m.periodic("500:900:3", harmonics=2.5), "harmonics"),
    (lambda g, m: m.periodic("500:900:3", harmonics=4, subharmonic=1.5), "subharmonic"),
    (lambda g, m: m.transient(duration=0.001, speed="1000rpm", records=[1, 2]), "records"),
    (lambda g, m: m.transient(speed_table=([], []), duration=0.01), "speed_table"),
    (lambda g, m: g.loads(None), "text"),
])
def test_bad_arguments_raise_model_error(geardyn, call, field):
    m = geardyn.load(CHEN)
    with pytest.raises(geardyn.ModelError) as e:
        call(geardyn, m)
    assert e.value.field == field
