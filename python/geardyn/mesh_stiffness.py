"""Gear mesh stiffness from geometry (docs/mesh-stiffness.md): gd_gear_pair_load and
gd_tvms_compute, as `geardyn mesh-stiffness`."""
import os

import numpy as np

from ._core import ffi, lib, check, new_error, cstr, quantity, model_error
from .analyses import _Result, _pandas
from .model import _load_options, _set_strings

__all__ = ["mesh_stiffness", "MeshStiffnessResult"]


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
