"""Periodic steady state by harmonic balance (docs/periodic.md): gd_periodic_run over a
speed range with pseudo-arclength continuation, Floquet stability and bifurcations, with
the record specs and the defaults of `geardyn periodic`."""
from ._numpy import np

from . import _core
from ._core import ffi, lib, check, new_error, cstr, model_error, whole
from .analyses import _Result, _pandas, sweep
from .transient import _records, _record_array
from .laws import with_laws

__all__ = ["periodic", "PeriodicResult"]

_METHODS = {"arclength": lib.GD_PER_ARCLENGTH, "sequential": lib.GD_PER_SEQUENTIAL}
_SOLVERS = {"hb": lib.GD_PER_HB, "harmonic_balance": lib.GD_PER_HB,
            "shooting": lib.GD_PER_SHOOTING, "auto": lib.GD_PER_AUTO,
            "multifreq": lib.GD_PER_MULTIFREQ,
            "reduced_shooting": lib.GD_PER_REDUCED_SHOOTING}


def _frequencies(values):
    """--frequency values: "FROM:TO:COUNT" either way (TO < FROM follows the branch
    downwards), or an array in the order given."""
    if isinstance(values, str):
        parts = values.split(":")
        if len(parts) == 3:
            a, b = (sweep(p + ":" + p + ":1", "speed", "frequency")[0]
                    for p in parts[:2])
            if b < a:
                return sweep(parts[1] + ":" + parts[0] + ":" + parts[2], "speed",
                             "frequency")[::-1].copy()
    return sweep(values, "speed", "frequency")


def periodic(system, speeds=None, harmonics="auto", subharmonic=1, records=None,
             method="arclength", both_directions=False, stability=True, tol=1e-10,
             samples=0, laws=None, solver="auto", shoot_budget=30.0, frequency=None,
             floquet_budget=30.0):
    """Periodic steady state over the reference speeds `speeds` (rad/s array or
    "FROM:TO:COUNT" with units), as `geardyn periodic`, with its defaults: harmonics H
    ("auto", the default: from the excitations, raised until the truncation estimate
    holds, as `--harmonics auto`), subharmonic N,
    records as for transient() (NODE.DOF[:disp|vel|speed], ratio:A/B, mesh:NAME[:what],
    sfd:BEARING[:what]; None: the CLI's defaults; a total angle has no periodic steady
    state), method "arclength" (through folds: several points per speed on a hysteresis
    loop) or "sequential" (a run-up), both_directions (also the run back), stability
    (Floquet multipliers and bifurcations), tol (Newton's relative residual), samples
    (AFT samples per period; 0: automatic). laws: geardyn.Law objects (laws of your own
    in Python) added to the model's. solver: "hb" (harmonic balance), "shooting"
    (Newton on the period map of the transient integrator: cam torques with
    include_acceleration too), "reduced_shooting" (laws linear in the state at fixed time
    only: the orbit in a reduced basis, as `--method reduced-shooting`), "multifreq" or
    "auto" (the default, as `--method auto`: the cheaper by a measured cost; the result's
    solver and solver_note say which ran and why); shoot_budget: CPU seconds per shooting
    point (30, the CLI's; None: no limit); floquet_budget: CPU seconds for one point's
    Floquet multipliers (30, the CLI's; None: no limit; a point over it keeps its orbit, with
    stable None and a reason saying how long they would take). frequency: continue in the frequency of
    the model's time-harmonic loads instead of the speed, as `--frequency` (rad/s array in
    the order to follow, or "FROM:TO:COUNT" with units, e.g. "0.8:0.5:31"; several loads
    keep their ratios), at the first of `speeds` (None: the model's speed); the points'
    `parameter` is the frequency."""
    prm = ffi.NULL
    if frequency is not None:
        w = _frequencies(frequency)
        prm = ffi.new("gd_periodic_param *")
        prm.speed = (system.model.speed if speeds is None
                     else float(sweep(speeds, "speed", "speeds")[0]))
        prm.load_frequency = 1
        name = ffi.new("char[]", b"load frequency")
        prm.name = name
    elif speeds is None:
        raise model_error("speeds", "give the speeds (or frequency=)", "e.g. 0:3000rpm:61")
    else:
        w = sweep(speeds, "speed", "speeds")
    if method not in _METHODS:
        raise model_error("method", "unknown method '%s'" % method, "use arclength or sequential")
    if solver not in _SOLVERS:
        raise model_error("solver", "unknown solver '%s'" % solver,
                          "use hb, shooting, reduced_shooting, multifreq or auto")
    opt = ffi.new("gd_periodic_options *")
    lib.gd_periodic_options_init(opt)
    opt.kind = _SOLVERS[solver]
    opt.shoot_stability = 1  # the CLI's: a non-smooth orbit's multipliers in the time domain
    if shoot_budget is not None:
        if not float(shoot_budget) > 0:
            raise model_error("shoot_budget", "expected CPU seconds > 0, got %r" % shoot_budget)
        opt.shoot_budget = float(shoot_budget)
    if floquet_budget is not None:
        if not float(floquet_budget) > 0:
            raise model_error("floquet_budget",
                              "expected CPU seconds > 0, got %r" % floquet_budget)
        opt.floquet_budget = float(floquet_budget)
    if harmonics == "auto":
        opt.adaptive = 1
    else:
        opt.harmonics = whole(harmonics, "harmonics", 1, 1000)  # 2.5 was taken as 2
    subharmonic = whole(subharmonic, "subharmonic", 1, 1000)
    samples = whole(samples, "samples", 0, 1 << 20)
    if not 1e-15 <= float(tol) < 1:
        raise model_error("tol", "expected a number in [1e-15, 1), got %r" % tol)
    if samples and int(samples) < 2 * opt.harmonics + 2:
        raise model_error("samples", "%d samples cannot resolve %d harmonics (give >= %d)"
                          % (int(samples), opt.harmonics, 2 * opt.harmonics + 2))
    opt.subharmonic, opt.tol, opt.samples = int(subharmonic), float(tol), int(samples)
    opt.method, opt.both_directions = _METHODS[method], int(bool(both_directions))
    opt.stability = int(bool(stability))
    err = new_error()
    tmp = ffi.new("gd_transient_model **")
    check(lib.gd_transient_model_build(system._handle, tmp, err), err)
    tm = ffi.gc(tmp[0], lib.gd_transient_model_free)
    spec, view, keep = with_laws(system, tm, laws)
    recs = _records(system, view, records)
    for kind, _i, _j, name, _u in recs:
        if kind == lib.GD_REC_ANGLE:
            raise model_error("record", "'%s': a total angle grows with time and has no "
                              "periodic steady state" % name,
                              "record the DOF's displacement (its perturbation) or its speed")
    rr = _record_array(recs)
    values = ffi.new("double[]", [float(x) for x in w])
    out = ffi.new("gd_periodic_result **")
    st = lib.gd_periodic_run(system._handle, spec, prm, values, len(w), opt, rr,
                             len(recs), out, err)
    for law in laws or []:
        law.raise_pending()
    check(st, err)
    del tm, keep  # the result owns copies of everything it reports
    return PeriodicResult(system, ffi.gc(out[0], lib.gd_periodic_result_free),
                          [r[3] for r in recs], [r[4] for r in recs])


POINT_DTYPE = _core.struct_dtype("gd_periodic_point", {
    "speed": "f8", "parameter": "f8", "direction": "i4", "converged": "i4", "harmonics": "i4",
    "omega": "f8", "residual": "f8", "iterations": "i4", "stable": "i4", "mu_max": "f8",
    "nmult": "i4"})


class PeriodicResult(_Result):
    """Periodic steady state (C gd_periodic_result), one point per crossing of a
    requested speed in branch order. points (structured view of the C points: speed,
    parameter, direction, converged, harmonics, omega, residual, iterations, stable (1, 0,
    -1 not computed), mu_max, nmult) and its columns as arrays (speed, direction, stable,
    converged, mu_max, ...); per record (npoints x nrecords, NaN where a point did not
    converge): mean, rms, peak_to_peak; amplitudes and phases_deg (npoints x nrecords x
    H + 1, NaN-padded); multipliers(i) (complex Floquet multipliers of point i);
    bifurcations (list of dicts: type, speed, parameter, direction, multiplier); reasons
    (why a point did not converge); names and units of the records; steps, cpu_seconds;
    solver ("harmonic_balance" or "shooting": what ran) and solver_note (with solver="auto": why)."""

    _figure = "periodic"
    _FIELDS_DTYPE = POINT_DTYPE  # served by __getattr__

    def __init__(self, system, owner, names, units):
        super().__init__(system, owner)
        r = owner
        self.names, self.units = names, units
        self.npoints, self.nrecords = int(r.npoints), int(r.nrecords)
        self.steps, self.cpu_seconds = int(r.steps), float(r.cpu_seconds)
        self.solver = cstr(lib.gd_per_kind_name(r.method))
        self.solver_note = cstr(r.method_note)
        self.bifurcations = []
        for i in range(int(r.nbifurcations)):
            b = r.bifurcations[i]
            self.bifurcations.append({
                "type": cstr(lib.gd_bifurcation_name(b.type)), "speed": float(b.speed),
                "parameter": float(b.parameter), "direction": int(b.direction),
                "multiplier": complex(b.mu_re, b.mu_im)})
        self.reasons = [cstr(r.points[i].reason) if not r.points[i].converged else ""
                        for i in range(self.npoints)]
        # per record statistics, copied out of the per-point arrays of the C result
        shape = (self.npoints, self.nrecords)
        self.mean, self.rms, self.peak_to_peak = (np.full(shape, np.nan) for _ in range(3))
        hmax = max([int(r.points[i].harmonics) for i in range(self.npoints)] + [0])
        self.amplitudes = np.full(shape + (hmax + 1,), np.nan)
        self.phases_deg = np.full(shape + (hmax + 1,), np.nan)
        for i in range(self.npoints):
            p = r.points[i]
            if not p.converged:
                continue
            h = int(p.harmonics) + 1
            for k in range(self.nrecords):
                s = p.records[k]
                self.mean[i, k], self.rms[i, k], self.peak_to_peak[i, k] = \
                    s.mean, s.rms, s.peak_to_peak
                self.amplitudes[i, k, :h] = ffi.unpack(s.amplitude, h)
                self.phases_deg[i, k, :h] = ffi.unpack(s.phase_deg, h)

    @property
    def points(self):
        return _core.struct_view(self._owner, self._owner.points, self.npoints, POINT_DTYPE)

    def __getattr__(self, name):
        # the point columns: speed, parameter, direction, converged, stable, mu_max, ...
        if name in POINT_DTYPE.names:
            return self.points[name]
        raise AttributeError(name)

    @property
    def speed_rpm(self):
        return self.points["speed"] * 30 / np.pi

    def multipliers(self, i):
        """The Floquet multipliers of point i (complex; empty when not computed)."""
        p = self._owner.points[i]
        n = int(p.nmult)
        if n == 0:
            return np.zeros(0, complex)
        return (np.array(ffi.unpack(p.mu_re, n)) + 1j * np.array(ffi.unpack(p.mu_im, n)))

    def __getitem__(self, name):
        """Peak-to-peak of the record called name over the points."""
        return self.peak_to_peak[:, self.names.index(name)]

    def to_pandas(self):
        """The rows of periodic.csv (`geardyn periodic --out`): one per point and record
        (one per point that did not converge)."""
        pd = _pandas()
        pts = self.points
        rows = []
        for i in range(self.npoints):
            p = pts[i]
            base = [i, int(p["direction"]), float(p["speed"]), float(p["parameter"]),
                    int(p["converged"]), int(p["harmonics"]), float(p["residual"]),
                    int(p["stable"]), float(p["mu_max"])]
            if not p["converged"]:
                rows.append(base + ["", np.nan, np.nan, np.nan])
                continue
            for k, name in enumerate(self.names):
                rows.append(base + [name, self.mean[i, k], self.rms[i, k],
                                    self.peak_to_peak[i, k]])
        return pd.DataFrame(rows, columns=[
            "point", "direction", "speed_rad_s", "parameter", "converged", "harmonics",
            "residual", "stable", "floquet_multiplier_max_abs", "record", "mean", "rms",
            "peak_to_peak"])
