"""Building a model from Python dicts and lists through the C builder API
(include/geardyn/builder.h, docs/builder.md).

The dict has the layout and key names of a model file (docs/model-format.md), so a
model file read with any YAML reader builds the same model: materials, dofs, shafts
(sections, nodes), disks, bearings (constant coefficients), springs, meshes (size,
angles, stiffness, damping, coupling), unbalances, speed, reference_shaft, rotation.
Values are SI numbers or strings with units ("25.4 mm", "3000 rpm"). Time-integration
items (tables, backlash, loads, cams), bearing speed tables and gear geometry are
file-only for now: load() or loads() reads them. planetary_sets (docs/planetary.md):
members, planets (count or angles, pin errors), teeth, radii, angles, mesh stiffness and
damping, carrier_frame; a set's tooth `geometry`, `mesh_laws` and `mesh_phases` are
file-only.

Errors are the builder's (field "bearings[1].kxx", line 0) raised as ModelError; an
unknown key is refused with the keys known there, as the file reader does.
"""
from . import _core
from ._core import ffi, lib, check, new_error, quantity, model_error

__all__ = ["build"]


class _Ctx:
    """Keeps the C strings and arrays of the specs alive until the model is finished."""

    def __init__(self):
        self.keep = []

    def s(self, value, field):
        if value is None:
            return ffi.NULL
        if not isinstance(value, str):
            raise model_error(field, "expected a name (string), got %r" % (value,))
        c = ffi.new("char[]", value.encode())
        self.keep.append(c)
        return c


def _keys(item, known, path):
    if not isinstance(item, dict):
        raise model_error(path, "expected a map, got %r" % (item,))
    for k in item:
        if k not in known:
            raise model_error("%s.%s" % (path, k), "unknown key '%s'" % k,
                              "known keys: " + ", ".join(known))


def _spec(ctx, kind, d, path, keys):
    """A gd_<kind>_spec filled by its _init, after checking d's keys, with the name,
    path and node references (node, to, driver, driven) the spec has."""
    _keys(d, keys, path)
    s = ffi.new("gd_%s_spec *" % kind)
    getattr(lib, "gd_%s_spec_init" % kind)(s)
    s.path = ctx.s(path, path)
    for ref in ("name", "node", "to", "driver", "driven"):
        if ref in keys:
            setattr(s, ref, ctx.s(d.get(ref), "%s.%s" % (path, ref)))
    return s


def _list(spec, key):
    v = spec.get(key) or []
    if not isinstance(v, list):
        raise model_error(key, "expected a list")
    return v


def _pair(value, kind, field):
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        raise model_error(field, "expected [driver, driven], got %r" % (value,))
    return [quantity(v, kind, "%s[%d]" % (field, i)) for i, v in enumerate(value)]


def _material(m, ctx, name, d):
    path = "materials.%s" % name
    s = _spec(ctx, "material", d, path, ("density", "E", "G", "poisson"))
    s.name = ctx.s(name, path)
    s.density = quantity(d.get("density", 0), "density", path + ".density")
    s.E = quantity(d.get("E", 0), "pressure", path + ".E")
    s.G = quantity(d.get("G", 0), "pressure", path + ".G")
    s.poisson = quantity(d.get("poisson", 0), "dimless", path + ".poisson")
    return lib.gd_model_add_material(m, s, ffi.NULL, ctx.err)


_SHAFT_KEYS = ("name", "material", "sections", "nodes", "elements_per_section",
               "max_element_length", "speed_ratio")


def _shaft(m, ctx, i, d):
    path = "shafts[%d]" % i
    s = _spec(ctx, "shaft", d, path, _SHAFT_KEYS)
    secs = d.get("sections") or []
    nodes = d.get("nodes") or []
    sec = ffi.new("gd_section_spec[]", max(len(secs), 1))
    for k, x in enumerate(secs):
        p = "%s.sections[%d]" % (path, k)
        _keys(x, ("length", "outer_diameter", "inner_diameter", "material", "elements"), p)
        lib.gd_section_spec_init(ffi.addressof(sec, k))
        sec[k].length = quantity(x.get("length", 0), "length", p + ".length")
        sec[k].outer_diameter = quantity(x.get("outer_diameter", 0), "length",
                                         p + ".outer_diameter")
        sec[k].inner_diameter = quantity(x.get("inner_diameter", 0), "length",
                                         p + ".inner_diameter")
        sec[k].material = ctx.s(x.get("material"), p + ".material")
        sec[k].elements = int(x.get("elements", 0))
    st = ffi.new("gd_station_spec[]", max(len(nodes), 1))
    for k, x in enumerate(nodes):
        p = "%s.nodes[%d]" % (path, k)
        _keys(x, ("name", "at"), p)
        lib.gd_station_spec_init(ffi.addressof(st, k))
        st[k].name = ctx.s(x.get("name"), p + ".name")
        st[k].at = quantity(x.get("at", 0), "length", p + ".at")
    ctx.keep += [sec, st]
    s.material = ctx.s(d.get("material"), path + ".material")
    s.nsections, s.sections, s.nstations, s.stations = len(secs), sec, len(nodes), st
    s.elements_per_section = int(d.get("elements_per_section", 0))
    s.max_element_length = quantity(d.get("max_element_length", 0), "length",
                                    path + ".max_element_length")
    if "speed_ratio" in d:
        s.has_speed_ratio = 1
        s.speed_ratio = quantity(d["speed_ratio"], "dimless", path + ".speed_ratio")
    return lib.gd_model_add_shaft(m, s, ffi.NULL, ctx.err)


def _disk(m, ctx, i, d):
    path = "disks[%d]" % i
    s = _spec(ctx, "disk", d, path,
              ("name", "node", "mass", "polar_inertia", "diametral_inertia", "geometry"))
    s.mass = quantity(d.get("mass", 0), "mass", path + ".mass")
    s.polar_inertia = quantity(d.get("polar_inertia", 0), "inertia", path + ".polar_inertia")
    if "diametral_inertia" in d:
        s.diametral_inertia = quantity(d["diametral_inertia"], "inertia",
                                       path + ".diametral_inertia")
    if "geometry" in d:
        g, p = d["geometry"], path + ".geometry"
        _keys(g, ("outer_diameter", "inner_diameter", "width", "material"), p)
        s.from_geometry = 1
        s.outer_diameter = quantity(g.get("outer_diameter", 0), "length", p + ".outer_diameter")
        s.inner_diameter = quantity(g.get("inner_diameter", 0), "length", p + ".inner_diameter")
        s.width = quantity(g.get("width", 0), "length", p + ".width")
        s.material = ctx.s(g.get("material"), p + ".material")
    return lib.gd_model_add_disk(m, s, ffi.NULL, ctx.err)


# bearing key -> (gd_bearing_coeffs fields, quantity)
_BEARING = {
    "k": (("kxx", "kyy"), "stiffness"), "c": (("cxx", "cyy"), "damping"),
    "kxx": (("kxx",), "stiffness"), "kxy": (("kxy",), "stiffness"),
    "kyx": (("kyx",), "stiffness"), "kyy": (("kyy",), "stiffness"),
    "kzz": (("kzz",), "stiffness"), "k_tilt": (("ktilt",), "rot_stiffness"),
    "k_torsion": (("ktorsion",), "rot_stiffness"),
    "cxx": (("cxx",), "damping"), "cxy": (("cxy",), "damping"), "cyx": (("cyx",), "damping"),
    "cyy": (("cyy",), "damping"), "czz": (("czz",), "damping"),
    "c_tilt": (("ctilt",), "rot_damping"), "c_torsion": (("ctorsion",), "rot_damping"),
}


def _bearing(m, ctx, i, d):
    path = "bearings[%d]" % i
    s = _spec(ctx, "bearing", d, path, ("name", "node", "to") + tuple(_BEARING))
    for short, longs in (("k", ("kxx", "kyy")), ("c", ("cxx", "cyy"))):
        if short in d and any(k in d for k in longs):
            raise model_error("%s.%s" % (path, short), "'%s' is kxx = kyy: not with %s"
                              % (short, " or ".join(longs)), "give one or the other")
    for key, (fields, kind) in _BEARING.items():
        if key in d:
            v = quantity(d[key], kind, "%s.%s" % (path, key))
            for f in fields:
                setattr(s.coeffs, f, v)
    return lib.gd_model_add_bearing(m, s, ffi.NULL, ctx.err)


def _spring(m, ctx, i, d):
    path = "springs[%d]" % i
    s = _spec(ctx, "spring", d, path, ("name", "node", "to", "dof", "stiffness", "damping"))
    dof = d.get("dof", "rz")
    if dof not in _core.DOF_NAMES:
        raise model_error(path + ".dof", "unknown DOF '%s'" % dof, "use x, y, z, rx, ry or rz")
    s.dof = _core.DOF_NAMES.index(dof)
    rot = dof.startswith("r")
    s.stiffness = quantity(d.get("stiffness", 0), "rot_stiffness" if rot else "stiffness",
                           path + ".stiffness")
    s.damping = quantity(d.get("damping", 0), "rot_damping" if rot else "damping",
                         path + ".damping")
    return lib.gd_model_add_spring(m, s, ffi.NULL, ctx.err)


_MESH_KEYS = ("name", "driver", "driven", "teeth", "base_radius", "pitch_radius", "module",
              "pressure_angle", "helix_angle", "hand", "line_of_centres", "driver_rotation",
              "stiffness", "damping", "coupling")


def _mesh(m, ctx, i, d):
    path = "meshes[%d]" % i
    s = _spec(ctx, "mesh", d, path, _MESH_KEYS)
    if "teeth" in d:
        t = d["teeth"]
        if not isinstance(t, (list, tuple)) or len(t) != 2:
            raise model_error(path + ".teeth", "expected [z1, z2]")
        s.teeth = [int(t[0]), int(t[1])]
    for key, kind in (("base_radius", "length"), ("pitch_radius", "length")):
        if key in d:
            setattr(s, key, _pair(d[key], kind, "%s.%s" % (path, key)))
    for key, kind in (("module", "length"), ("pressure_angle", "angle"),
                      ("helix_angle", "angle"), ("line_of_centres", "angle"),
                      ("stiffness", "stiffness"), ("damping", "damping")):
        if key in d:
            setattr(s, key, quantity(d[key], kind, "%s.%s" % (path, key)))
    for key, values, attr in (("hand", {"right": 1, "left": -1}, "hand"),
                              ("driver_rotation", {"ccw": 1, "cw": -1}, "driver_rotation"),
                              ("coupling", {n: k for k, n in enumerate(_core.COUPLING_NAMES)},
                               "coupling")):
        if key in d:
            if d[key] not in values:
                raise model_error("%s.%s" % (path, key), "unknown value '%s'" % (d[key],),
                                  "use " + " or ".join(values))
            setattr(s, attr, values[d[key]])
    return lib.gd_model_add_mesh(m, s, ffi.NULL, ctx.err)


def _unbalance(m, ctx, i, d):
    path = "unbalances[%d]" % i
    s = _spec(ctx, "unbalance", d, path, ("name", "node", "amount", "mass", "eccentricity",
                                          "phase"))
    if "amount" in d:
        if "mass" in d or "eccentricity" in d:
            raise model_error(path + ".amount", "give amount, or mass and eccentricity")
        s.amount = quantity(d["amount"], "mass_length", path + ".amount")
    elif "mass" in d and "eccentricity" in d:
        s.amount = quantity(d["mass"], "mass", path + ".mass") * \
            quantity(d["eccentricity"], "length", path + ".eccentricity")
    else:
        raise model_error(path, "no amount", "give amount (kg m), or mass and eccentricity")
    s.phase = quantity(d.get("phase", 0), "angle", path + ".phase")
    return lib.gd_model_add_unbalance(m, s, ffi.NULL, ctx.err)


_PLANETARY_KEYS = ("name", "held", "sun", "ring", "carrier", "planets", "teeth", "base_radius",
                   "carrier_radius", "pressure_angle", "helix_angle", "planet_tip_radius",
                   "mesh_stiffness", "mesh_damping", "carrier_frame", "centrifugal_stiffness")
_MEMBERS = ("sun", "ring", "carrier")
_MEMBER_KEYS = ("node", "mass", "inertia", "k_support", "k_torsion")
_PLANET_KEYS = ("count", "angles", "mass", "inertia", "bearing_stiffness", "pin_errors",
                "pin_errors_radial")
_FILE_ONLY = ("geometry", "mesh_laws", "mesh_phases")


def _per_gear(d, key, keys, kind, path, one_value):
    """`key:` as a map {sun:, ring:[, planet:]} of quantities, or (one_value) one value for
    all; None when absent (the file reader's read_per_gear)."""
    if key not in d:
        return None
    v, p = d[key], "%s.%s" % (path, key)
    if one_value and not isinstance(v, dict):
        x = quantity(v, kind, p)
        return [x] * len(keys)
    _keys(v, keys, p)
    return [quantity(v[k], kind, "%s.%s" % (p, k)) if k in v else 0.0 for k in keys]


def _qty_list(ctx, values, kind, field, count=None, what=""):
    """A list of quantities as a C double array kept alive by ctx."""
    if not isinstance(values, (list, tuple)):
        raise model_error(field, "expected a list, got %r" % (values,))
    if count is not None and len(values) != count:
        raise model_error(field, "%d %s for %d planets" % (len(values), what, count),
                          "give one per planet")
    arr = ffi.new("double[]", [quantity(v, kind, "%s[%d]" % (field, i))
                               for i, v in enumerate(values)] or [0.0])
    ctx.keep.append(arr)
    return arr


def _planetary(m, ctx, i, d):
    """One planetary set (docs/planetary.md, "Model file keys"): the constant-coefficient
    set; `geometry`, `mesh_laws` and `mesh_phases` are read from files only."""
    path = "planetary_sets[%d]" % i
    for k in _FILE_ONLY:
        if isinstance(d, dict) and k in d:
            raise model_error("%s.%s" % (path, k), "'%s' is not built from a dict yet" % k,
                              "load the model from a file or text (geardyn.load / loads)")
    _keys(d, _PLANETARY_KEYS, path)
    s = ffi.new("gd_planetary_spec *")
    lib.gd_planetary_spec_init(s)
    s.path = ctx.s(path, path)
    s.name = ctx.s(d.get("name"), path + ".name")
    held = d.get("held", "none")
    if held not in _MEMBERS + ("none",):
        raise model_error(path + ".held", "unknown member '%s'" % (held,),
                          "use sun, ring, carrier or none")
    s.held = -1 if held == "none" else _MEMBERS.index(held)
    if "carrier_frame" in d:
        if d["carrier_frame"] not in ("planets", "all"):
            raise model_error(path + ".carrier_frame", "unknown value '%s'" % (d["carrier_frame"],),
                              "use all or planets")
        s.carrier_frame = 1 if d["carrier_frame"] == "all" else 0
    else:
        s.carrier_frame = -1
    if "centrifugal_stiffness" in d:
        if not isinstance(d["centrifugal_stiffness"], bool):
            raise model_error(path + ".centrifugal_stiffness",
                              "'%s' is not true or false" % (d["centrifugal_stiffness"],),
                              "write true or false")
        s.centrifugal_stiffness = 1 if d["centrifugal_stiffness"] else 0
    for j, member in enumerate(_MEMBERS):
        p = "%s.%s" % (path, member)
        b = d.get(member)
        if b is None:
            raise model_error(p, "the set's %s is missing" % member,
                              "give {node: NAME, mass, inertia, k_support, k_torsion}")
        _keys(b, _MEMBER_KEYS, p)
        s.member[j].node = ctx.s(b.get("node"), p + ".node")
        for key, kind in (("mass", "mass"), ("inertia", "inertia"), ("k_support", "stiffness"),
                          ("k_torsion", "rot_stiffness")):
            setattr(s.member[j], key, quantity(b.get(key, 0), kind, "%s.%s" % (p, key)))
    teeth = _per_gear(d, "teeth", ("sun", "ring", "planet"), "dimless", path, False)
    if teeth is not None:
        for j, z in enumerate(teeth):
            if z != 0 and (z != int(z) or not 0 < z <= 100000):
                raise model_error(path + ".teeth", "invalid teeth number %g" % z,
                                  "teeth numbers are whole numbers from 3 to 100000")
            s.teeth[j] = int(z)
    for key, keys, kind, one, attr in (
            ("base_radius", ("sun", "ring", "planet"), "length", False, "base_radius"),
            ("pressure_angle", ("sun", "ring"), "angle", True, "pressure_angle"),
            ("mesh_stiffness", ("sun", "ring"), "stiffness", True, "mesh_stiffness"),
            ("mesh_damping", ("sun", "ring"), "damping", True, "mesh_damping")):
        v = _per_gear(d, key, keys, kind, path, one)
        if v is not None:
            setattr(s, attr, v)
    for key, kind in (("carrier_radius", "length"), ("helix_angle", "angle"),
                      ("planet_tip_radius", "length")):
        if key in d:
            setattr(s, key, quantity(d[key], kind, "%s.%s" % (path, key)))
    pp = path + ".planets"
    pl = d.get("planets")
    if pl is None:
        raise model_error(pp, "the set's planets are missing",
                          "give {count: N, mass, inertia, bearing_stiffness}")
    _keys(pl, _PLANET_KEYS, pp)
    s.planet_mass = quantity(pl.get("mass", 0), "mass", pp + ".mass")
    s.planet_inertia = quantity(pl.get("inertia", 0), "inertia", pp + ".inertia")
    s.bearing_stiffness = quantity(pl.get("bearing_stiffness", 0), "stiffness",
                                   pp + ".bearing_stiffness")
    count = pl.get("count")
    if count is not None:
        count = _core.whole(count, pp + ".count", 1, 64)
    if "angles" in pl:
        angles = pl["angles"]
        if count is not None and isinstance(angles, (list, tuple)) and count != len(angles):
            raise model_error(pp + ".count", "count %d but %d angles" % (count, len(angles)),
                              "give one angle per planet, or leave out count")
        s.planet_angles = _qty_list(ctx, angles, "angle", pp + ".angles")
        count = len(angles)
    elif count is None:
        raise model_error(pp, "the number of planets is missing",
                          "give `count: N` (equally spaced) or `angles: [...]`")
    s.nplanets = count
    for key, attr in (("pin_errors", "pin_errors"), ("pin_errors_radial", "pin_errors_radial")):
        if key in pl:
            setattr(s, attr, _qty_list(ctx, pl[key], "length", "%s.%s" % (pp, key), count,
                                       "pin errors"))
    return lib.gd_model_add_planetary(m, s, ffi.NULL, ctx.err)


_TOP = ("title", "description", "materials", "dofs", "shafts", "disks", "bearings", "springs",
        "meshes", "planetary_sets", "unbalances", "speed", "reference_shaft", "rotation")
# the file reader's order (src/model_file/model_parse.c), so a dict and its YAML build the
# same model
_LISTS = (("shafts", _shaft), ("disks", _disk), ("bearings", _bearing), ("springs", _spring),
          ("meshes", _mesh), ("planetary_sets", _planetary), ("unbalances", _unbalance))


def build_handle(spec, name):
    """A finished C model (ffi.gc'd) from the dict spec."""
    _keys(spec, _TOP, "model")
    out = ffi.new("gd_model **")
    err = new_error()
    check(lib.gd_model_new(name.encode(), out, err), err)
    m = ffi.gc(out[0], lib.gd_model_free)
    ctx = _Ctx()
    ctx.err = err
    mats = spec.get("materials") or {}
    if not isinstance(mats, dict):
        raise model_error("materials", "expected a map name -> material")
    for mname, d in mats.items():
        check(_material(m, ctx, mname, d), err)
    if "dofs" in spec:
        mask = 0
        for d in spec["dofs"]:
            if d not in _core.DOF_NAMES:
                raise model_error("dofs", "unknown DOF '%s'" % d, "use x, y, z, rx, ry or rz")
            mask |= 1 << _core.DOF_NAMES.index(d)
        check(lib.gd_model_set_dofs(m, mask, err), err)
    if not spec.get("shafts"):
        raise model_error("shafts", "no shafts", "describe at least one shaft")
    for key, add in _LISTS:
        for i, d in enumerate(_list(spec, key)):
            if not isinstance(d, dict):
                raise model_error("%s[%d]" % (key, i), "expected a map, got %r" % (d,))
            check(add(m, ctx, i, d), err)
    if "reference_shaft" in spec or "rotation" in spec:
        rot = spec.get("rotation", "ccw")
        if rot not in ("ccw", "cw"):
            raise model_error("rotation", "unknown rotation '%s'" % rot, "use ccw or cw")
        ref = spec.get("reference_shaft")
        if ref is None:
            ref = spec["shafts"][0].get("name") or "shaft1"
        loc = ffi.new("gd_loc *")
        check(lib.gd_model_set_reference_shaft(m, ctx.s(ref, "reference_shaft"),
                                               1 if rot == "ccw" else -1, loc[0], err), err)
    if "speed" in spec:
        check(lib.gd_model_set_speed(m, quantity(spec["speed"], "speed", "speed"), err), err)
    check(lib.gd_model_finish(m, err), err)
    return m
