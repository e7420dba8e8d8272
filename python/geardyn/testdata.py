"""Test data, modal parameters from measured FRFs, correlation and model updating
(docs/testing.md): UFF 58/58b and CSV files read by the C library, LSCF or peak picking,
the model's modes paired with the measured ones, the model's FRF at the measured points,
and bounded Levenberg-Marquardt updating of --set values to the measured frequencies.
Every result holds numpy arrays a user can plot."""
import os

from ._numpy import np

from . import _core
from ._core import ffi, lib, check, new_error, cstr
from .model import _load_options, _set_strings, load as _load_model

__all__ = ["read_testdata", "testmodal", "correlate", "update", "TestData", "EmaResult",
           "Correlation", "UpdateResult"]

_QUANTITY = _core.names(lib.gd_td_quantity_names, 4)


class Function:
    """One measured function: name, freq_hz, H (complex, SI), response and reference
    (point label, direction "+y"), quantity ("receptance", "mobility", "accelerance",
    "ratio"), units as written, file and line."""

    def __init__(self, f):
        self.name = cstr(f.name)
        self.freq_hz = np.array(ffi.unpack(f.freq_hz, f.n))
        self.H = np.array(ffi.unpack(f.re, f.n)) + 1j * np.array(ffi.unpack(f.im, f.n))
        self.response = (int(f.response_node), cstr(lib.gd_td_dir_name(f.response_dir)))
        self.reference = (int(f.reference_node), cstr(lib.gd_td_dir_name(f.reference_dir)))
        self.quantity = _QUANTITY[f.quantity]
        self.units = cstr(f.units)
        self.file, self.line = cstr(f.file), int(f.line)


class TestData:
    """Files read together: functions (list of Function) and, from a modes CSV,
    modes_hz and modes_zeta (NaN where not given)."""

    __test__ = False  # not a pytest class

    def __init__(self, handle, paths):
        self._handle = handle
        self.paths = paths
        td = handle
        self.functions = [Function(td.functions[i]) for i in range(td.nfunctions)]
        self.modes_hz = np.array(ffi.unpack(td.mode_hz, td.nmodes)) if td.nmodes else \
            np.zeros(0)
        self.modes_zeta = np.array(ffi.unpack(td.mode_zeta, td.nmodes)) if td.nmodes else \
            np.zeros(0)

    def _frfs(self):
        """The FRFs (ratios left out) as a C array, with what keeps it alive."""
        td = self._handle
        ptrs = [ffi.addressof(td.functions[i]) for i in range(td.nfunctions)
                if td.functions[i].quantity != lib.GD_TD_RATIO]
        arr = ffi.new("const gd_td_function *[]", ptrs) if ptrs else ffi.NULL
        return arr, len(ptrs)


def read_testdata(paths, skip_datasets=False):
    """Reads UFF 58/58b, FRF CSV and modes CSV files (one path or a list) into one
    TestData. Raises ModelError naming the file, line and record."""
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]
    paths = [os.fspath(p) for p in paths]
    keep = [ffi.new("char[]", p.encode()) for p in paths]
    arr = ffi.new("const char *[]", keep)
    out = ffi.new("gd_testdata **")
    err = new_error()
    check(lib.gd_testdata_read(len(paths), arr, 1 if skip_datasets else 0, out, err), err)
    return TestData(ffi.gc(out[0], lib.gd_testdata_free), paths)


def _as_data(data):
    return data if isinstance(data, TestData) else read_testdata(data)


def _ema_options(band, order):
    opt = ffi.new("gd_ema_options *")
    lib.gd_ema_options_init(opt)
    opt.max_order = int(order)
    if band is not None:
        opt.band_lo_hz, opt.band_hi_hz = float(band[0]), float(band[1])
    return opt


class EmaResult:
    """Modes of measured FRFs: frequency_hz, damping_ratio, stable_orders (LSCF);
    residues (complex, nfrf x nmodes: column r is mode r's shape over the FRFs, in the
    order of data.functions' FRFs); the stabilisation diagram as arrays pole_order,
    pole_frequency_hz, pole_damping_ratio, pole_status ("o" new, "f" frequency stable,
    "s" frequency and damping stable); band_hz; max_order."""

    def __init__(self, owner, data):
        r = owner
        self._owner = owner
        self.data = data
        modes = [r.modes[j] for j in range(r.nmodes)]
        self.frequency_hz = np.array([m.frequency_hz for m in modes])
        self.damping_ratio = np.array([m.damping_ratio for m in modes])
        self.stable_orders = np.array([m.stable_count for m in modes], dtype=int)
        n = r.nfrf * r.nmodes
        if n and r.residue_re != ffi.NULL:
            re = np.array(ffi.unpack(r.residue_re, n)).reshape((r.nmodes, r.nfrf)).T
            im = np.array(ffi.unpack(r.residue_im, n)).reshape((r.nmodes, r.nfrf)).T
            self.residues = re + 1j * im
        else:
            self.residues = np.zeros((r.nfrf, r.nmodes), dtype=complex)
        poles = [r.poles[i] for i in range(r.npoles)]
        self.pole_order = np.array([p.order for p in poles], dtype=int)
        self.pole_frequency_hz = np.array([p.frequency_hz for p in poles])
        self.pole_damping_ratio = np.array([p.damping_ratio for p in poles])
        self.pole_status = np.array([p.status.decode() for p in poles])
        self.band_hz = (r.band_lo_hz, r.band_hi_hz)
        self.max_order = int(r.max_order)


def testmodal(data, band=None, order=40, method="lscf"):
    """Modes of measured FRFs (paths or a TestData): LSCF (default, with its
    stabilisation diagram and LSFD residues) or "peaks" (peak picking, half-power
    damping). band: (f1, f2) in Hz. As `geardyn testmodal`."""
    data = _as_data(data)
    frfs, n = data._frfs()
    opt = _ema_options(band, order)
    out = ffi.new("gd_ema_result **")
    err = new_error()
    fn = {"lscf": lib.gd_ema_lscf, "peaks": lib.gd_ema_peaks}.get(method)
    if fn is None:
        raise _core.model_error("method", "unknown method '%s'" % method, "lscf or peaks")
    check(fn(n, frfs, opt, out, err), err)
    return EmaResult(ffi.gc(out[0], lib.gd_ema_free), data)


def _setup(path):
    if path is None:
        return ffi.NULL
    out = ffi.new("gd_test_setup **")
    err = new_error()
    check(lib.gd_test_setup_load(os.fspath(path).encode(), out, err), err)
    return ffi.gc(out[0], lib.gd_test_setup_free)


def _measured(system, data, setup, band, order):
    """gd_measured_modes (owned: freed with it) and the EMA it came from (or None)."""
    mm = ffi.gc(ffi.new("gd_measured_modes *"), lib.gd_measured_modes_free)
    err = new_error()
    ema = None
    if data._handle.nmodes:
        check(lib.gd_measured_from_testdata(data._handle, mm, err), err)
    else:
        ema = testmodal(data, band, order)
        frfs, n = data._frfs()
        check(lib.gd_measured_from_ema(system._handle, setup, n, frfs, ema._owner, mm, err),
              err)
    return mm, ema


def _table(t):
    pairs = [t.pairs[i] for i in range(t.npairs)]
    return {"test_hz": np.array([p.f_test for p in pairs]),
            "model_hz": np.array([p.f_model for p in pairs]),
            "model_mode": np.array([p.model for p in pairs], dtype=int),
            "difference_pct": np.array([p.diff_pct for p in pairs]),
            "mac": np.array([p.mac for p in pairs]),
            "rms_pct": float(t.rms_pct)}


class Correlation:
    """Measured against model modes: test_hz, model_hz, model_mode (0-based index of the
    model's elastic modes), difference_pct ((f_model - f_test) / f_model x 100), mac
    (NaN without measured shapes), rms_pct; frfs: list of (Function, model H at its
    lines); ema: the EmaResult the measured modes came from (None for a modes CSV)."""

    def __init__(self, table, frfs, ema):
        for k, v in table.items():
            setattr(self, k, v)
        self.frfs = frfs
        self.ema = ema

    def to_pandas(self):
        import pandas
        return pandas.DataFrame({k: getattr(self, k) for k in
                                 ("test_hz", "model_hz", "difference_pct", "mac")})


def correlate(model, data, setup=None, band=None, order=40):
    """The model (a geardyn.Model) against measurements (paths or TestData): paired
    modes and the model's FRF at every measured one. setup: a test-setup YAML file
    (point labels to node names). As `geardyn correlate`."""
    data = _as_data(data)
    system = model.system
    st = _setup(setup)
    mm, ema = _measured(system, data, st, band, order)
    out = ffi.new("gd_corr_table **")
    err = new_error()
    check(lib.gd_correlate_modes(system._handle, mm, out, err), err)
    t = ffi.gc(out[0], lib.gd_corr_table_free)
    frfs = []
    td = data._handle
    for i in range(td.nfunctions):
        f = td.functions[i]
        if f.quantity == lib.GD_TD_RATIO:
            continue
        re = np.empty(f.n)
        im = np.empty(f.n)
        check(lib.gd_correlate_frf(system._handle, st, ffi.addressof(td.functions[i]),
                                   f.quantity, ffi.from_buffer("double[]", re),
                                   ffi.from_buffer("double[]", im), err), err)
        frfs.append((Function(f), re + 1j * im))
    return Correlation(_table(t), frfs, ema)


class UpdateResult:
    """Model updating: keys, lower, upper, initial, value, sigma (standard deviation,
    NaN without redundancy), sens (df/dp in Hz per SI unit, ntargets x nparams, from the
    eigenvalue derivatives) and sens_fd (central differences, with fd_check), before and
    after (dicts as Correlation's arrays), iterations, at_bound."""

    def __init__(self, r, params):
        np_, nt = r.nparams, r.ntargets
        self.keys = [k for k, _ in params]
        self.lower = np.array([b[0] for _, b in params], dtype=float)
        self.upper = np.array([b[1] for _, b in params], dtype=float)
        self.initial = np.array(ffi.unpack(r.initial, np_))
        self.value = np.array(ffi.unpack(r.value, np_))
        self.sigma = np.array(ffi.unpack(r.sigma, np_))
        self.sens = np.array(ffi.unpack(r.sens, nt * np_)).reshape((nt, np_))
        self.sens_fd = (np.array(ffi.unpack(r.sens_fd, nt * np_)).reshape((nt, np_))
                        if r.sens_fd != ffi.NULL else None)
        self.before = _table(r.before)
        self.after = _table(r.after)
        self.iterations = int(r.iterations)
        self.at_bound = bool(r.at_bound)


def update(path, data, params, sets=None, setup=None, band=None, order=40, fd_check=False):
    """Fits values of the model file at path to the measured frequencies. params:
    {"bearings.*.k": (5e7, 2e8), "bearings.A1.k,bearings.A2.k": (lo, hi)} (SI bounds;
    keys joined by ',' move together); sets: fixed overrides applied first (as
    geardyn.load). As `geardyn correlate --update`."""
    data = _as_data(data)
    params = list(params.items())
    set_list = _set_strings(sets or {})
    model = _load_model(path, set_list)
    mm, _ = _measured(model.system, data, _setup(setup), band, order)
    src = ffi.new("gd_model_source **")
    err = new_error()
    check(lib.gd_model_source_load(os.fspath(path).encode(), src, err), err)
    src = ffi.gc(src[0], lib.gd_model_source_free)
    keys = [ffi.new("char[]", k.encode()) for k, _ in params]
    par = ffi.new("gd_update_param[]", len(params))
    for i, (k, (lo, hi)) in enumerate(params):
        par[i].key = keys[i]
        par[i].lo, par[i].hi = float(lo), float(hi)
    lo_opt, keep = _load_options(set_list)
    opt = ffi.new("gd_update_options *")
    lib.gd_update_options_init(opt)
    opt.nparams = len(params)
    opt.params = par
    opt.load = lo_opt[0]
    opt.fd_check = 1 if fd_check else 0
    out = ffi.new("gd_update_result **")
    check(lib.gd_model_update(src, mm, opt, out, err), err)
    r = ffi.gc(out[0], lib.gd_update_free)
    del keep
    return UpdateResult(r, params)
