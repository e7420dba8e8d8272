"""Laws of your own, written in Python (docs/laws.md): the slow path, for prototyping a
law before it becomes a C file under src/laws/.

    import numpy as np, geardyn

    def cubic(t, q, v):                  # local q, q' of the law's DOFs
        f = np.array([-0.1 * q[0] ** 3])         # generalised force on them
        jq = np.array([-0.3 * q[0] ** 2])        # df/dq = sum_k jq[k] u_k w_k^T
        return f, jq, np.zeros(1)               # jv: df/dq' likewise

    law = geardyn.Law("cubic", ["m.x"], cubic, terms=[([1.0], [1.0])],
                      records={"force": "N"}, record=lambda k, t, q, v: 0.1 * q[0] ** 3)
    m = geardyn.load("duffing.yaml")
    m.transient(duration=300, laws=[law], records="law:cubic")
    m.periodic("1:1:1", harmonics=15, laws=[law])

The C library calls back into Python for every evaluation (tens of thousands per
transient, one per time sample and Newton step in harmonic balance): expect it to run
100-1000 times slower than a C law. An exception raised by a callback, Ctrl-C's
KeyboardInterrupt included, stops the analysis: the callback keeps the exception and
from then on returns NaN for the force, its Jacobian and its records without calling
Python again (never a silent zero), the C side stops at the first non-finite force
(the integrators' error return, the Newton solvers' failed step), and the exception is
raised again when the analysis returns.
"""
from ._numpy import np

from ._core import ffi, lib, check, new_error, model_error, DOF_NAMES

__all__ = ["Law"]


class Law:
    """A user law on DOFs given as "NODE.DOF" strings (None: ground, a zero DOF).
    force(t, q, v) returns (f, jq, jv): the generalised force on the local DOFs and the
    coefficients of the Jacobian terms; terms is a list of (u, w) local vectors, one per
    term (df/dq = sum_k jq[k] u_k w_k^T, df/dq' = sum_k jv[k] u_k w_k^T); records maps
    record names to units, record(k, t, q, v) returns record k's value."""

    def __init__(self, name, dofs, force, terms, records=None, record=None, smooth=True):
        if not name or len(name) >= 48:
            raise model_error("law", "give a name of 1 to 47 characters")
        if not 1 <= len(dofs) <= 12:
            raise model_error("law", "a law acts on 1 to 12 DOFs, not %d" % len(dofs))
        if not 0 <= len(terms) <= 25:
            raise model_error("law", "a law has at most 25 Jacobian terms, not %d" % len(terms))
        for u, w in terms:
            if len(u) != len(dofs) or len(w) != len(dofs):
                raise model_error("law", "every term's u and w have one entry per DOF (%d)"
                                  % len(dofs))
        if records and record is None:
            raise model_error("law", "records need a record(k, t, q, v) function")
        self.name, self.dofs, self.force = name, list(dofs), force
        self.terms = [(np.asarray(u, float), np.asarray(w, float)) for u, w in terms]
        self.records = dict(records or {})
        self.record = record
        self.error = None
        keep = self._keep = []  # C strings and arrays the type points to

        def cs(text):
            c = ffi.new("char[]", text.encode())
            keep.append(c)
            return c
        t = self._type = ffi.new("gd_law_type *")
        t.name = cs(name)
        t.summary = cs("a law written in Python")
        t.flags = lib.GD_LAW_SMOOTH if smooth else 0
        # the local DOFs are the user's list: one "direction" entry each (the problem
        # reads only their count; the DOFs themselves are given per instance)
        dirs = ffi.new("int[]", [0] * len(self.dofs))
        keep.append(dirs)
        t.dirs, t.ndirs, t.two_nodes = dirs, len(self.dofs), 0
        t.nterms = len(self.terms)
        t.term = lib.gd_py_law_term
        t.force = lib.gd_py_law_force
        if self.records:
            recs = ffi.new("gd_law_record[]", len(self.records))
            for k, (n, u) in enumerate(self.records.items()):
                recs[k].name, recs[k].unit = cs(n), cs(u)
            keep.append(recs)
            t.records, t.nrecords, t.record = recs, len(self.records), lib.gd_py_law_record
        self._handle = ffi.new_handle(self)
        err = new_error()
        check(lib.gd_law_type_validate(t, err), err)

    def instance(self, system):
        """The C instance (gd_law) on system's DOFs; owned by this Law."""
        law = ffi.new("gd_law *")
        lib.gd_law_init(law, self._type, self.name.encode())
        law.ndofs = len(self.dofs)
        for j, spec in enumerate(self.dofs):
            if spec is None:
                law.dof[j] = -1
                continue
            node, dot, d = spec.rpartition(".")
            if not dot or node not in system.model.nodes or d not in DOF_NAMES:
                raise model_error("law", "law '%s': '%s' is not NODE.DOF (nodes: %s)"
                                  % (self.name, spec, ", ".join(system.model.nodes)))
            i = system.dof(node, d)
            if i < 0:
                raise model_error("law", "law '%s': %s is not an active DOF" % (self.name, spec))
            law.dof[j] = i
        law.user = self._handle
        self._keep.append(law)
        return law

    def raise_pending(self):
        """Raises the first exception a callback met (then forgets it)."""
        e, self.error = self.error, None
        if e is not None:
            raise e


def _local(x, n):
    return (np.frombuffer(ffi.buffer(x.q, 8 * n), dtype=float),
            np.frombuffer(ffi.buffer(x.v, 8 * n), dtype=float))


@ffi.def_extern()
def gd_py_law_term(law, k, u, w):
    obj = ffi.from_handle(law.user)
    uk, wk = obj.terms[k]
    for j in range(law.ndofs):
        u[j], w[j] = uk[j], wk[j]


def _poison(obj, n, f, jq, jv):
    """NaN force and Jacobian after an exception: the C side stops at a non-finite force
    (issue 38 M1: a zero force let the analysis run on with a wrong answer)."""
    nan = float("nan")
    for j in range(n):
        f[j] = nan
    for k in range(len(obj.terms)):
        if jq != ffi.NULL:
            jq[k] = nan
        if jv != ffi.NULL:
            jv[k] = nan


@ffi.def_extern()
def gd_py_law_force(law, x, f, jq, jv):
    obj = ffi.from_handle(law.user)
    n = law.ndofs
    if obj.error is not None:  # already failed: no more Python (a looping law stays out)
        _poison(obj, n, f, jq, jv)
        return
    try:
        q, v = _local(x, n)
        ff, a, b = obj.force(x.t, q, v)
        ff = [float(ff[j]) for j in range(n)]
        a = [float(a[k]) for k in range(len(obj.terms))] if jq != ffi.NULL else None
        b = [float(b[k]) for k in range(len(obj.terms))] if jv != ffi.NULL else None
        for j in range(n):
            f[j] += ff[j]
        for k in range(len(obj.terms)):
            if a is not None:
                jq[k] = a[k]
            if b is not None:
                jv[k] = b[k]
    except BaseException as e:  # noqa: BLE001 - Ctrl-C too: handed back after the C call
        obj.error = e
        _poison(obj, n, f, jq, jv)


@ffi.def_extern()
def gd_py_law_record(law, k, x):
    obj = ffi.from_handle(law.user)
    if obj.error is not None:
        return float("nan")
    try:
        q, v = _local(x, law.ndofs)
        return float(obj.record(k, x.t, q, v))
    except BaseException as e:  # noqa: BLE001
        obj.error = e
        return float("nan")


def with_laws(system, tm, laws):
    """The model's transient spec with the user laws appended: (spec cdata, a view with
    spec, meshes and sfd_bearing for the record parser, the arrays to keep alive)."""
    spec = ffi.new("gd_transient_spec *")
    spec[0] = tm.spec
    if not laws:
        return spec, tm, []
    n0 = tm.spec.nlaws
    seen = {ffi.string(tm.spec.laws[i].name).decode() for i in range(n0)}
    for law in laws:
        if isinstance(law, Law) and law.name in seen:  # issue 38 L2: two columns of one name
            raise model_error("laws", "duplicate law name '%s'" % law.name,
                              "give every law its own name")
        if isinstance(law, Law):
            seen.add(law.name)
    arr = ffi.new("gd_law[]", n0 + len(laws))
    for i in range(n0):
        arr[i] = tm.spec.laws[i]
    for i, law in enumerate(laws):
        if not isinstance(law, Law):
            raise model_error("laws", "laws= takes geardyn.Law objects")
        arr[n0 + i] = law.instance(system)[0]
    spec.laws, spec.nlaws = arr, n0 + len(laws)

    class _View:
        pass
    view = _View()
    view.spec, view.meshes, view.sfd_bearing = spec[0], tm.meshes, tm.sfd_bearing
    return spec, view, [arr]
