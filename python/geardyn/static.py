"""The static analysis (docs/static.md): equilibrium K q = f under the model's mean
loads, an input torque and gravity; shaft deflection and slope, bearing reactions, mesh
forces and misalignment. One C call (gd_static_run, the GIL released); the arrays are
numpy views of the C result (no copy)."""
from ._numpy import np

from . import _core
from ._core import ffi, lib, check, new_error, cstr, quantity, model_error

__all__ = ["static", "StaticResult"]

_MESH_FIELDS = ("force", "tangential", "radial", "axial", "tilt_in_plane",
                "tilt_out_of_plane", "face_width", "f_sh", "f_beta_x")
_MESH_DTYPE = _core.struct_dtype("gd_static_mesh", dict(
    [(k, "f8") for k in _MESH_FIELDS] + [("on_driver", ("f8", (6,))),
                                         ("on_driven", ("f8", (6,)))]))


def _node(system, name, field):
    n = lib.gd_model_find_node(system._model_handle, name.encode())
    if n < 0:
        raise model_error(field, "unknown node '%s'" % name)
    return n


def static(system, torque=0.0, input=None, hold=None, speed=None, gravity=True, loads=True):
    """Static equilibrium. torque: input torque (N m or "20 N*m") about the input node's
    shaft in its sense of rotation, at node `input` (default: the reference shaft's
    first node). hold: node whose torsion holds its free gear train (default: the output
    with a torque, the input without). speed: for bearing speed tables (default: the
    model's). gravity, loads: include the model's gravity and mean excitation loads."""
    opt = ffi.new("gd_static_options *")
    out = ffi.new("gd_static_result **")
    err = new_error()
    lib.gd_static_options_init(opt)
    opt.input_torque = quantity(torque, "torque", "torque")
    if input is not None:
        opt.input_node = _node(system, input, "input")
    if hold is not None:
        opt.hold_node = _node(system, hold, "hold")
    if speed is not None:
        opt.speed = quantity(speed, "speed", "speed")
    opt.gravity = 1 if gravity else 0
    opt.loads = 1 if loads else 0
    if lib.gd_static_run(system._handle, opt, out, err) != lib.GD_OK:
        check(err.status, err)
    return StaticResult(system, ffi.gc(out[0], lib.gd_static_free))


class StaticResult:
    """Static result (C gd_static_result). q, f: the active DOFs' displacement and
    applied load (system.dofs); u: nodes x 6 (x, y, z, rx, ry, rz; model.nodes);
    bearing_force, bearing_moment: nbearings x 3, on the shaft; springs: per spring;
    mesh arrays (one per mesh): force, tangential, radial, axial, tilt_in_plane,
    tilt_out_of_plane, face_width, f_sh, f_beta_x, on_driver and on_driven (x 6);
    holds: list of (node, dof, kind, reaction); law_forces: the laws' forces on the
    active DOFs (K q = f + law_forces); laws: {law name: {"type": ..., record: value}}
    with each supporting law's records (a journal bearing's fx, fy, ecc) at the state.
    planetary: one dict per planetary set (docs/planetary.md, "Static load sharing"):
    name, load_sharing_factor (K_gamma), sun_mesh_force, ring_mesh_force, bearing_force
    (N, arrays of one value per planet), the keys of `static --json`'s planetary_sets."""

    def __init__(self, system, owner):
        self.system = system
        self._owner = owner
        r = owner
        self.speed = r.speed
        self.q = _core.view(r, r.q, r.ndof)
        self.f = _core.view(r, r.f, r.ndof)
        self.u = _core.view(r, r.u, (r.nnodes, 6))
        reac = _core.view(r, ffi.cast("double *", r.bearings), (r.nbearings, 6))
        self.bearing_force, self.bearing_moment = reac[:, :3], reac[:, 3:]
        self.springs = _core.view(r, r.springs, r.nsprings)
        self._meshes = _core.struct_view(r, r.meshes, r.nmeshes, _MESH_DTYPE)
        m = system._model_handle
        self.holds = [(cstr(m.nodes[r.holds[h].node].name),
                       _core.DOF_NAMES[r.holds[h].dof],
                       "prescribed" if r.holds[h].prescribed else "torque",
                       r.holds[h].reaction) for h in range(r.nholds)]
        self.law_forces = _core.view(r, r.law_forces, r.ndof)
        self.laws = {}
        for k in range(r.nlaws):
            law = r.laws[k]
            entry = {"type": cstr(law.type)}
            for j in range(law.nrecords):
                entry[cstr(law.record_names[j])] = law.records[j]
            self.laws[cstr(law.name)] = entry

    @property
    def planetary(self):
        out = []
        m = self.system._model_handle
        for k in range(m.nplanetary):
            pl = ffi.new("gd_static_planetary_loads *")
            err = new_error()
            check(lib.gd_static_planetary(self.system._handle, self._owner, k, pl, err), err)
            n = int(pl.nplanets)
            out.append({"name": cstr(m.planetary[k].name),
                        "load_sharing_factor": float(pl.load_sharing),
                        "sun_mesh_force": np.array([pl.sun_force[i] for i in range(n)]),
                        "ring_mesh_force": np.array([pl.ring_force[i] for i in range(n)]),
                        "bearing_force": np.array([pl.bearing_force[i] for i in range(n)])})
        return out

    def __getattr__(self, name):
        if name in _MESH_DTYPE.names:
            return self._meshes[name]
        raise AttributeError(name)

    def to_pandas(self):
        """Nodes: one row per node (shaft, node, position and the six displacements)."""
        import pandas
        m = self.system._model_handle
        rows = []
        for s in range(m.nshafts):
            sh = m.shafts[s]
            for i in range(sh.nnodes):
                node = sh.first_node + i
                rows.append([cstr(sh.name), cstr(m.nodes[node].name),
                             m.nodes[node].position] + list(self.u[node]))
        return pandas.DataFrame(rows, columns=["shaft", "node", "position_m"] +
                                list(_core.DOF_NAMES))
