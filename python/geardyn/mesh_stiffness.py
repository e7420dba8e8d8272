"""Gear mesh stiffness from geometry (docs/mesh-stiffness.md): gd_gear_pair_load and
gd_tvms_compute, as `geardyn mesh-stiffness`; the loaded tooth contact analysis
(gd_ltca_compute, `--load`) and the Harris map (gd_ltca_map_compute, `--load-range`)."""
import os

from ._numpy import np

from ._core import ffi, lib, check, new_error, cstr, quantity, model_error
from .analyses import _Result, _pandas
from .model import _load_options, _set_strings

__all__ = ["mesh_stiffness", "MeshStiffnessResult", "contact_analysis", "ContactAnalysisResult",
           "harris_map", "HarrisMapResult"]


def mesh_stiffness(path, mesh=None, sets=None, method=None, points=None, cycles=None,
                   slices=None, helix_angle=None):
    """Contact ratios and time-varying mesh stiffness of the gear pair of a mesh entry
    (`mesh` by name; None: the first with a geometry) of a model or gear-pair file.
    method: energy, iso6336, single-pair-law or square (default: the file's)."""
    opt, _keep = _load_options(_set_strings(sets))
    g = ffi.new("gd_gear_pair_geometry *")
    tv = ffi.new("gd_tvms_options *")
    name = ffi.new("char[]", 160)
    err = new_error()
    check(lib.gd_gear_pair_load(os.fsencode(path), mesh.encode() if mesh else ffi.NULL, opt,
                                g, tv, name, 160, err), err)
    if method is not None:
        mp = ffi.new("gd_tvms_method *")
        check(lib.gd_tvms_method_parse(method.encode(), mp, err), err)
        tv.method = mp[0]
    if points is not None:
        tv.points = int(points)
    if cycles is not None:
        tv.cycles = int(cycles)
    if slices is not None:
        tv.slices = int(slices)
    if helix_angle is not None:
        g.helix_angle = quantity(helix_angle, "angle", "helix_angle")
    out = ffi.new("gd_tvms_result **")
    check(lib.gd_tvms_compute(g, tv, out, err), err)
    return MeshStiffnessResult(ffi.gc(out[0], lib.gd_tvms_free), os.fspath(path), cstr(name),
                               (int(g.gear[0].teeth), int(g.gear[1].teeth)))


class MeshStiffnessResult(_Result):
    """TVMS (C gd_tvms_result): angle_rad, stiffness (N/m along the contact normal),
    pairs_in_contact, load_share (samples x max_pairs) as views; mean, max, min,
    peak_to_peak; contact ratios and the derived geometry; harmonics; ISO 6336 values."""

    _figure = "mesh_stiffness"

    _SCALARS = ("mean", "max", "min", "peak_to_peak", "transverse_factor",
                "iso_single_stiffness", "iso_mesh_stiffness_alpha", "iso_mesh_stiffness_beta",
                "body_stiffness", "mesh_period_rad")
    _GEOM = ("contact_ratio_transverse", "contact_ratio_face", "contact_ratio_total",
             "base_pitch_transverse", "base_pitch_normal", "center_distance",
             "transverse_pressure_angle", "working_pressure_angle", "base_helix_angle")

    def __init__(self, owner, file, mesh, teeth):
        super().__init__(None, owner)
        r = owner
        self.file, self.mesh, self.teeth = file, mesh, teeth
        self.method = cstr(lib.gd_tvms_method_name(r.method))
        self.slices, self.n, self.max_pairs = int(r.slices), int(r.n), int(r.max_pairs)
        for k in self._SCALARS:
            setattr(self, k, float(getattr(r, k)))
        for k in self._GEOM:
            setattr(self, k, float(getattr(r.geom, k)))
        for k in ("pitch_radius", "base_radius", "tip_radius", "root_radius", "bore_radius"):
            setattr(self, k, (float(getattr(r.geom, k)[0]), float(getattr(r.geom, k)[1])))
        self.harmonics = [{"order": h + 1, "amplitude": float(r.harmonic_amplitude[h]),
                           "phase_rad": float(r.harmonic_phase[h])} for h in range(r.harmonics)]

    @property
    def angle_rad(self):
        return self._view(self._owner.angle_rad, self.n)

    @property
    def stiffness(self):
        return self._view(self._owner.stiffness, self.n)

    @property
    def pairs_in_contact(self):
        return self._view(self._owner.pairs_in_contact, self.n, np.int32)

    @property
    def load_share(self):
        return self._view(self._owner.load_share, (self.n, self.max_pairs))

    def to_pandas(self):
        """One row per sample, as mesh_stiffness.csv."""
        pd = _pandas()
        df = pd.DataFrame({"angle_rad": self.angle_rad, "stiffness_N_per_m": self.stiffness,
                           "pairs_in_contact": self.pairs_in_contact})
        for j in range(self.max_pairs):
            df["load_share_%d" % j] = self.load_share[:, j]
        return df


def _gear_pair(path, mesh, sets, method, points, cycles, slices, misalignment):
    """The gear pair and stiffness options of a mesh entry, with the given overrides."""
    opt, _keep = _load_options(_set_strings(sets))
    g = ffi.new("gd_gear_pair_geometry *")
    tv = ffi.new("gd_tvms_options *")
    name = ffi.new("char[]", 160)
    err = new_error()
    check(lib.gd_gear_pair_load(os.fsencode(path), mesh.encode() if mesh else ffi.NULL, opt,
                                g, tv, name, 160, err), err)
    if method is not None:
        mp = ffi.new("gd_tvms_method *")
        check(lib.gd_tvms_method_parse(method.encode(), mp, err), err)
        tv.method = mp[0]
    for key, v in (("points", points), ("cycles", cycles), ("slices", slices)):
        if v is not None:
            setattr(tv, key, int(v))
    if misalignment is not None:
        tv.misalignment = quantity(misalignment, "length", "misalignment")
    return g, tv, cstr(name), err


def contact_analysis(path, load=None, mesh=None, sets=None, misalignment=None, method=None,
                     points=None, cycles=None, slices=None):
    """Loaded tooth contact analysis of the gear pair of a mesh entry, as `geardyn
    mesh-stiffness PATH --load LOAD [--misalignment M] --json`: load is the driver torque
    (N m, or a string such as "100 N m"; None: the mesh's `stiffness: {from:
    contact_analysis, load: ...}`), misalignment the separation at the back face minus
    the front face (m or "10 um"; None: the file's). Micro-geometry comes from the file
    (sets: --set overrides, e.g. {"meshes.mesh.geometry.driver.modifications.tip_relief.
    amount": "5 um"})."""
    g, tv, name, err = _gear_pair(path, mesh, sets, method, points, cycles, slices,
                                  misalignment)
    if load is not None:
        tv.load_torque = quantity(load, "torque", "load")
    out = ffi.new("gd_ltca_result **")
    check(lib.gd_ltca_compute(g, tv, out, err), err)
    return ContactAnalysisResult(ffi.gc(out[0], lib.gd_ltca_free), os.fspath(path), name)


def harris_map(path, loads, mesh=None, sets=None, misalignment=None, method=None, points=None,
               cycles=None, slices=None):
    """Harris map: the contact analysis at each driver torque of loads (N m or strings
    with a unit, each > 0), as `geardyn mesh-stiffness PATH --load-range ... --json`."""
    g, tv, name, err = _gear_pair(path, mesh, sets, method, points, cycles, slices,
                                  misalignment)
    torques = [quantity(v, "torque", "loads") for v in loads]
    arr = ffi.new("double[]", torques)
    out = ffi.new("gd_ltca_map **")
    check(lib.gd_ltca_map_compute(g, tv, arr, len(torques), out, err), err)
    return HarrisMapResult(ffi.gc(out[0], lib.gd_ltca_map_free), os.fspath(path), name)


class ContactAnalysisResult(_Result):
    """Loaded tooth contact analysis (C gd_ltca_result). Per position (n samples, views):
    angle_rad, ste (loaded transmission error along the contact normal, m; the driver lags
    by ste / (r_b1 cos beta_b) rad), ste_unloaded (m), stiffness (dF/d delta at the load,
    N/m), pairs_in_contact, pair_load (n x max_pairs, N), line_load (n x slices, N/m),
    face_load_factor (n), flags (GD_LTCA_* bits); line_load_mean (slices). Scalars over
    the first cycle: ste_mean, ste_peak_to_peak, stiffness_mean/min/max,
    face_load_factor_cycle (K_Hbeta), flagged; torque, force, misalignment."""

    _figure = "contact_analysis"

    _SCALARS = ("torque", "force", "misalignment", "mesh_period_rad", "slice_width",
                "body_stiffness", "face_load_factor_cycle", "ste_mean", "ste_peak_to_peak",
                "stiffness_mean", "stiffness_min", "stiffness_max")
    PARTIAL_FACE, EDGE_CONTACT, NO_CONTACT = (lib.GD_LTCA_PARTIAL_FACE,
                                              lib.GD_LTCA_EDGE_CONTACT, lib.GD_LTCA_NO_CONTACT)

    def __init__(self, owner, file, mesh):
        super().__init__(None, owner)
        r = owner
        self.file, self.mesh = file, mesh
        self.method = cstr(lib.gd_tvms_method_name(r.method))
        self.n, self.points = int(r.n), int(r.points)
        self.slices, self.max_pairs, self.flagged = int(r.slices), int(r.max_pairs), int(r.flagged)
        for k in self._SCALARS:
            setattr(self, k, float(getattr(r, k)))
        self.contact_ratio_total = float(r.geom.contact_ratio_total)

    def _n(self, name, dtype="f8"):
        return self._view(getattr(self._owner, name), self.n, dtype)

    angle_rad = property(lambda self: self._n("angle_rad"))
    ste = property(lambda self: self._n("ste"))
    ste_unloaded = property(lambda self: self._n("ste_unloaded"))
    stiffness = property(lambda self: self._n("stiffness"))
    face_load_factor = property(lambda self: self._n("face_load_factor"))
    pairs_in_contact = property(lambda self: self._n("pairs_in_contact", np.int32))
    flags = property(lambda self: self._n("flags", np.int32))

    @property
    def pair_load(self):
        return self._view(self._owner.pair_load, (self.n, self.max_pairs))

    @property
    def line_load(self):
        return self._view(self._owner.line_load, (self.n, self.slices))

    @property
    def line_load_mean(self):
        return self._view(self._owner.line_load_mean, self.slices)

    def to_pandas(self):
        """One row per position, as contact_analysis.csv of `--out`."""
        pd = _pandas()
        df = pd.DataFrame({"angle_rad": self.angle_rad, "ste_m": self.ste,
                           "ste_unloaded_m": self.ste_unloaded,
                           "stiffness_N_per_m": self.stiffness,
                           "pairs_in_contact": self.pairs_in_contact,
                           "face_load_factor": self.face_load_factor, "flags": self.flags})
        for j in range(self.max_pairs):
            df["pair_load_%d_N" % j] = self.pair_load[:, j]
        return df


class HarrisMapResult(_Result):
    """Harris map (C gd_ltca_map): per load (views of nloads) torque (N m),
    ste_peak_to_peak, ste_mean (m), stiffness_mean (N/m), face_load_factor (K_Hbeta),
    flagged; ste (nloads x points, m) over the first mesh cycle, ste_unloaded (points)."""

    _figure = "harris_map"

    def __init__(self, owner, file, mesh):
        super().__init__(None, owner)
        self.file, self.mesh = file, mesh
        self.nloads, self.points = int(owner.nloads), int(owner.points)

    def _l(self, name, dtype="f8"):
        return self._view(getattr(self._owner, name), self.nloads, dtype)

    torque = property(lambda self: self._l("torque"))
    ste_peak_to_peak = property(lambda self: self._l("ste_peak_to_peak"))
    ste_mean = property(lambda self: self._l("ste_mean"))
    stiffness_mean = property(lambda self: self._l("stiffness_mean"))
    face_load_factor = property(lambda self: self._l("face_load_factor_cycle"))
    flagged = property(lambda self: self._l("flagged", np.int32))

    @property
    def ste(self):
        return self._view(self._owner.ste, (self.nloads, self.points))

    @property
    def ste_unloaded(self):
        return self._view(self._owner.ste_unloaded, self.points)

    def to_pandas(self):
        """One row per load, as harris_map.csv of `--out`."""
        pd = _pandas()
        return pd.DataFrame({"torque_N_m": self.torque, "ste_peak_to_peak_m": self.ste_peak_to_peak,
                             "ste_mean_m": self.ste_mean,
                             "stiffness_N_per_m": self.stiffness_mean,
                             "face_load_factor": self.face_load_factor,
                             "flagged_positions": self.flagged})
