"""Time integration (docs/transient.md): gd_transient_model_build, gd_transient_new,
gd_transient_run, with the record specs and the defaults of `geardyn transient`."""
import math

from ._numpy import np

from . import _core
from ._core import ffi, lib, check, new_error, cstr, quantity, model_error
from .analyses import _Result, _pandas
from .laws import with_laws

__all__ = ["transient", "TransientResult", "Waterfall"]

_MESH_WHAT = {"force": (lib.GD_REC_MESH_FORCE, "N"), "state": (lib.GD_REC_MESH_STATE, "-"),
              "deflection": (lib.GD_REC_MESH_DEFLECTION, "m"),
              "stiffness": (lib.GD_REC_MESH_STIFFNESS, "N/m")}
_SFD_WHAT = {"fx": (lib.GD_REC_SFD_FX, "N"), "fy": (lib.GD_REC_SFD_FY, "N"),
             "ecc": (lib.GD_REC_SFD_ECCENTRICITY, "-")}
_DOF_WHAT = {"disp": lib.GD_REC_DISP, "vel": lib.GD_REC_VEL, "angle": lib.GD_REC_ANGLE,
             "speed": lib.GD_REC_SPEED}
_DOF_UNIT = {"disp": ("m", "rad"), "vel": ("m/s", "rad/s"), "angle": ("m", "rad"),
             "speed": ("m/s", "rad/s")}


def _mesh_names(model):
    """The time-integration laws' mesh numbering (gd_model_mesh_name): the gear meshes,
    then each planetary set's "SET.sun_mesh<n>" and "SET.ring_mesh<n>"."""
    h = model._handle
    return [cstr(lib.gd_model_mesh_name(h, i)) for i in range(lib.gd_model_mesh_count(h))]


def _pick(item, name, names, what, plural):
    """Indices of the item's NAME among names ('*': all)."""
    if not names:
        raise model_error("record", "'%s': the model has no %s" % (item, what))
    if name == "*":
        return range(len(names))
    if name in names:
        return [names.index(name)]
    raise model_error("record", "'%s': unknown %s '%s'" % (item, what, name),
                      "%s: %s" % (plural, ", ".join(names)))


def _parse_record(system, tm, item):
    """One record item of `--record` (transient_record.h): NODE.DOF[:disp|vel|angle|speed],
    ratio:A/B, mesh:NAME[:what] ('*': every mesh), sfd:BEARING[:fx|fy|ecc],
    law:NAME[:RECORD] (a law of the model's `laws:` list). Returns
    [(kind, index, index2, name, unit)]."""
    m = system.model
    if item.startswith("ratio:"):
        a, slash, b = item[6:].partition("/")
        if not slash or not a or not b:
            raise model_error("record", "'%s': expected ratio:NODE_A/NODE_B" % item)
        dofs = []
        for n in (a, b):
            if n not in m.nodes:
                raise model_error("record", "'%s': unknown node '%s'" % (item, n),
                                  "nodes: " + ", ".join(m.nodes))
            d = system.dof(n, "rz")
            if d < 0:
                raise model_error("record", "'%s': node '%s' has no active rz DOF" % (item, n))
            dofs.append(d)
        return [(lib.GD_REC_SPEED_RATIO, dofs[0], dofs[1], "ratio:%s/%s" % (a, b), "-")]
    if item.startswith("mesh:"):
        name, _c, what = item[5:].partition(":")
        what = what or "force"
        if what not in _MESH_WHAT:
            raise model_error("record", "'%s': unknown mesh quantity '%s'" % (item, what),
                              "use force, state, deflection or stiffness")
        kind, unit = _MESH_WHAT[what]
        meshes = _mesh_names(m)
        idx = _pick(item, name, meshes, "mesh", "meshes")
        return [(kind, i, 0, "mesh:%s:%s" % (meshes[i], what), unit) for i in idx]
    if item.startswith("sfd:"):
        name, _c, what = item[4:].partition(":")
        what = what or "ecc"
        if what not in _SFD_WHAT:
            raise model_error("record", "'%s': unknown damper quantity '%s'" % (item, what),
                              "use fx, fy or ecc")
        kind, unit = _SFD_WHAT[what]
        dampers = [m.bearings[tm.sfd_bearing[s]] for s in range(tm.spec.nsfds)]
        idx = _pick(item, name, dampers, "squeeze film damper", "dampers")
        return [(kind, s, 0, "sfd:%s:%s" % (dampers[s], what), unit) for s in idx]
    if item.startswith("law:"):
        name, _c, what = item[4:].partition(":")
        laws = [ffi.string(tm.spec.laws[i].name).decode() for i in range(tm.spec.nlaws)]
        out = []
        for i in _pick(item, name, laws, "law (a `laws:` list)", "laws"):
            t = tm.spec.laws[i].type
            recs = [ffi.string(t.records[k].name).decode() for k in range(t.nrecords)]
            if not recs:
                raise model_error("record", "'%s': law '%s' has no records" % (item, laws[i]))
            w = what or recs[0]
            if w not in recs:
                raise model_error("record", "'%s': law '%s' has no record '%s'"
                                  % (item, laws[i], w), "use " + ", ".join(recs))
            k = recs.index(w)
            out.append((lib.GD_REC_LAW, i, k, "law:%s:%s" % (laws[i], w),
                        ffi.string(t.records[k].unit).decode()))
        return out
    spec = item[5:] if item.startswith("node:") else item
    base, colon, what = spec.rpartition(":")
    if not colon:
        base, what = spec, "disp"
    if what not in _DOF_WHAT:
        raise model_error("record", "'%s': unknown DOF quantity '%s'" % (item, what),
                          "use disp, vel, angle or speed")
    node, dot, d = base.rpartition(".")
    if not dot or not node or not d:
        raise model_error("record", "'%s': expected NODE.DOF[:disp|vel|angle|speed], "
                          "ratio:A/B, mesh:NAME[:what] or sfd:BEARING[:what]" % item)
    if node not in m.nodes:
        raise model_error("record", "'%s': unknown node '%s'" % (item, node),
                          "nodes: " + ", ".join(m.nodes))
    if d not in _core.DOF_NAMES:
        raise model_error("record", "'%s': unknown DOF '%s'" % (item, d),
                          "use x, y, z, rx, ry or rz")
    i = system.dof(node, d)
    if i < 0:
        raise model_error("record", "'%s': %s is not an active DOF" % (item, base))
    unit = _DOF_UNIT[what][1 if d.startswith("r") else 0]
    return [(_DOF_WHAT[what], i, 0, "%s:%s" % (base, what), unit)]


def _default_records(system, tm):
    """The CLI's records when none is given: every nonlinear mesh's force (and contact
    state with backlash), every damper's fx and fy; else the total speed of every rz
    DOF; else every DOF's displacement (at most 64)."""
    m = system.model
    meshes = _mesh_names(m)
    recs = []
    for i in range(tm.spec.nmeshes):
        name = meshes[tm.meshes[i].mesh]
        recs.append((lib.GD_REC_MESH_FORCE, tm.meshes[i].mesh, 0, "mesh:%s:force" % name, "N"))
        if tm.meshes[i].backlash:
            recs.append((lib.GD_REC_MESH_STATE, tm.meshes[i].mesh, 0, "mesh:%s:state" % name,
                         "-"))
    for s in range(tm.spec.nsfds):
        name = m.bearings[tm.sfd_bearing[s]]
        recs += [(lib.GD_REC_SFD_FX, s, 0, "sfd:%s:fx" % name, "N"),
                 (lib.GD_REC_SFD_FY, s, 0, "sfd:%s:fy" % name, "N")]
    for i in range(tm.spec.nlaws):
        t = tm.spec.laws[i].type
        if t.nrecords:
            name = ffi.string(tm.spec.laws[i].name).decode()
            recs.append((lib.GD_REC_LAW, i, 0, "law:%s:%s" % (name, ffi.string(
                t.records[0].name).decode()), ffi.string(t.records[0].unit).decode()))
    if recs:
        return recs
    rz = [i for i in range(system.ndof) if system.dof_type[i] == lib.GD_RZ]
    if rz:
        return [(lib.GD_REC_SPEED, i, 0, system.dofs[i] + ":speed", "rad/s") for i in rz]
    return [(lib.GD_REC_DISP, i, 0, system.dofs[i] + ":disp",
             "rad" if system.dof_type[i] >= lib.GD_RX else "m")
            for i in range(min(system.ndof, 64))]


def _records(system, tm, records):
    """The records of a spec list (comma-separated items allowed), or the CLI's defaults
    (None), as [(kind, index, index2, name, unit)]."""
    if records is None:
        return _default_records(system, tm)
    recs = []
    for text in ([records] if isinstance(records, str) else records):
        if not isinstance(text, str):  # records=[1, 2]: AttributeError before
            raise model_error("records", "expected record names (strings), got %r" % (text,),
                              "write e.g. records=['gear_a.x', 'mesh:mesh']")
        for item in text.split(","):
            item = item.strip()
            if not item:
                raise model_error("record", "'%s': empty item" % text)
            recs += _parse_record(system, tm, item)
    return recs


def _record_array(recs):
    """The gd_tr_record array of _records' list."""
    rr = ffi.new("gd_tr_record[]", max(len(recs), 1))
    for k, (kind, i, i2, _n, _u) in enumerate(recs):
        rr[k].kind, rr[k].index, rr[k].index2 = kind, i, i2
    return rr


def _times(duration, revolutions, speed, record_from, output_interval):
    """t_end, record_from, output interval as `geardyn transient` resolves them."""
    if (duration is None) == (revolutions is None):
        raise model_error("duration", "give duration or revolutions (not both)")
    if duration is not None:
        t_end = quantity(duration, "time", "duration")
        if not t_end > 0:
            raise model_error("duration", "give a time > 0")
    else:
        n = float(revolutions)
        if not n > 0:
            raise model_error("revolutions", "give a positive number")
        if not speed > 0:
            raise model_error("revolutions", "revolutions need a reference speed > 0",
                              "give speed= or 'speed:' in the model, or use duration=")
        t_end = 2 * math.pi * n / speed
    frm = 0.5 * t_end
    if record_from is not None:
        frm = quantity(record_from, "time", "record_from")
        if frm < 0 or frm >= t_end:
            raise model_error("record_from", "give a time in [0, %g s)" % t_end)
    dt = (t_end - frm) / 2000.0
    if speed > 0 and 2 * math.pi / speed / 32 < dt:
        dt = max(2 * math.pi / speed / 32, (t_end - frm) / 2e6)
    if output_interval is not None:
        dt = quantity(output_interval, "time", "output_interval")
        if not dt > 0:
            raise model_error("output_interval", "give a time > 0")
    return t_end, frm, dt


def _profile(system, speed_ramp, speed_table, duration):
    """The gd_speed_profile of speed_ramp=(FROM, TO) over [0, duration] or
    speed_table=(times, speeds), its arrays (kept alive), t_end and its speed range."""
    prof = ffi.new("gd_speed_profile *")
    keep = []
    if speed_ramp is not None:
        if duration is None:
            raise model_error("speed_ramp", "a speed ramp needs duration=",
                              "give duration= (the ramp's length)")
        t_end = quantity(duration, "time", "duration")
        w0, w1 = (quantity(v, "speed", "speed_ramp") for v in speed_ramp)
        if w0 < 0 or w1 < 0 or w0 == w1 or not t_end > 0:
            raise model_error("speed_ramp", "give FROM != TO, speeds >= 0, duration > 0")
        prof.kind, prof.t0, prof.t1 = lib.GD_SPEED_RAMP, 0.0, t_end
        setattr(prof, "from", w0)  # a Python keyword
        prof.to = w1
        lo, hi = min(w0, w1), max(w0, w1)
    else:
        try:
            times, speeds = (np.ascontiguousarray(a, dtype=float) for a in speed_table)
        except (TypeError, ValueError):
            raise model_error("speed_table", "give (times, speeds): two arrays of numbers") \
                from None
        if times.shape != speeds.shape or times.ndim != 1 or times.size < 2:
            # an empty table: IndexError before
            raise model_error("speed_table", "give (times, speeds) of one length, at least two "
                              "rows")
        ct, cw = ffi.new("double[]", list(times)), ffi.new("double[]", list(speeds))
        keep += [ct, cw]
        prof.kind, prof.n, prof.t, prof.speed = lib.GD_SPEED_TABLE, len(times), ct, cw
        t_end = (quantity(duration, "time", "duration") if duration is not None
                 else float(times[-1]))
        lo, hi = float(np.min(np.abs(speeds))), float(np.max(np.abs(speeds)))
    err = new_error()
    check(lib.gd_speed_profile_check(prof, err), err)
    return prof, keep, t_end, lo, hi


class Waterfall:
    """Order-tracked run-up waterfall (C gd_waterfall): speeds (rad/s; speeds_rpm), one
    amplitude spectrum per block of revs_per_block turns (frequencies[i], amplitudes[i],
    Hz and the record's unit), the orders of campbell (orders, order_labels) and the
    order cuts order_amplitude (norders x nspeeds, NaN above the spectra's reach)."""

    def __init__(self, w, unit=""):
        n, no = int(w.nspeeds), int(w.norders)
        self.unit = unit  # the tracked record's unit
        self.speeds = np.array([w.speeds[i] for i in range(n)])
        self.speeds_rpm = self.speeds * 30 / math.pi
        self.revs_per_block = float(w.revs_per_block)
        self.orders = np.array([w.orders[k].order for k in range(no)])
        self.order_labels = [cstr(w.orders[k].label) for k in range(no)]
        self.order_amplitude = np.array([w.order_amplitude[i] for i in range(no * n)]).reshape(
            no, n) if no else np.zeros((0, n))
        self.frequencies = [np.array([w.spectra[i].freq[k] for k in range(w.spectra[i].n)])
                            for i in range(n)]
        self.amplitudes = [np.array([w.spectra[i].amplitude[k]
                                     for k in range(w.spectra[i].n)]) for i in range(n)]

    def plot(self):
        """The waterfall as a plotly Figure: spectra over speed with the order lines, and
        the order cuts (geardyn/figures.py)."""
        from . import figures
        return figures.waterfall(self, self.unit)

    def _repr_html_(self):
        try:
            return self.plot().to_html(full_html=False, include_plotlyjs=True)
        except ImportError:
            return None

    def __repr__(self):
        return "Waterfall(%d blocks of %g turns, %.6g-%.6g rpm, orders %s)" % (
            len(self.speeds), self.revs_per_block, self.speeds_rpm.min(),
            self.speeds_rpm.max(), ", ".join(self.order_labels))


def _order_track(system, res, prof, index, revs_per_block, samples_per_rev):
    """The Waterfall of record index of res under the profile."""
    n = res.nout
    ang = ffi.new("double[]", max(n, 1))
    for k in range(n):
        lib.gd_speed_profile_eval(prof, res._owner.t[k], ang + k, ffi.NULL, ffi.NULL)
    o = ffi.new("gd_order_track_options *")
    lib.gd_order_track_options_init(o)
    o.revs_per_block, o.samples_per_rev = float(revs_per_block), int(samples_per_rev)
    out = ffi.new("gd_waterfall **")
    err = new_error()
    check(lib.gd_waterfall_order_track(system._handle, res._owner.t,
                                       res._owner.values + index * n, ang, n, o, out, err), err)
    w = ffi.gc(out[0], lib.gd_waterfall_free)
    return Waterfall(w, res.units[index] if index < len(res.units) else "")


def _cutoff(condense):
    """The cut-off of `--condense C`: -1 for "auto", 0 for "all", else a frequency > 0
    (rad/s, or a string with a unit)."""
    if isinstance(condense, str) and condense in ("auto", "all"):
        return -1.0 if condense == "auto" else 0.0
    try:
        f = quantity(condense, "speed", "condense")
    except ValueError:
        raise model_error("condense", "'%s' is not off, auto, all or a frequency > 0" % (condense,),
                          "e.g. condense=\"8kHz\"") from None
    if not (f > 0 and math.isfinite(f)):
        raise model_error("condense", "'%s' is not off, auto, all or a frequency > 0" % (condense,),
                          "e.g. condense=\"8kHz\"")
    return f


def _condensed_dict(ci):
    """The condensation's description, the keys of the CLI's `condensed` JSON object
    (frequencies in Hz) and the rest of gd_tr_condensed_info."""
    hz = 1 / (2 * math.pi)
    return {"states": int(ci.nstates), "law_dofs": int(ci.ncoords),
            "modes_kept": int(ci.nkept), "modes_discarded": int(ci.ndiscarded),
            "rigid_modes": int(ci.nrigid), "cutoff_hz": ci.cutoff * hz,
            "first_discarded_hz": ci.first_discarded * hz,
            "excitation_hz": ci.excitation * hz, "contact_hz": ci.contact * hz,
            "static_correction": float(ci.static_correction),
            "truncation_estimate": float(ci.estimate)}


def transient(system, duration=None, revolutions=None, speed=None, records=None,
              record_from=None, output_interval=None, rtol=1e-6, method="auto", start="rest",
              laws=None, speed_ramp=None, speed_table=None, step=None, waterfall=None,
              revs_per_block=16, condense=None, estimate=True):
    """Time integration at a constant reference speed (default: the model's), for
    `duration` (s or "12 ms") or `revolutions` of the reference shaft. records: list of
    record specs (NODE.DOF[:disp|vel|angle|speed], ratio:A/B, mesh:NAME[:force|state|
    deflection|stiffness], sfd:BEARING[:fx|fy|ecc]); None: the CLI's defaults. Samples
    from record_from (default half-way) every output_interval (default: 2000 samples,
    at least 32 per revolution). method "auto" (as the CLI: a linear time-invariant model
    by its exact harmonic response and free motion at a step checked against twice the
    step, anything else by bdf; result.method_note says which), "bdf", "adams" or "lti";
    start "rest" or "static".
    laws: geardyn.Law objects (laws of your own in Python) added to the model's.
    Run-up (docs/transient.md, "Run-up through a speed profile"): speed_ramp=(FROM, TO)
    over duration, or speed_table=(times, speeds) (s, rad/s); speed is then only the
    reference the matrices are built at (default the profile's mid speed), records start
    at 0 s, method "auto" takes bdf ("galpha" with step= is usually much cheaper);
    waterfall=RECORD order-tracks that record into result.waterfall (a Waterfall) in
    blocks of revs_per_block turns.
    condense: as `--condense` (docs/transient.md, "Condensed transient"): None (the
    default, as the CLI's: condensed by the cut-off rule where it pays, at least 100 DOFs
    with laws on at most a quarter of them, else the full model), "off" (the full model),
    "auto" (the cut-off rule), "all" (every mode: exact) or a cut-off frequency (rad/s,
    or "8kHz"):
    the structure condensed onto the DOFs its laws act on, its modes up to the cut-off
    and the rest as their static correction; result.condensed describes it (None when
    not condensed). bdf or adams, started at rest, no speed profile; prescribed DOFs are
    clamped in the condensed structure, their motion a forcing through its coupling.
    estimate: bdf and adams repeat the run at rtol / 10 for result.error_estimate (about
    1.5x the run's cost); False skips it, as the CLI's --no-estimate."""
    prof = keep_prof = None
    if speed_ramp is not None or speed_table is not None:
        if speed_ramp is not None and speed_table is not None:
            raise model_error("speed_table", "give speed_ramp or speed_table, not both")
        if revolutions is not None:
            raise model_error("revolutions", "revolutions do not apply to a speed profile",
                              "give duration=")
        prof, keep_prof, t_prof, lo, hi = _profile(system, speed_ramp, speed_table, duration)
        duration = t_prof
        if record_from is None:
            record_from = 0.0
    elif waterfall is not None:
        raise model_error("waterfall", "waterfall= needs speed_ramp= or speed_table=")
    w = system.model.speed if speed is None else quantity(speed, "speed", "speed")
    if prof is not None and speed is None:
        w = 0.5 * (lo + hi)
    t_end, frm, dt = _times(duration, revolutions, w, record_from, output_interval)
    spr = 32
    if prof is not None and output_interval is None and hi > 0:
        if waterfall is not None:  # as the CLI: 2.5 x the highest shaft or mesh order
            h = system.model._handle
            top = max([1.0] + [abs(h.shafts[i].speed_ratio) for i in range(h.nshafts)])
            for k in range(h.nmeshes):
                g = h.meshes[k]
                ratio = h.shafts[h.nodes[g.driver].shaft].speed_ratio
                top = max(top, g.teeth[0] * abs(ratio))
            while spr < 2.5 * top:
                spr *= 2
        dt = min((t_end - frm) / 2000.0, 2 * math.pi / hi / (2.0 * spr if waterfall else 32))
    methods = {"auto": lib.GD_TR_AUTO, "bdf": lib.GD_TR_BDF, "adams": lib.GD_TR_ADAMS,
               "lti": lib.GD_TR_LTI, "galpha": lib.GD_TR_GEN_ALPHA}
    if method not in methods:
        raise model_error("method", "unknown method '%s'" % method,
                          "use auto, bdf, adams, galpha or lti")
    if start not in ("rest", "static"):
        raise model_error("start", "unknown start '%s'" % start, "use rest or static")
    err = new_error()
    tmp = ffi.new("gd_transient_model **")
    check(lib.gd_transient_model_build(system._handle, tmp, err), err)
    tm = ffi.gc(tmp[0], lib.gd_transient_model_free)
    spec, view, keep = with_laws(system, tm, laws)
    recs = _records(system, view, records)
    wi = -1
    if waterfall is not None:
        one = _records(system, view, [waterfall])
        if len(one) != 1:
            raise model_error("waterfall", "give one record (got %d)" % len(one))
        names = [r[3] for r in recs]
        if one[0][3] not in names:
            recs += one
            names.append(one[0][3])
        wi = names.index(one[0][3])
    trp = ffi.new("gd_transient **")
    if condense is None or (isinstance(condense, str) and condense == "off"):
        check(lib.gd_transient_new(system._handle, spec, w, trp, err), err)
        # the CLI's default: condensed where it pays (gd_transient_condense_pays), from
        # rest by bdf or adams at a constant speed; condense="off" keeps the full model
        if condense is None and prof is None and start == "rest" and \
                method in ("auto", "bdf", "adams"):
            why = ffi.new("char[160]")
            if lib.gd_transient_condense_pays(trp[0], why, 160):
                ct = ffi.new("gd_transient **")
                cerr = ffi.new("gd_error *")
                if lib.gd_transient_new_condensed(system._handle, spec, w, -1.0, ct, cerr) == 0:
                    lib.gd_transient_free(trp[0])
                    trp = ct
    else:
        check(lib.gd_transient_new_condensed(system._handle, spec, w, _cutoff(condense),
                                             trp, err), err)
    tr = ffi.gc(trp[0], lib.gd_transient_free)
    opt = ffi.new("gd_transient_options *")
    lib.gd_transient_options_init(opt)
    opt.t_end, opt.record_from, opt.output_interval, opt.rtol = t_end, frm, dt, float(rtol)
    opt.method = methods[method]
    # as the CLI: CVODE's global error from a run at rtol / 10 (estimate=False: --no-estimate)
    opt.error_estimate = 1 if estimate else 0
    if step is not None:
        opt.step = quantity(step, "time", "step")
    if prof is not None:
        opt.profile = prof
    opt.init = lib.GD_TR_INIT_STATIC if start == "static" else lib.GD_TR_INIT_REST
    rr = _record_array(recs)
    out = ffi.new("gd_transient_result **")
    st = lib.gd_transient_run(tr, opt, rr, len(recs), out, err)
    for law in laws or []:
        law.raise_pending()
    check(st, err)
    res = TransientResult(system, ffi.gc(out[0], lib.gd_transient_result_free),
                          [r[3] for r in recs], [r[4] for r in recs],
                          [_mesh_names(system.model)[tm.meshes[i].mesh]
                           for i in range(tm.spec.nmeshes)],
                          [bool(tm.meshes[i].backlash) for i in range(tm.spec.nmeshes)])
    res.speed, res.t_end, res.record_from, res.output_interval = w, t_end, frm, dt
    res.method, res.start = method, start
    res.waterfall = None
    if wi >= 0:
        res.waterfall = _order_track(system, res, prof, wi, revs_per_block, spr)
    del keep_prof
    info = ffi.new("gd_tr_condensed_info *")
    if lib.gd_transient_condensed_info(tr, info):
        # as the CLI: the records are the system's DOFs, less the prescribed ones
        res.free_dofs = system.ndof - tm.spec.nprescribed
        res.condensed = _condensed_dict(info)
    else:
        res.free_dofs = lib.gd_transient_nstates(tr) // 2
        res.condensed = None
    del tr, tm, keep  # the problem borrows the spec: free it first
    return res


STATS_DTYPE = _core.struct_dtype("gd_tr_stats", {k: "f8" for k in (
    "min", "max", "mean", "rms", "peak_to_peak", "std")})
CONTACT_DTYPE = _core.struct_dtype("gd_tr_contact_stats", {
    "contact_losses": "i4", "coast_impacts": "i4", "drive_impacts": "i4",
    "separated_time": "f8", "coast_time": "f8", "drive_time": "f8"})


class TransientResult(_Result):
    """Time integration result (C gd_transient_result). t (samples), values (nrecords x
    nsamples view), names and units of the records, stats (structured: min, max, mean,
    rms, peak_to_peak, std per record), contacts (per nonlinear mesh), q_end, v_end, and
    the solver's counters (steps, rhs_evals, ...)."""

    _figure = "transient"

    def __init__(self, system, owner, names, units, meshes, backlash):
        super().__init__(system, owner)
        r = owner
        self.names, self.units, self.meshes, self.backlash = names, units, meshes, backlash
        self.nout, self.nrecords = int(r.nout), int(r.nrecords)
        self.steps, self.rhs_evals, self.lin_iters = int(r.steps), int(r.rhs_evals), \
            int(r.lin_iters)
        self.prec_setups, self.events, self.reinits = int(r.prec_setups), int(r.events), \
            int(r.reinits)
        self.cpu_seconds = float(r.cpu_seconds)
        # the method that ran and its error control (auto resolved; the CLI's header)
        self.method_note = cstr(r.method_note)
        self.step, self.error_estimate = float(r.step), float(r.error_estimate)

    @property
    def t(self):
        return self._view(self._owner.t, self.nout)

    @property
    def values(self):
        return self._view(self._owner.values, (self.nrecords, self.nout))

    def __getitem__(self, name):
        """The samples of the record called name (e.g. "mesh:m01:force")."""
        return self.values[self.names.index(name)]

    @property
    def stats(self):
        return _core.struct_view(self._owner, self._owner.stats, self.nrecords, STATS_DTYPE)

    @property
    def contacts(self):
        return _core.struct_view(self._owner, self._owner.contacts, int(self._owner.nmeshes),
                                 CONTACT_DTYPE)

    @property
    def q_end(self):
        return self._view(self._owner.q_end, int(self._owner.ndof))

    @property
    def v_end(self):
        return self._view(self._owner.v_end, int(self._owner.ndof))

    def to_pandas(self):
        """The records, one column each, indexed by time (records.csv)."""
        pd = _pandas()
        return pd.DataFrame(self.values.T, index=pd.Index(self.t, name="time_s"),
                            columns=self.names)
