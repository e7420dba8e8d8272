"""The linear analyses: modal, Campbell, frequency response and unbalance response.

Each runs one C call (the GIL is released during it) and returns a result object over
the C result: its arrays are numpy views of the C memory (no copy), freed with the last
of them. Complex quantities are stored by the library as separate real and imaginary
arrays; the *_re/*_im attributes are those views, and the complex properties (shapes,
left, H, response) are made from them (a copy: numpy complex arrays interleave).
"""
import math
import threading

from ._numpy import np

from . import _core
from ._core import ffi, lib, check, new_error, cstr, quantity, model_error, whole

__all__ = ["modal", "campbell", "frf", "unbalance", "sweep", "ModalResult",
           "CampbellResult", "FrfResult", "UnbalanceResult"]


def _pandas():
    try:
        import pandas
    except ImportError:  # pragma: no cover - pandas is optional
        raise ImportError("to_pandas() needs pandas (Debian: python3-pandas)") from None
    return pandas


def sweep(values, kind="speed", field="speeds"):
    """Speeds or frequencies in rad/s: an array of numbers (rad/s), or "FROM:TO:COUNT"
    with units as on the command line ("0:3000rpm:121"; a FROM without a unit takes
    TO's), spaced exactly as the CLI spaces them."""
    if isinstance(values, str):
        parts = values.split(":")
        if len(parts) != 3:
            raise model_error(field, "'%s' is not FROM:TO:COUNT" % values,
                              "write e.g. 0:12000rpm:121")
        sfrom, sto, scount = (p.strip() for p in parts)
        unit = sto.lstrip("0123456789.eE+-").strip()
        to = quantity(sto, kind, field)
        from_has_unit = sfrom.lstrip("0123456789.eE+-").strip() != ""
        frm = quantity(sfrom if from_has_unit or not unit else sfrom + " " + unit, kind, field)
        try:
            n = int(scount)
        except ValueError:
            raise model_error(field, "COUNT '%s' is not a whole number" % scount) from None
        if n < 1 or frm < 0 or to < frm or (n > 1 and to == frm):
            raise model_error(field, "'%s': give 0 <= FROM < TO and COUNT >= 1" % values)
        return np.array([frm if n == 1 else frm + (to - frm) * i / (n - 1) for i in range(n)])
    arr = np.ascontiguousarray(np.atleast_1d(np.asarray(
        [quantity(v, kind, field) for v in np.atleast_1d(values)], dtype=np.float64)))
    if arr.size == 0:
        raise model_error(field, "no values", "give at least one")
    return arr


def _doubles(values):
    """A C double array over a contiguous float64 numpy array (no copy); keep the array."""
    return ffi.cast("double *", ffi.from_buffer(values))


def _speed(sysobj, speed):
    return sysobj.model.speed if speed is None else quantity(speed, "speed", "speed")


class _Result:
    """Base: holds the owner (the ffi.gc'd C result) and the system. Every result has
    plot() (a plotly figure, geardyn/figures.py), shows that figure in a notebook
    (_repr_html_, plotly.js inlined: no network) and says what it holds (repr, dir)."""

    __slots__ = ("system", "_owner", "__dict__")
    _figure = None  # the figures.py function of the subclass

    def __init__(self, system, owner):
        self.system = system
        self._owner = owner

    def plot(self, **kw):
        """The result's figure as a plotly Figure (fig.show(), fig.write_html(...))."""
        from . import figures
        return getattr(figures, self._figure)(self, **kw)

    def _repr_html_(self):
        try:
            return self.plot().to_html(full_html=False, include_plotlyjs=True)
        except ImportError:
            return None

    def __repr__(self):
        from . import figures
        return figures.summary(self)

    def __dir__(self):
        from . import figures
        return figures.public_names(self)

    def _view(self, ptr, shape, dtype="f8", order="C"):
        return _core.view(self._owner, ptr, shape, dtype, order)


class _ReImResult(_Result):
    """A result whose values are complex, stored by the library as separate re and im
    arrays of shape _shape: the two views, and the complex array made from them (a copy:
    numpy complex arrays interleave)."""

    @property
    def re(self):
        return self._view(self._owner.re, self._shape)

    @property
    def im(self):
        return self._view(self._owner.im, self._shape)

    def _complex(self):
        return self.re + 1j * self.im


# ---------------------------------------------------------------- modal

_KINDS = {"auto": lib.GD_MODAL_AUTO, "undamped": lib.GD_MODAL_UNDAMPED,
          "damped": lib.GD_MODAL_DAMPED}
# Per-thread argument structs for modal(), reused call after call: the solve of a small
# model takes a few microseconds, and three allocations per call would be a tenth of it.
_tls = threading.local()



def _operating(system, operating_point, torque, speed, check_eq):
    """The state the model's laws (rolling and journal bearings) are linearised about,
    as the CLI's `--operating-point static|zero` and `--torque` (docs/bearings.md):
    "static" (the default) the static equilibrium under the mean loads, gravity and
    `torque` (N m at the reference shaft's first node), solved at each speed; "zero"
    q = 0. With check_eq (one speed: modal, frf) a missing equilibrium at `speed` raises
    the located ModelError of `static`. Nothing to do for a model without laws."""
    if operating_point not in ("static", "zero"):
        raise model_error("operating_point", "unknown operating point '%s'" % (operating_point,),
                          "use static or zero")
    t = 0.0 if torque is None else quantity(torque, "torque", "torque")
    if not system._handle.nlaws:
        return
    err = new_error()
    if operating_point == "zero":
        check(lib.gd_system_set_operating_point(system._handle, lib.GD_OPERATING_ZERO,
                                                ffi.NULL, ffi.NULL, err), err)
        return
    so = ffi.new("gd_static_options *")
    lib.gd_static_options_init(so)
    so.speed = speed
    so.input_torque = t
    check(lib.gd_static_operating_point(system._handle, so, 1 if check_eq else 0, err), err)


def modal(system, speed=None, modes=None, kind="auto", left=False, tol=None,
          operating_point="static", torque=None):
    """Modes at reference speed `speed` (default: the model's). modes: number of lowest
    modes, "all" or 0 for all; None as the CLI: all up to 30 DOFs, else 20. kind:
    "auto" (damped when the model has damping or gyroscopics), "undamped", "damped".
    left: also the bi-orthonormal left eigenvectors (damped modes). tol: the relative
    residual the sparse solver iterates to (None: 1e-9, as `geardyn modal --tol`); each
    mode's is in `residual` (and `residual_floor`, what rounding leaves).
    operating_point, torque: the laws' operating point, as `--operating-point`,
    `--torque` (the static equilibrium by default; docs/bearings.md)."""
    try:
        opt, out, err = _tls.modal
    except AttributeError:
        opt, out, err = _tls.modal = (ffi.new("gd_modal_options *"),
                                      ffi.new("gd_modal_result **"), new_error())
    lib.gd_modal_options_init(opt)
    opt.speed = system._model_handle.speed if speed is None else \
        quantity(speed, "speed", "speed")
    if modes is None:
        opt.nmodes = 0 if system.ndof <= 30 else 20
    else:
        opt.nmodes = 0 if modes == "all" else whole(modes, "modes", 0, 1000000)
    try:
        opt.kind = _KINDS[kind]
    except KeyError:
        raise model_error("kind", "unknown kind '%s'" % kind, "use auto, undamped or damped")
    opt.want_left = 1 if left else 0
    if tol is not None:
        if isinstance(tol, bool) or not isinstance(tol, (int, float)) or \
                not (1e-15 <= tol < 1):
            raise model_error("tol", "tol must be a number in [1e-15, 1), got %r" % (tol,),
                              "give a relative residual such as 1e-10")
        opt.tol = float(tol)
    _operating(system, operating_point, torque, opt.speed, True)
    if lib.gd_modal_solve(system._handle, opt, out, err) != lib.GD_OK:
        check(err.status, err)
    return ModalResult(system, ffi.gc(out[0], lib.gd_modal_free))


class ModalResult(_Result):
    """Modes (C gd_modal_result). Per mode (arrays of nmodes): omega_n, frequency_hz,
    omega_d, damping_ratio, log_decrement, eigenvalues, rigid_body, whirl,
    energy_share (nmodes x 4: lateral, torsional, axial, tilt), dominant_motion,
    dominant_component, residual (relative residual of each eigenpair), residual_floor.
    Shapes: shape_re, shape_im (ndof x nmodes views), shapes
    (complex), left (complex or None); energy_by_component (ncomponents x nmodes)."""

    _figure = "modal"
    _FIELDS_DTYPE = _core.MODE_DTYPE  # served by __getattr__

    __slots__ = ("_modes",)

    def __init__(self, system, owner):
        self.system = system
        self._owner = owner
        self._modes = None

    ndof = property(lambda self: self._owner.ndof)
    nmodes = property(lambda self: self._owner.nmodes)
    damped = property(lambda self: bool(self._owner.damped))
    speed = property(lambda self: self._owner.speed)

    @property
    def modes(self):
        """Structured array viewing the C gd_mode records (no copy), made on first use."""
        if self._modes is None:
            self._modes = _core.struct_view(self._owner, self._owner.modes, self.nmodes,
                                            _core.MODE_DTYPE)
        return self._modes

    def __getattr__(self, name):
        # one field of the C records as a strided view (cheaper than through `modes`)
        if name in _core.MODE_DTYPE.names:
            return _core.field_view(self._owner, self._owner.modes, self._owner.nmodes,
                                    _core.MODE_DTYPE, name)
        raise AttributeError(name)

    @property
    def eigenvalues(self):
        m = self.modes
        return m["lambda_re"] + 1j * m["lambda_im"]

    @property
    def whirl(self):
        return [_core.WHIRL_NAMES[w] for w in self.modes["whirl"]]

    @property
    def dominant_motion_names(self):
        return [_core.MOTION_NAMES[w] for w in self.modes["dominant_motion"]]

    @property
    def shape_re(self):
        return self._view(self._owner.shape_re, (self.ndof, self.nmodes), order="F")

    @property
    def shape_im(self):
        return self._view(self._owner.shape_im, (self.ndof, self.nmodes), order="F")

    @property
    def shapes(self):
        """Complex mode shapes, ndof x nmodes (largest entry 1)."""
        return self.shape_re + 1j * self.shape_im

    @property
    def left_re(self):
        if self._owner.left_re == ffi.NULL:
            return None
        return self._view(self._owner.left_re, (self.ndof, self.nmodes), order="F")

    @property
    def left_im(self):
        if self._owner.left_im == ffi.NULL:
            return None
        return self._view(self._owner.left_im, (self.ndof, self.nmodes), order="F")

    @property
    def left(self):
        """Complex left eigenvectors (v^T (2 lambda M + D) u = 1), or None when not
        requested (modal(left=True))."""
        re, im = self.left_re, self.left_im
        return None if re is None else re + 1j * im

    @property
    def energy_by_component(self):
        nc = int(self._owner.ncomponents)
        return self._view(self._owner.energy_by_component, (nc, self.nmodes), order="F")

    @property
    def planetary_classes(self):
        """Each planetary set's class of every mode (docs/planetary.md, "Mode classes";
        gd_modal_planetary_class): {set name: ["rotational", "translational", "planet",
        "mixed" or "-" per mode]}, as `modal --json`'s modes[].planetary_classes; {} without
        sets."""
        h, sysh = self.system._model_handle, self.system._handle
        names = [cstr(lib.gd_planetary_class_names[c]) for c in range(lib.GD_PCLASS_COUNT)]
        return {cstr(h.planetary[k].name):
                [names[lib.gd_modal_planetary_class(sysh, self._owner, j, k)]
                 for j in range(self.nmodes)] for k in range(h.nplanetary)}

    @property
    def classes(self):
        """The class of every mode: that of the first planetary set that moves in it ("-"
        when none does), `modal --json`'s modes[].class; None without planetary sets."""
        pc = list(self.planetary_classes.values())
        if not pc:
            return None
        return [next((c[j] for c in pc if c[j] != "-"), "-") for j in range(self.nmodes)]

    def to_pandas(self):
        """One row per mode, the columns of `geardyn modal --json` (with `class` when the
        model has planetary sets)."""
        pd = _pandas()
        m = self.modes
        comp = self.system.components
        df = pd.DataFrame({
            "mode": np.arange(1, self.nmodes + 1),
            "omega_n_rad_s": m["omega_n"], "frequency_hz": m["frequency_hz"],
            "omega_d_rad_s": m["omega_d"], "damped_frequency_hz": m["omega_d"] / (2 * math.pi),
            "damping_ratio": m["damping_ratio"], "log_decrement": m["log_decrement"],
            "eigenvalue_real": m["lambda_re"], "eigenvalue_imag": m["lambda_im"],
            "whirl": self.whirl, "dominant_motion": self.dominant_motion_names,
            "dominant_component": [comp[c] if c >= 0 else None
                                   for c in m["dominant_component"]],
            "rigid_body": m["rigid_body"].astype(bool),
            "overdamped": m["overdamped"].astype(bool), "unstable": m["unstable"].astype(bool),
        })
        for k, name in enumerate(_core.MOTION_NAMES):
            df["energy_" + name] = m["energy_share"][:, k]
        classes = self.classes
        if classes is not None:
            df["class"] = classes
        return df.set_index("mode")

    def shapes_to_pandas(self):
        """Mode shapes, one row per DOF, one complex column per mode."""
        pd = _pandas()
        return pd.DataFrame(self.shapes, index=self.system.dofs,
                            columns=np.arange(1, self.nmodes + 1))


# ---------------------------------------------------------------- Campbell

_METHODS = {"auto": "GD_EIG_AUTO", "dense": "GD_EIG_DENSE", "sparse": "GD_EIG_SPARSE"}


def campbell(system, speeds, modes=None, orders=(), shaft_orders=True, mesh_orders=True,
             method="auto", kind="auto", shift=None, mac_min=None, threads=0,
             operating_point="static", torque=None):
    """Damped modes over `speeds` (rad/s array or "FROM:TO:COUNT"), tracked by MAC;
    critical speeds for the shaft, user (`orders`) and tooth-mesh orders; instability
    onset. modes: elastic modes tracked ("all" or 0: all; None, the default, as the CLI:
    every mode up to 1.25 x the highest order at the top speed, plus 2, at least 12,
    gd_campbell_default_modes). operating_point, torque: as modal()."""
    sp = sweep(speeds, "speed", "speeds")
    ords = np.ascontiguousarray(np.asarray(orders, dtype=np.float64).ravel())
    opt = ffi.new("gd_campbell_options *")
    lib.gd_campbell_options_init(opt)
    opt.nspeeds, opt.speeds = len(sp), _doubles(sp)
    if modes is not None:
        opt.nmodes = 0 if modes == "all" else whole(modes, "modes", 0, 1000000)
    if len(ords):
        opt.norders, opt.orders = len(ords), _doubles(ords)
    opt.shaft_orders, opt.mesh_orders = int(bool(shaft_orders)), int(bool(mesh_orders))
    if method not in _METHODS:
        raise model_error("method", "unknown method '%s'" % method, "use auto, dense or sparse")
    opt.method = getattr(lib, _METHODS[method])
    if kind not in ("auto", "undamped", "damped"):
        raise model_error("kind", "unknown kind '%s'" % kind, "use auto, undamped or damped")
    opt.kind = _KINDS[kind]
    if shift is not None:
        opt.shift = quantity(shift, "speed", "shift")
    if mac_min is not None:
        opt.mac_min = float(mac_min)
    opt.nthreads = whole(threads, "threads", 0, 4096)
    _operating(system, operating_point, torque, -1.0, False)
    out = ffi.new("gd_campbell_result **")
    err = new_error()
    if modes is None:  # the CLI's count, from the orders at the top speed
        n, limit = ffi.new("int *"), ffi.new("double *")
        check(lib.gd_campbell_default_modes(system._handle, opt, n, limit, err), err)
        opt.nmodes = n[0]
    check(lib.gd_campbell(system._handle, opt, out, err), err)
    return CampbellResult(system, ffi.gc(out[0], lib.gd_campbell_free))


class CampbellResult(_Result):
    """Campbell diagram (C gd_campbell_result). speeds (rad/s), speeds_rpm; per track
    and speed (ntracks x nspeeds): frequency_hz (damped, NaN where the track does not
    exist), natural_frequency_hz, damping_ratio, log_decrement, and `modes` (the C
    records); tracks, orders and critical_speeds as lists of dicts;
    instability_onset (rad/s, NaN when stable)."""

    def __init__(self, system, owner):
        super().__init__(system, owner)
        r = owner
        self.nspeeds, self.ntracks = int(r.nspeeds), int(r.ntracks)
        self.sparse = bool(r.sparse)
        self.nrigid = int(r.nrigid)
        self.instability_onset = float(r.instability_onset)
        self.instability_track = int(r.instability_track)
        self.tracks = [{"id": int(t.id), "whirl": _core.WHIRL_NAMES[t.whirl],
                        "dominant_motion": _core.MOTION_NAMES[t.dominant_motion]}
                       for t in (r.tracks[i] for i in range(self.ntracks))]
        self.orders = [{"label": cstr(o.label), "order": float(o.order),
                        "kind": ("shaft", "user", "mesh")[o.kind]}
                       for o in (r.orders[i] for i in range(r.norders))]
        self.critical_speeds = [
            {"mode": int(c.mode), "order": self.orders[c.order]["label"],
             "order_value": self.orders[c.order]["order"], "speed_rad_s": float(c.speed),
             "speed_rpm": float(c.speed_rpm), "frequency_hz": float(c.frequency_hz)}
            for c in (r.critical[i] for i in range(r.ncritical))]

    @property
    def speeds(self):
        return self._view(self._owner.speeds, self.nspeeds)

    @property
    def speeds_rpm(self):
        return self.speeds * 30 / math.pi

    @property
    def modes(self):
        return _core.struct_view(self._owner, self._owner.modes, (self.ntracks, self.nspeeds),
                                 _core.MODE_DTYPE)

    @property
    def exists(self):
        return self.modes["rigid_body"] >= 0

    @property
    def frequency_hz(self):
        """Damped frequency omega_d / 2 pi; NaN where the track does not exist."""
        m = self.modes
        return np.where(m["rigid_body"] >= 0, m["omega_d"] / (2 * math.pi), np.nan)

    @property
    def natural_frequency_hz(self):
        return self.modes["frequency_hz"]

    @property
    def damping_ratio(self):
        return self.modes["damping_ratio"]

    @property
    def log_decrement(self):
        return self.modes["log_decrement"]

    def to_pandas(self):
        """Long form, one row per (speed, track) where the track exists, as campbell.csv."""
        pd = _pandas()
        m, ok = self.modes, self.exists
        t_idx, s_idx = np.nonzero(ok)
        ids = np.array([t["id"] for t in self.tracks])
        sp = self.speeds
        return pd.DataFrame({
            "speed_rad_s": sp[s_idx], "speed_rpm": sp[s_idx] * 30 / math.pi,
            "mode": ids[t_idx], "frequency_hz": self.frequency_hz[t_idx, s_idx],
            "natural_frequency_hz": m["frequency_hz"][t_idx, s_idx],
            "damping_ratio": m["damping_ratio"][t_idx, s_idx],
            "log_decrement": m["log_decrement"][t_idx, s_idx],
            "whirl": [_core.WHIRL_NAMES[w] for w in m["whirl"][t_idx, s_idx]],
            "dominant_motion": [_core.MOTION_NAMES[w] for w in m["dominant_motion"][t_idx, s_idx]],
        }).sort_values(["speed_rad_s", "mode"], kind="stable").reset_index(drop=True)

    def plot(self, ax=None, orders=True, max_frequency=None):
        """The Campbell diagram as a plotly Figure (damped frequency of every track
        over speed in rpm, order lines named at their ends, critical speeds;
        max_frequency in Hz ends the axis). With ax (a matplotlib Axes): drawn there
        with matplotlib instead, as before, and the Axes returned."""
        if ax is None:
            from . import figures
            return figures.campbell(self, max_frequency=max_frequency)
        import matplotlib.pyplot as plt
        ax = ax or plt.gca()
        rpm = self.speeds_rpm
        f = self.frequency_hz
        for t, tr in enumerate(self.tracks):
            ax.plot(rpm, f[t], label="mode %d (%s)" % (tr["id"], tr["whirl"]))
        if orders:
            for o in self.orders:
                ax.plot(rpm, o["order"] * self.speeds / (2 * math.pi), "k--", lw=0.7)
        ax.set_xlabel("speed (rpm)")
        ax.set_ylabel("damped natural frequency (Hz)")
        return ax


# ---------------------------------------------------------------- probes

def _dof_of(system, text, what):
    node, dot, d = text.rpartition(".")
    if not dot:
        raise model_error(what, "'%s' is not NODE.DOF" % text, "e.g. pinion.x, gear.rz")
    if lib.gd_model_find_node(system._model_handle, node.encode()) < 0:
        raise model_error(what, "unknown node '%s'" % node,
                          "nodes: " + ", ".join(system.model.nodes))
    if d not in _core.DOF_NAMES:
        raise model_error(what, "unknown DOF '%s'" % d, "use x, y, z, rx, ry or rz")
    i = system.dof(node, d)
    if i < 0:
        raise model_error(what, "DOF %s of node '%s' is not active in this model" % (d, node))
    return i


def _probe(system, text, what="output"):
    """A gd_probe from NODE.DOF | node:NODE.DOF | mesh:NAME | bearing:NAME.DIR (the
    CLI's output specs)."""
    p = ffi.new("gd_probe *")
    name = text.encode()[:ffi.sizeof(p.name) - 1]
    ffi.memmove(p.name, name, len(name))
    kind = lib.gd_probe_element(text.encode(), ffi.NULL)
    if kind != ffi.NULL:
        # PROBE:NAME or PROBE:NAME.DIR, the element kind's own syntax (geardyn/elements.h)
        prefix, kname = cstr(kind.probe), cstr(kind.name)
        body = text[len(prefix) + 1:]
        inst, dot, d = body.rpartition(".") if kind.probe_dirs else (body, "", "")
        if kind.probe_dirs and not dot:
            raise model_error(what, "'%s' is not %s:NAME.DIR" % (text, prefix),
                              "e.g. %s:A1.x" % prefix)
        p.element, p.index = kind, lib.gd_probe_instance(system._handle, kind, inst.encode())
        if p.index < 0:
            names = [c for c, k in zip(system.components, system.component_kinds) if k == kname]
            plural = kname + ("es" if kname.endswith(("s", "sh", "ch", "x")) else "s")
            raise model_error(what, "unknown %s '%s'" % (kname, inst),
                              "%s: %s" % (plural, ", ".join(names)))
        if kind.probe_dirs:
            if d not in _core.DOF_NAMES:
                raise model_error(what, "unknown direction '%s'" % d, "use x, y, z, rx, ry or rz")
            p.dir = _core.DOF_NAMES.index(d)
    else:
        p.element = ffi.NULL
        p.index = _dof_of(system, text[5:] if text.startswith("node:") else text, what)
    return p


def _probes(system, specs, what="output"):
    arr = ffi.new("gd_probe[]", max(len(specs), 1))
    for k, s in enumerate(specs):
        arr[k] = _probe(system, s, what)[0]
    return arr


# ---------------------------------------------------------------- FRF

_QUANTITIES = ("receptance", "mobility", "accelerance")


def _planetary_load(system, text):
    """The load of `planetary:SET:sun_mesh:L` (or ring_mesh): gd_planetary_mesh_excitation
    over the system's DOFs, as C arrays (re, im)."""
    parts = text.split(":")
    if len(parts) != 4:
        raise model_error("input", "'%s': write planetary:SET:sun_mesh:L or "
                          "planetary:SET:ring_mesh:L (L the mesh harmonic, 1, 2, ...)" % text)
    _p, name, kind, harm = parts
    sets = system.model.planetary_sets
    if name not in sets:
        raise model_error("input", "'%s': the model has no planetary set '%s'%s"
                          % (text, name, "" if sets else " (it has none)"))
    if kind not in ("sun_mesh", "ring_mesh"):
        raise model_error("input", "'%s': unknown mesh kind '%s'" % (text, kind),
                          "use sun_mesh or ring_mesh")
    if not (harm.isdigit() and 1 <= int(harm) <= 1000):
        raise model_error("input", "'%s': the harmonic '%s' is not a whole number from 1 to "
                          "1000" % (text, harm))
    n = max(system.ndof, 1)
    re, im = ffi.new("double[]", n), ffi.new("double[]", n)
    err = new_error()
    check(lib.gd_planetary_mesh_excitation(system._handle, sets.index(name), int(harm),
                                           1 if kind == "ring_mesh" else 0, re, im, err), err)
    return re, im


def frf(system, input, outputs, freqs, speed=None, method="direct", modes=None,
        quantity="receptance", threads=0, operating_point="static", torque=None):
    """Frequency response to a unit force or moment at `input` (NODE.DOF, torque:NODE, or
    NODE.xy for directional FRFs; planetary:SET:sun_mesh:L or planetary:SET:ring_mesh:L,
    a planetary set's phased mesh excitation at mesh harmonic L per unit transmission
    error) at `outputs` (NODE.DOF, mesh:NAME, bearing:NAME.DIR; NODE.xy with a
    directional input) over `freqs` (rad/s or "FROM:TO:COUNT").
    method: "direct" or "modal" (summing `modes` modes, default all). quantity:
    receptance, mobility or accelerance (displacement outputs)."""
    if isinstance(outputs, str):
        outputs = [outputs]
    if not isinstance(input, str):
        raise model_error("input", "expected an input spec (string), got %r" % (input,))
    fr = sweep(freqs, "speed", "freqs")
    inp = input[5:] if input.startswith("node:") else input
    directional = inp.endswith(".xy") and len(inp) > 3
    load = None
    if input.startswith("planetary:"):
        load = _planetary_load(system, input)
        nz = [i for i in range(system.ndof) if load[0][i] != 0 or load[1][i] != 0]
        inputs = [nz[0] if nz else 0]  # as the CLI: the first DOF the load acts on
        directional = False
    elif input.startswith("torque:"):
        inputs = [_dof_of(system, input[7:] + ".rz", "input")]
    elif directional:
        inputs = [_dof_of(system, inp[:-3] + ".x", "input"),
                  _dof_of(system, inp[:-3] + ".y", "input")]
    else:
        inputs = [_dof_of(system, inp, "input")]
    specs = []
    for o in outputs:
        base = o[5:] if o.startswith("node:") else o
        if directional:
            if not base.endswith(".xy"):
                raise model_error("output", "with a directional input (%s) give outputs "
                                  "NODE.xy, not '%s'" % (input, o))
            specs += [base[:-3] + ".x", base[:-3] + ".y"]
        else:
            if base.endswith(".xy"):
                raise model_error("output", "'%s' is directional: give a directional input "
                                  "NODE.xy too" % o)
            specs.append(o)
    probes = _probes(system, specs)
    if quantity not in _QUANTITIES:
        raise model_error("quantity", "unknown quantity '%s'" % quantity,
                          "use receptance, mobility or accelerance")
    if quantity != "receptance":
        for k in range(len(specs)):
            if probes[k].element != ffi.NULL:
                raise model_error("quantity", "%s applies to displacement outputs; '%s' is a "
                                  "force" % (quantity, specs[k]))
    if method not in ("direct", "modal"):
        raise model_error("method", "unknown method '%s'" % method, "use direct or modal")
    ins = ffi.new("int[]", inputs)
    opt = ffi.new("gd_frf_options *")
    lib.gd_frf_options_init(opt)
    opt.nfreq, opt.freqs = len(fr), _doubles(fr)
    opt.speed = _speed(system, speed)
    opt.ninputs, opt.inputs = len(inputs), ins
    opt.noutputs, opt.outputs = len(specs), probes
    opt.quantity = _QUANTITIES.index(quantity)
    opt.method = lib.GD_FRF_MODAL if method == "modal" else lib.GD_FRF_DIRECT
    if modes is not None:
        opt.nmodes = 0 if modes == "all" else whole(modes, "modes", 0, 1000000)
    opt.nthreads = whole(threads, "threads", 0, 4096)
    _operating(system, operating_point, torque, opt.speed, True)
    out = ffi.new("gd_frf_result **")
    err = new_error()
    if load is None:
        check(lib.gd_frf(system._handle, opt, out, err), err)
    else:
        check(lib.gd_frf_load(system._handle, opt, load[0], load[1], out, err), err)
    res = FrfResult(system, ffi.gc(out[0], lib.gd_frf_free), input, list(outputs), specs,
                    [probes[k].element != ffi.NULL for k in range(len(specs))],
                    quantity, method, float(opt.speed), directional)
    return res


class FrfResult(_ReImResult):
    """Frequency response (C gd_frf_result). freqs (rad/s); re, im (noutputs x ninputs
    x nfreq views) and H (complex); singular (per frequency). With a directional input:
    forward and backward (noutputs x nfreq complex). series(): the CLI's named outputs."""

    _figure = "frf"

    def __init__(self, system, owner, input, outputs, specs, is_force, quantity, method,
                 speed, directional):
        super().__init__(system, owner)
        r = owner
        self.input, self.outputs, self.probes = input, outputs, specs
        self.quantity, self.method, self.speed = quantity, method, speed
        self.directional = directional
        self.is_force = is_force
        self.nfreq, self.ninputs, self.noutputs = int(r.nfreq), int(r.ninputs), int(r.noutputs)
        self._shape = (self.noutputs, self.ninputs, self.nfreq)
        self.nsingular, self.modes_summed, self.rigid_body_modes = \
            int(r.nsingular), int(r.nmodes_used), int(r.nrigid)
        if directional:
            n = self.nfreq
            fwd = np.empty((len(outputs), 4, n))
            for o in range(len(outputs)):
                b = fwd[o]
                lib.gd_frf_directional(r, 2 * o, 2 * o + 1, _doubles(b[0]), _doubles(b[1]),
                                       _doubles(b[2]), _doubles(b[3]))
            self.forward = fwd[:, 0] + 1j * fwd[:, 1]
            self.backward = fwd[:, 2] + 1j * fwd[:, 3]

    @property
    def freqs(self):
        return self._view(self._owner.freqs, self.nfreq)

    H = property(_ReImResult._complex)

    @property
    def singular(self):
        return self._view(self._owner.singular, self.nfreq, np.int32).astype(bool)

    def series(self):
        """[(name, quantity, complex values over freqs)] as `geardyn frf --json` lists
        them."""
        if self.directional:
            out = []
            for o, name in enumerate(self.outputs):
                out.append((name + " forward", self.quantity, self.forward[o]))
                out.append((name + " backward", self.quantity, self.backward[o]))
            return out
        H = self.H
        return [(s, "force" if f else self.quantity, H[k, 0])
                for k, (s, f) in enumerate(zip(self.probes, self.is_force))]

    def to_pandas(self):
        """Long form, one row per output and frequency, as frf.csv."""
        pd = _pandas()
        fr = self.freqs
        frames = []
        for name, _q, h in self.series():
            frames.append(pd.DataFrame({
                "output": name, "frequency_rad_s": fr, "frequency_hz": fr / (2 * math.pi),
                "magnitude": np.abs(h), "phase_deg": np.degrees(np.angle(h)),
                "real": h.real, "imag": h.imag}))
        return pd.concat(frames, ignore_index=True)


# ---------------------------------------------------------------- unbalance

ORBIT_DTYPE = _core.struct_dtype("gd_orbit", {"major": "f8", "minor": "f8", "angle": "f8",
                                             "whirl": _core._ENUM})


def _default_unbalance_outputs(system):
    """The CLI's outputs when none is given: x, y, rz of each unbalanced node and its
    orbit, every mesh force, every bearing's x and y force."""
    h = system._model_handle
    names, orbits = [], []
    nodes = system.model.nodes
    for u in range(h.nunbalances):
        node = h.unbalances[u].node
        if node in orbits:
            continue
        for d in ("x", "y", "rz"):
            if lib.gd_system_dof(system._handle, node, _core.DOF_NAMES.index(d)) >= 0:
                names.append("%s.%s" % (nodes[node], d))
        if (lib.gd_system_dof(system._handle, node, lib.GD_X) >= 0
                and lib.gd_system_dof(system._handle, node, lib.GD_Y) >= 0):
            orbits.append(node)
    forces = ffi.new("gd_probe[]", 64)
    n = lib.gd_probe_defaults(system._handle, forces, 64)
    names += [cstr(forces[k].name) for k in range(n)]
    return names[:64], [nodes[n] for n in orbits]


def unbalance(system, speeds, outputs=None, orbits=None, threads=0,
              operating_point="static", torque=None):
    """Steady response to the model's unbalances over `speeds` (rad/s or
    "FROM:TO:COUNT"), one harmonic per distinct shaft speed. outputs: NODE.DOF,
    mesh:NAME, bearing:NAME.DIR, orbit:NODE; None: the CLI's defaults."""
    sp = sweep(speeds, "speed", "speeds")
    if outputs is None and orbits is None:
        specs, orbit_nodes = _default_unbalance_outputs(system)
    else:
        specs, orbit_nodes = [], list(orbits or [])
        for o in ([outputs] if isinstance(outputs, str) else (outputs or [])):
            if o.startswith("orbit:"):
                orbit_nodes.append(o[6:])
            else:
                specs.append(o)
    orb = []
    for name in orbit_nodes:
        n = lib.gd_model_find_node(system._model_handle, name.encode())
        if n < 0:
            raise model_error("output", "unknown node '%s'" % name)
        if system.dof(name, "x") < 0 or system.dof(name, "y") < 0:
            raise model_error("output", "node '%s' has no active x and y for an orbit" % name)
        orb.append(n)
    probes = _probes(system, specs)
    orbit_arr = ffi.new("int[]", max(len(orb), 1))
    for k, n in enumerate(orb):
        orbit_arr[k] = n
    opt = ffi.new("gd_unbalance_options *")
    lib.gd_unbalance_options_init(opt)
    opt.nspeeds, opt.speeds = len(sp), _doubles(sp)
    opt.noutputs, opt.outputs = len(specs), probes
    opt.norbits, opt.orbit_nodes = len(orb), orbit_arr
    opt.nthreads = whole(threads, "threads", 0, 4096)
    _operating(system, operating_point, torque, -1.0, False)
    out = ffi.new("gd_unbalance_result **")
    err = new_error()
    check(lib.gd_unbalance_response(system._handle, opt, out, err), err)
    return UnbalanceResult(system, ffi.gc(out[0], lib.gd_unbalance_free), specs,
                           [system.model.nodes[n] for n in orb])


class UnbalanceResult(_ReImResult):
    """Unbalance response (C gd_unbalance_result). speeds (rad/s); harmonics (list of
    dicts: order, unbalances); re, im (nharmonics x noutputs x nspeeds views) and
    response (complex; x = Re(X e^{i w t})); orbits (nharmonics x norbits x nspeeds
    structured view: major, minor, angle, whirl)."""

    _figure = "unbalance"

    def __init__(self, system, owner, outputs, orbit_nodes):
        super().__init__(system, owner)
        r = owner
        self.outputs, self.orbit_nodes = outputs, orbit_nodes
        self.nspeeds, self.noutputs = int(r.nspeeds), int(r.noutputs)
        self.norbits, self.nharmonics = int(r.norbits), int(r.nharmonics)
        self._shape = (self.nharmonics, self.noutputs, self.nspeeds)
        self.harmonics = [{"order": float(r.harmonics[h].order),
                           "unbalances": int(r.harmonics[h].nunbalances)}
                          for h in range(self.nharmonics)]

    @property
    def speeds(self):
        return self._view(self._owner.speeds, self.nspeeds)

    response = property(_ReImResult._complex)

    @property
    def orbits(self):
        return _core.struct_view(self._owner, self._owner.orbits,
                                 (self.nharmonics, self.norbits, self.nspeeds), ORBIT_DTYPE)

    @property
    def singular(self):
        return self._view(self._owner.singular, self.nspeeds, np.int32).astype(bool)

    def to_pandas(self):
        """Long form, one row per harmonic, output and speed, as unbalance.csv."""
        pd = _pandas()
        sp = self.speeds
        X = self.response
        frames = []
        for h, harm in enumerate(self.harmonics):
            for o, name in enumerate(self.outputs):
                x = X[h, o]
                frames.append(pd.DataFrame({
                    "output": name, "harmonic_order": harm["order"], "speed_rad_s": sp,
                    "speed_rpm": sp * 30 / math.pi, "magnitude": np.abs(x),
                    "phase_deg": np.degrees(np.angle(x)), "real": x.real, "imag": x.imag}))
        return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()

    def orbits_to_pandas(self):
        pd = _pandas()
        sp = self.speeds
        ob = self.orbits
        frames = []
        for h, harm in enumerate(self.harmonics):
            for k, node in enumerate(self.orbit_nodes):
                o = ob[h, k]
                frames.append(pd.DataFrame({
                    "node": node, "harmonic_order": harm["order"], "speed_rad_s": sp,
                    "speed_rpm": sp * 30 / math.pi, "major": o["major"], "minor": o["minor"],
                    "angle_deg": np.degrees(o["angle"]),
                    "whirl": [_core.WHIRL_NAMES[w] for w in o["whirl"]]}))
        return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()
