"""Python overhead of a modal solve: CPU microseconds per solve from Python (geardyn's
System.modal, and the bare cffi call) against the C floor measured by
`bench_modal MODEL --loop N` in the same run. Prints figures; asserts nothing.

usage: bench_python.py BUILD_DIR MODEL [SOLVES_PER_BATCH]"""
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "python"))
import geardyn  # noqa: E402
from geardyn import ffi, lib  # noqa: E402


def best_us(fn, reps, batches=7):
    """CPU microseconds of this thread per call, best of the batches (CPU time, as the
    C floor: on a shared machine wall time counts the waits for a core)."""
    best = 1e30
    for _ in range(batches):
        t0 = time.thread_time()
        for _ in range(reps):
            fn()
        best = min(best, (time.thread_time() - t0) / reps)
    return best * 1e6


def main():
    build, model = sys.argv[1], sys.argv[2]
    reps = int(sys.argv[3]) if len(sys.argv) > 3 else 2000
    s = geardyn.load(model).system
    nmodes = 0 if s.ndof <= 30 else 20

    def bare():  # the cffi call alone, no result object
        opt = ffi.new("gd_modal_options *")
        lib.gd_modal_options_init(opt)
        opt.nmodes = nmodes
        out = ffi.new("gd_modal_result **")
        err = ffi.new("gd_error *")
        lib.gd_modal_solve(s._handle, opt, out, err)
        lib.gd_modal_free(out[0])

    def full():  # geardyn's API, reading the frequencies (a view)
        s.modal().omega_n

    # the machine is shared: C and Python batches alternate over 5 rounds, best of each
    c_us = py_bare = py_full = py_read = 1e30
    for _ in range(5):
        c_us = min(c_us, float(subprocess.run(
            [os.path.join(build, "bench_modal"), model, "--loop", str(reps)], check=True,
            capture_output=True, text=True).stdout))
        py_bare = min(py_bare, best_us(bare, reps))
        py_full = min(py_full, best_us(s.modal, reps))
        py_read = min(py_read, best_us(full, reps))
    print("model                 %s (%d DOFs, %d modes)" % (model, s.ndof, s.modal().nmodes))
    print("C gd_modal_solve      %8.2f us   (bench_modal --loop, floor)" % c_us)
    print("Python bare cffi call %8.2f us   ratio %.3f" % (py_bare, py_bare / c_us))
    print("Python system.modal() %8.2f us   ratio %.3f" % (py_full, py_full / c_us))
    print("  + .omega_n view     %8.2f us   ratio %.3f" % (py_read, py_read / c_us))


if __name__ == "__main__":
    main()
