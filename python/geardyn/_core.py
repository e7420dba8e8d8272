"""The native module, errors, quantities and zero-copy views of C result arrays.

Every C call goes through cffi's compiled (API-mode) module `geardyn._native`, which
releases the GIL for the duration of each call. C results are owned by a cdata made with
ffi.gc(pointer, gd_X_free): the numpy arrays handed out are views of the C memory that
keep that owner alive, so the C result is freed when the last of them (and the Python
result object) is collected.
"""
import math

from ._numpy import np

from ._native import ffi, lib

__all__ = ["ffi", "lib", "GeardynError", "ModelError", "SolverError", "check", "new_error",
           "quantity", "view", "struct_view", "cstr", "names"]


class GeardynError(Exception):
    """A failing geardyn call: the C library's gd_error as attributes.

    status (the C gd_status name, e.g. "input error"), file, line, column (1-based; 0
    when unknown), field (e.g. "bearings[1].kxx"), message and hint (what to do)."""

    def __init__(self, status, file="", line=0, column=0, field="", message="", hint=""):
        self.status, self.file, self.line, self.column = status, file, line, column
        self.field, self.message, self.hint = field, message, hint
        super().__init__(self._text())

    def _text(self):
        where = self.file
        if self.line:
            where += ":%d" % self.line + (":%d" % self.column if self.column else "")
        head = ": ".join(p for p in (where, self.field, self.message) if p)
        return head + ("\n  hint: " + self.hint if self.hint else "")


class ModelError(GeardynError, ValueError):
    """The model, an option or a file is wrong (GD_EINPUT, GD_EIO): the user's to fix."""


class SolverError(GeardynError, ArithmeticError):
    """A solver failed (GD_ENUMERIC): singular system, no convergence."""


def cstr(chars):
    """A C string (char array or char *) as str; "" for NULL."""
    if chars == ffi.NULL:
        return ""
    return ffi.string(chars).decode("utf-8", "replace")


def new_error():
    return ffi.new("gd_error *")


def error_from(err):
    status = int(err.status)
    args = (cstr(lib.gd_status_name(status)), cstr(err.file), int(err.line), int(err.column),
            cstr(err.field), cstr(err.message), cstr(err.hint))
    if status == lib.GD_ENOMEM:
        return MemoryError(args[5] or "geardyn: out of memory")
    if status == lib.GD_ENUMERIC:
        return SolverError(*args)
    return ModelError(*args)


def check(status, err):
    """Raises the error err describes when status is not GD_OK."""
    if status != lib.GD_OK:
        raise error_from(err)


def model_error(field, message, hint="", file=""):
    return ModelError("input error", file, 0, 0, field, message, hint)


_QTY = {
    "length": lib.GD_QTY_LENGTH, "mass": lib.GD_QTY_MASS, "time": lib.GD_QTY_TIME,
    "angle": lib.GD_QTY_ANGLE, "speed": lib.GD_QTY_ANGULAR_SPEED,
    "force": lib.GD_QTY_FORCE, "torque": lib.GD_QTY_TORQUE,
    "stiffness": lib.GD_QTY_STIFFNESS, "damping": lib.GD_QTY_DAMPING,
    "rot_stiffness": lib.GD_QTY_ROT_STIFFNESS, "rot_damping": lib.GD_QTY_ROT_DAMPING,
    "inertia": lib.GD_QTY_INERTIA, "density": lib.GD_QTY_DENSITY,
    "pressure": lib.GD_QTY_PRESSURE, "viscosity": lib.GD_QTY_VISCOSITY,
    "mass_length": lib.GD_QTY_MASS_LENGTH, "dimless": lib.GD_QTY_DIMLESS,
}


def quantity(value, kind, field=""):
    """A number (SI) as float, or a string with a unit ("3000 rpm", "25.4 mm") parsed by
    the library (gd_parse_quantity) into SI. kind: "speed", "length", "angle", ..."""
    if isinstance(value, str):
        out = ffi.new("double *")
        err = new_error()
        if lib.gd_parse_quantity(value.encode(), _QTY[kind], out, err) != lib.GD_OK:
            raise model_error(field, "'%s': %s" % (value, cstr(err.message)),
                              "write a number in SI units or a number with a unit")
        return out[0]
    if isinstance(value, (bool, complex, np.complexfloating)):
        raise model_error(field, "expected a real number, got %r" % (value,))
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise model_error(field, "expected a number, got %r" % (value,)) from None
    if not math.isfinite(v):  # issue 38 L5: modal(speed=nan) ran
        raise model_error(field, "expected a finite number, got %r" % (value,))
    return v


def whole(value, field, lo, hi):
    """value as an int in lo..hi: an int, or a float without a fraction (issue 38 L5:
    modes=-1 and harmonics=2.5 were taken); ModelError naming field otherwise."""
    if not isinstance(value, bool):
        try:
            f = float(value)
            if not isinstance(value, (complex, np.complexfloating)) and f.is_integer() \
                    and lo <= f <= hi:
                return int(f)
        except (TypeError, ValueError, OverflowError):
            pass
    raise model_error(field, "expected a whole number from %d to %d, got %r" % (lo, hi, value))


def names(array, count):
    """A C array of count const char * as a list of str."""
    return [cstr(array[i]) for i in range(count)]


class _Memory:
    """C memory exposed to numpy through the array interface (bytes, or a strided array
    of one type); it keeps the owner (the ffi.gc'd C result) alive as long as any array
    viewing it lives."""

    __slots__ = ("__array_interface__", "_owner")

    def __init__(self, owner, address, nbytes, writable, typestr="|u1", shape=None,
                 strides=None):
        self._owner = owner
        self.__array_interface__ = {"data": (address, not writable),
                                    "shape": shape or (nbytes,), "typestr": typestr,
                                    "strides": strides, "version": 3}


def field_view(owner, pointer, count, struct, name):
    """numpy array of one field of an array of count C structs laid out as the
    structured dtype `struct` (struct_dtype): a strided view, no copy. A field that is
    itself an array (energy_share) gives count x its shape."""
    ftype, offset = struct.fields[name][:2]
    base, sub = ftype.base, ftype.shape
    if pointer == ffi.NULL or count == 0:
        return np.zeros((count,) + sub, dtype=base)
    address = int(ffi.cast("uintptr_t", pointer)) + offset
    shape = (count,) + sub
    strides = (struct.itemsize,) + tuple(base.itemsize * math.prod(sub[k + 1:])
                                         for k in range(len(sub)))
    return np.asarray(_Memory(owner, address, 0, False, base.str, shape, strides))


def view(owner, pointer, shape, dtype="f8", order="C", writable=False):
    """numpy array of the C memory at pointer (no copy), of the given shape and dtype,
    row-major ("C") or column-major ("F"); owner is kept alive by the array. The array
    interface describes the final array directly (not bytes viewed as dtype), so its
    base has its size: scipy copies arrays that view a base twice their size."""
    dtype = dtype.dtype if isinstance(dtype, StructDtype) else np.dtype(dtype)
    shape = (int(shape),) if isinstance(shape, int) else tuple(int(s) for s in shape)
    count = math.prod(shape)
    if pointer == ffi.NULL or count == 0:
        return np.zeros(shape, dtype=dtype, order=order)
    address = int(ffi.cast("uintptr_t", pointer))
    if dtype.fields is not None:  # structured: bytes viewed as the records
        raw = np.asarray(_Memory(owner, address, count * dtype.itemsize, writable))
        return raw.view(dtype).reshape(shape)
    strides = None
    if order == "F":
        strides = tuple(dtype.itemsize * math.prod(shape[:k]) for k in range(len(shape)))
    return np.asarray(_Memory(owner, address, 0, writable, dtype.str, shape, strides))


class StructDtype:
    """numpy structured dtype laid out exactly as a C struct, made on first use (numpy is
    imported on first use, _numpy.py): `names` without numpy, `dtype` the numpy dtype,
    whose other attributes (fields, itemsize) it answers too."""

    def __init__(self, ctype, fields):
        self.names = tuple(fields)
        self._spec = {"names": list(fields), "formats": list(fields.values()),
                      "offsets": [ffi.offsetof(ctype, name) for name in fields],
                      "itemsize": ffi.sizeof(ctype)}

    def __getattr__(self, name):
        if name == "dtype":
            self.dtype = np.dtype(self._spec)
            return self.dtype
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(self.dtype, name)


def struct_dtype(ctype, fields):
    """The structured dtype laid out exactly as C struct ctype, for the given fields
    (name -> numpy type, or (numpy type, shape)); the rest is padding (a StructDtype)."""
    return StructDtype(ctype, fields)


def struct_view(owner, pointer, shape, dtype):
    """numpy structured array viewing an array of C structs (no copy)."""
    return view(owner, pointer, shape, dtype)


_ENUM = "i%d" % ffi.sizeof("gd_whirl")  # a dtype string: numpy is imported on first use
MODE_DTYPE = struct_dtype("gd_mode", {
    "lambda_re": "f8", "lambda_im": "f8", "omega_n": "f8", "omega_d": "f8",
    "frequency_hz": "f8", "damping_ratio": "f8", "log_decrement": "f8",
    "rigid_body": "i4", "overdamped": "i4", "unstable": "i4", "whirl": _ENUM,
    "energy_share": ("f8", (int(lib.GD_NMOTIONS),)), "dominant_motion": _ENUM,
    "dominant_component": "i4", "residual": "f8", "residual_floor": "f8"})

WHIRL_NAMES = names(lib.gd_whirl_names, 4)
MOTION_NAMES = names(lib.gd_motion_names, int(lib.GD_NMOTIONS))
DOF_NAMES = names(lib.gd_dof_names, int(lib.GD_NODE_DOFS))
COUPLING_NAMES = names(lib.gd_coupling_names, 3)
