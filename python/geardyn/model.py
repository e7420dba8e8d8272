"""Models and systems: loading (YAML file or text, with --set overrides), the system
(DOF numbering, matrices) and the analyses run on it."""
import collections
import copy
import os

from ._numpy import np

from . import _core
from . import analyses as _analyses
from . import transient as _transient
from . import periodic as _periodic
from . import static as _static
from ._core import ffi, lib, check, new_error, cstr, quantity, model_error
from .builder import build_handle

__all__ = ["Model", "System", "Matrices", "load", "loads"]


def _format_value(value):
    """A Python value as the VALUE of an override PATH=VALUE (YAML flow syntax); floats
    are written with repr so they reach the library bit for bit."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, str):
        return value
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_format_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join("%s: %s" % (k, _format_value(v)) for k, v in value.items()) + "}"
    raise TypeError("cannot write %r as a model value" % (value,))


def _set_strings(sets):
    """sets: None, a dict {path: value}, or a list of "PATH=VALUE" strings / (path, value)
    pairs."""
    if not sets:
        return []
    items = sets.items() if isinstance(sets, dict) else sets
    out = []
    for item in items:
        if isinstance(item, str):
            out.append(item)
        else:
            path, value = item
            out.append("%s=%s" % (path, _format_value(value)))
    return out


def _load_options(sets):
    """gd_load_options over the strings; returns it with the cdata that must stay alive."""
    keep = [ffi.new("char[]", s.encode()) for s in sets]
    arr = ffi.new("const char *[]", keep) if keep else ffi.NULL
    opt = ffi.new("gd_load_options *")
    lib.gd_load_options_init(opt)
    opt.nset = len(keep)
    opt.set = arr
    return opt, (keep, arr)


def _coupling_level(coupling):
    if coupling is None:
        return None
    if coupling not in _core.COUPLING_NAMES:
        raise model_error("coupling", "unknown coupling level '%s'" % coupling,
                          "use torsional, lateral-torsional or full")
    return _core.COUPLING_NAMES.index(coupling)


class Model:
    """A validated model (C gd_model). Make one with load(), loads() or build().

    The model's analyses run on its system (built once, on first use): modal(),
    campbell(), frf(), unbalance(), transient(), periodic() and matrices(). set() changes
    a value the way `--set PATH=VALUE` does and rebuilds the model."""

    def __init__(self, handle, source):
        self._handle = handle  # ffi.gc'd gd_model *
        self._source = source  # ("file", path) | ("text", text, name) | ("dict", spec, name)
        self._sets = []
        self._coupling = None
        self._system = None

    # ---- construction ----
    @classmethod
    def _load(cls, source, sets=(), coupling=None):
        level = _coupling_level(coupling)
        strings = _set_strings(sets)
        if source[0] == "dict":
            handle = build_handle(source[1], source[2])
        else:
            opt, _keep = _load_options(strings)
            out = ffi.new("gd_model **")
            err = new_error()
            if source[0] == "file":
                st = lib.gd_model_load_opts(os.fsencode(source[1]), opt, out, err)
            else:
                st = lib.gd_model_load_string_opts(source[1].encode(), source[2].encode(), opt,
                                                   out, err)
            check(st, err)
            handle = ffi.gc(out[0], lib.gd_model_free)
        if level is not None:
            lib.gd_model_set_coupling(handle, level)
        m = cls(handle, source)
        m._sets = strings
        m._coupling = coupling
        return m

    def set(self, path, value):
        """Changes one value as `--set PATH=VALUE` does (docs/model-format.md,
        "Overrides"), e.g. set("meshes.mesh.stiffness", 3e8) or
        set("bearings.*.kxx", "2e8 N/m"), and reloads the model; a wrong path or value
        raises ModelError. Systems and results made before keep the old model.
        Returns the model."""
        if self._source[0] == "dict":
            spec = copy.deepcopy(self._source[1])
            _set_in_dict(spec, path, value)
            new = Model._load(("dict", spec, self._source[2]), coupling=self._coupling)
        else:
            new = Model._load(self._source, self._sets + _set_strings([(path, value)]),
                              self._coupling)
        self._handle, self._source, self._sets = new._handle, new._source, new._sets
        self._system = None
        return self

    def copy(self):
        """An independent model from the same source and overrides."""
        return Model._load(self._source, self._sets, self._coupling)

    # ---- contents ----
    @property
    def file(self):
        return cstr(self._handle.file)

    @property
    def speed(self):
        """The model's reference speed, rad/s."""
        return float(self._handle.speed)

    @property
    def nodes(self):
        return [cstr(self._handle.nodes[i].name) for i in range(self._handle.nnodes)]

    @property
    def shafts(self):
        return [cstr(self._handle.shafts[i].name) for i in range(self._handle.nshafts)]

    @property
    def meshes(self):
        return [cstr(self._handle.meshes[i].name) for i in range(self._handle.nmeshes)]

    @property
    def bearings(self):
        return [cstr(self._handle.bearings[i].name) for i in range(self._handle.nbearings)]

    @property
    def planetary_sets(self):
        """The planetary sets' names (docs/planetary.md)."""
        return [cstr(self._handle.planetary[i].name) for i in range(self._handle.nplanetary)]

    def planetary(self, name):
        """Planetary set `name` (or its index) as `geardyn check` describes it: held member,
        planet nodes and angles (rad), teeth, radii, pressure angles, mesh stiffnesses, and
        its kinematics (gd_planetary_kinematics_of): the speeds of sun, ring and carrier
        and of the planets per unit input speed (the sun's, or the ring's when the sun is
        held; NaN for a differential), the mesh order Z_s |w_s - w_c|, and the assembly
        numbers (Z_s + Z_r) psi_n / 2 pi (whole when the set assembles)."""
        h = self._handle
        names = self.planetary_sets
        if isinstance(name, str):
            if name not in names:
                raise model_error("planetary", "unknown planetary set '%s'" % name,
                                  "sets: " + (", ".join(names) or "none"))
            k = names.index(name)
        else:
            k = _core.whole(name, "planetary", 0, max(len(names) - 1, 0))
            if not names:
                raise model_error("planetary", "the model has no planetary set")
        g = h.planetary[k]
        kin = ffi.new("gd_planetary_kinematics *")
        lib.gd_planetary_kinematics_of(ffi.addressof(h.planetary[k]), kin)
        members = [cstr(lib.gd_planetary_member_names[j]) for j in range(3)]
        n = int(g.nplanets)
        return {
            "name": names[k], "held": "none" if g.held < 0 else members[g.held],
            "members": {members[j]: self.nodes[g.member[j].node] for j in range(3)},
            "planets": [self.nodes[g.first_planet + i] for i in range(n)],
            "angles": np.array([g.planet_angle[i] for i in range(n)]),
            "equally_spaced": bool(g.equally_spaced),
            "teeth": {"sun": g.teeth[0], "ring": g.teeth[1], "planet": g.teeth[2]},
            "base_radius": {"sun": g.base_radius[0], "ring": g.base_radius[1],
                            "planet": g.base_radius[2]},
            "carrier_radius": float(g.carrier_radius),
            "pressure_angle": {"sun": g.pressure_angle[0], "ring": g.pressure_angle[1]},
            "mesh_stiffness": {"sun": g.mesh_stiffness[0], "ring": g.mesh_stiffness[1]},
            "kinematics": {
                "input": None if kin.input < 0 else members[kin.input],
                "speed": {members[j]: kin.speed[j] for j in range(3)},
                "planet_speed": float(kin.planet_speed), "teeth_ratio": float(kin.teeth_ratio),
                "mesh_order": float(kin.mesh_order), "has_teeth": bool(kin.has_teeth),
                "assembly": np.array([kin.assembly[i] for i in range(n)]),
                "assembles": None if kin.assembles < 0 else bool(kin.assembles)},
        }

    @property
    def system(self):
        """The system (DOF numbering and matrices), built on first use."""
        if self._system is None:
            self._system = System(self)
        return self._system

    def __repr__(self):
        extra = ", %d planetary sets" % self._handle.nplanetary if self._handle.nplanetary else ""
        return "<geardyn.Model %s: %d shafts, %d nodes, %d meshes%s>" % (
            self.file or "?", self._handle.nshafts, self._handle.nnodes, self._handle.nmeshes,
            extra)

    # ---- analyses (on the system) ----
    def matrices(self, speed=0.0):
        return self.system.matrices(speed)

    def modal(self, **kw):
        return self.system.modal(**kw)

    def campbell(self, speeds, **kw):
        return self.system.campbell(speeds, **kw)

    def static(self, **kw):
        return self.system.static(**kw)

    def frf(self, input, outputs, freqs, **kw):
        return self.system.frf(input, outputs, freqs, **kw)

    def unbalance(self, speeds, **kw):
        return self.system.unbalance(speeds, **kw)

    def transient(self, **kw):
        return self.system.transient(**kw)

    def periodic(self, speeds=None, **kw):
        return self.system.periodic(speeds, **kw)


def _set_in_dict(spec, path, value):
    """`--set` for a model built from a dict: PATH segments are map keys, list indices,
    list items' names, or '*' (every item)."""
    parts = path.split(".")
    if not path or any(p == "" for p in parts):
        raise model_error(path, "empty segment in the path", "write e.g. meshes.mesh.stiffness")

    def walk(node, i, where):
        key = parts[i]
        last = i == len(parts) - 1
        if isinstance(node, dict):
            targets = list(node) if key == "*" else [key]
            if key != "*" and key not in node and not last:
                raise model_error(where + key, "no key '%s'" % key,
                                  "keys here: " + ", ".join(map(str, node)))
        elif isinstance(node, list):
            if key == "*":
                targets = list(range(len(node)))
            elif key.isdigit() and int(key) < len(node):
                targets = [int(key)]
            else:
                targets = [k for k, item in enumerate(node)
                           if isinstance(item, dict) and item.get("name") == key]
            if not targets:
                raise model_error(where + key, "nothing matches '%s'" % key,
                                  "names here: " + ", ".join(
                                      str(item.get("name", k)) for k, item in enumerate(node)
                                      if isinstance(item, dict)))
        else:
            raise model_error(where + key, "'%s' is a value, not a map or list" % where[:-1])
        for t in targets:
            if last:
                node[t] = value
            else:
                walk(node[t], i + 1, "%s%s." % (where, t))

    walk(spec, 0, "")


def load(path, sets=None, coupling=None):
    """Loads a model file. sets: overrides applied to the file's values before
    validation, as `--set` does: {"meshes.mesh.stiffness": 3e8} or
    ["meshes.mesh.stiffness=3e8 N/m"]. coupling: None (the file's), "torsional",
    "lateral-torsional" or "full" (as --coupling). Raises ModelError (file, line,
    field, hint)."""
    return Model._load(("file", os.fspath(path)), sets, coupling)


def loads(text, name="<string>", sets=None, coupling=None):
    """Loads a model from YAML text; name stands for the file in error messages."""
    if not isinstance(text, str):  # loads(None): AttributeError before
        raise model_error("text", "expected the model's YAML text as a str, got %r"
                          % type(text).__name__, "read the file first, or use load(path)")
    return Model._load(("text", text, name), sets, coupling)


def build(spec, name="<dict>", coupling=None):
    """A Model from a dict laid out as a model file (see the module's doc), built
    through the C builder API. Raises ModelError naming the field."""
    return Model._load(("dict", spec, name), coupling=coupling)


Matrices = collections.namedtuple("Matrices", "M K C G dofs")
Matrices.__doc__ = """M, K (+ speed-table bearings at the speed), C (without gyroscopics)
and G (per unit reference speed: the damping at speed W is C + W G), as
scipy.sparse.csc_matrix over the active DOFs; dofs are their "node.dof" labels."""


class System:
    """The model turned into numbers (C gd_system): DOF numbering and sparse matrices.
    Read-only: analyses on one system may run in several threads at once."""

    def __init__(self, model):
        self.model = model
        self._model_handle = model._handle  # the system borrows it: keep it alive
        out = ffi.new("gd_system **")
        err = new_error()
        check(lib.gd_system_build(model._handle, out, err), err)
        self._handle = ffi.gc(out[0], lib.gd_system_free)
        h = self._handle
        self.ndof = int(h.ndof)
        self.dof_node = np.array([h.dof_node[i] for i in range(self.ndof)], dtype=np.int32)
        self.dof_type = np.array([h.dof_type[i] for i in range(self.ndof)], dtype=np.int32)
        node_names = model.nodes
        self.dofs = ["%s.%s" % (node_names[n], _core.DOF_NAMES[d])
                     for n, d in zip(self.dof_node, self.dof_type)]
        idx, name = ffi.new("int *"), ffi.new("const char **")
        self.components, self.component_kinds = [], []
        for c in range(h.ncomponents):
            kind = lib.gd_system_component(h, c, idx, name)
            self.components.append(cstr(name[0]))
            # a linearised law (after the elements) has no element kind
            self.component_kinds.append(cstr(kind.name) if kind != ffi.NULL else "law")

    def dof(self, node, dof):
        """Active DOF index of (node name, "x".."rz"), or -1."""
        n = lib.gd_model_find_node(self._model_handle, node.encode())
        if n < 0 or dof not in _core.DOF_NAMES:
            return -1
        return int(lib.gd_system_dof(self._handle, n, _core.DOF_NAMES.index(dof)))

    def matrices(self, speed=0.0):
        """M, K, C, G at reference speed `speed` (rad/s or "3000 rpm") as scipy.sparse
        csc matrices (gd_system_matrices; the same numbers as `geardyn matrices`). The
        index and value arrays are the C library's, not copies; they are freed with the
        matrices."""
        import scipy.sparse as sp
        w = quantity(speed, "speed", "speed")
        mats = [ffi.gc(ffi.new("gd_csc *"), lib.gd_csc_free) for _ in range(4)]
        err = new_error()
        check(lib.gd_system_matrices(self._handle, w, *mats, err), err)
        out = []
        for a in mats:
            n = int(a.n)
            nnz = int(a.colptr[n]) if a.colptr != ffi.NULL else 0
            colptr = _core.view(a, a.colptr, n + 1, np.int32, writable=True)
            rowind = _core.view(a, a.rowind, nnz, np.int32, writable=True)
            values = _core.view(a, a.values, nnz, np.float64, writable=True)
            out.append(sp.csc_matrix((values, rowind, colptr), shape=(n, n), copy=False))
        return Matrices(*out, dofs=list(self.dofs))

    # the analyses (analyses.py, transient.py), each documented there
    def modal(self, speed=None, modes=None, kind="auto", left=False, tol=None,
              operating_point="static", torque=None):
        return _analyses.modal(self, speed, modes, kind, left, tol, operating_point, torque)

    def campbell(self, speeds, **kw):
        return _analyses.campbell(self, speeds, **kw)

    def static(self, **kw):
        return _static.static(self, **kw)

    def frf(self, input, outputs, freqs, **kw):
        return _analyses.frf(self, input, outputs, freqs, **kw)

    def unbalance(self, speeds, **kw):
        return _analyses.unbalance(self, speeds, **kw)

    def transient(self, **kw):
        return _transient.transient(self, **kw)

    def periodic(self, speeds=None, **kw):
        return _periodic.periodic(self, speeds, **kw)

    modal.__doc__ = _analyses.modal.__doc__
    campbell.__doc__ = _analyses.campbell.__doc__
    static.__doc__ = _static.static.__doc__
    frf.__doc__ = _analyses.frf.__doc__
    unbalance.__doc__ = _analyses.unbalance.__doc__
    transient.__doc__ = _transient.transient.__doc__
    periodic.__doc__ = _periodic.periodic.__doc__
