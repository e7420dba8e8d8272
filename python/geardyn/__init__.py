"""geardyn: dynamics of geared rotor systems, a Python interface to the C library.

    import geardyn
    m = geardyn.load("examples/kumar2011_coupled.yaml")
    r = m.modal()                       # numpy arrays over the C result, no copy
    r.omega_n, r.shapes, r.to_pandas()
    m.set("meshes.mesh.stiffness", 3e8)  # as --set PATH=VALUE
    M, K, C, G, dofs = m.matrices(speed="3000 rpm")   # scipy.sparse

See docs/python.md. Errors raise geardyn.ModelError (file, line, field, hint).
"""
from ._core import GeardynError, ModelError, SolverError, ffi, lib, cstr
from .model import Model, System, Matrices, load, loads, build
from .analyses import (ModalResult, CampbellResult, FrfResult, UnbalanceResult, sweep)
from .transient import TransientResult
from .periodic import PeriodicResult
from .static import StaticResult
from .mesh_stiffness import (mesh_stiffness, MeshStiffnessResult, contact_analysis,
                             ContactAnalysisResult, harris_map, HarrisMapResult)
from .laws import Law
from .testdata import (read_testdata, testmodal, correlate, update, TestData, EmaResult,
                       Correlation, UpdateResult)

__all__ = ["GeardynError", "ModelError", "SolverError", "Model", "System", "Matrices", "load",
           "loads", "build", "sweep", "mesh_stiffness", "ModalResult", "CampbellResult",
           "FrfResult", "UnbalanceResult", "TransientResult", "PeriodicResult", "StaticResult",
           "MeshStiffnessResult", "contact_analysis", "ContactAnalysisResult", "harris_map",
           "HarrisMapResult", "Law", "read_testdata", "testmodal", "correlate", "update",
           "TestData", "EmaResult", "Correlation", "UpdateResult",
           "version", "__version__"]


def version():
    """The linked C library's version (gd_version())."""
    return cstr(lib.gd_version())


__version__ = version()
