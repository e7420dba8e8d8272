"""The Python module loads only the core (issue 35 item 1): after `import geardyn` and an
analysis, no image, font, PDF or GUI library is mapped into the process (PNG and PDF are
the plugin geardyn-raster.so, which only a PNG or PDF plot loads)."""
import re

import pytest

from conftest import example

# librsvg's and cairo's dependencies, as tests/structure/check_linked_libs.sh forbids them
FORBIDDEN = re.compile(r"/lib(rsvg|cairo|pango|fontconfig|freetype|png16|harfbuzz|icu\w*|X\w+|"
                       r"xcb\w*|poppler|gdk_pixbuf|pixman|hdf5\w*)[-.]")


def test_only_the_core_is_loaded(geardyn):
    m = geardyn.load(example("kumar2011_coupled")).modal()
    assert len(m.frequency_hz) > 0
    with open("/proc/self/maps") as f:
        maps = {line.split()[-1] for line in f if "/" in line}
    assert any("libgeardyn.so" in p for p in maps)
    loaded = sorted(p for p in maps if FORBIDDEN.search(p))
    assert loaded == [], "not core libraries: %s" % loaded


def test_modal_tol_and_residuals(geardyn):
    """modal(tol=...) as `geardyn modal --tol`: every elastic mode's residual at most tol
    (or 100 times its rounding floor), frequencies as the dense solver's to 1e-10."""
    import os
    import numpy as np
    from conftest import ROOT
    rig = geardyn.load(os.path.join(ROOT, "bench", "models", "rig366.yaml"))
    sp = rig.modal(speed="3000 rpm", modes=8, tol=1e-11)
    de = rig.modal(speed="3000 rpm", modes=8, left=True)  # left vectors: the dense solver
    el = ~sp.rigid_body.astype(bool)
    assert np.all(sp.residual[el] <= np.maximum(1e-11, 100 * sp.residual_floor[el]))
    assert np.allclose(sp.omega_n, de.omega_n, rtol=1e-10, atol=0)
    with pytest.raises(geardyn.ModelError):
        rig.modal(tol=0)


def test_import_leaves_numpy_for_the_first_array():
    """`import geardyn` imports no numpy (issue 35: numpy's import is ~9x the package's
    own, in instructions): loading and checking a model needs none; the first result
    array imports it, and the structured views (modes) are laid out as the C records."""
    import os
    import subprocess
    import sys
    from conftest import ROOT
    code = ("import sys, geardyn\n"
            "assert 'numpy' not in sys.modules, 'import geardyn imported numpy'\n"
            "m = geardyn.load(%r)\n"
            "assert 'numpy' not in sys.modules, 'load imported numpy'\n"
            "r = m.modal()\n"
            "import numpy as np\n"
            "assert isinstance(r.frequency_hz, np.ndarray)\n"
            "assert r.modes.dtype.itemsize == geardyn.ffi.sizeof('gd_mode')\n"
            "assert np.array_equal(r.modes['frequency_hz'], r.frequency_hz)\n"
            "print(geardyn.version())\n" % example("kumar2011_coupled"))
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == geardyn_version()


def geardyn_version():
    import geardyn
    return geardyn.version()
