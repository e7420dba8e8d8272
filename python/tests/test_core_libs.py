"""The Python module loads only the core (issue 35 item 1): after `import geardyn` and an
analysis, no image, font, PDF or GUI library is mapped into the process (PNG and PDF are
the plugin geardyn-raster.so, which only a PNG or PDF plot loads)."""
import re

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
