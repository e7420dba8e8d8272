"""numpy, imported on its first use rather than by `import geardyn` (issue 35: numpy's
import is several times the rest of the package's, and a script that only loads and
checks a model, or reads the version, needs none of it).

`np` stands for the module: the first lookup of a name imports numpy and keeps the
value as a plain attribute, so later lookups cost what a module's do. Code at a
module's top level must not touch `np` (that would import numpy at `import geardyn`):
defaults are dtype strings ("f8"), not np.float64."""


class _Numpy:
    def __getattr__(self, name):
        import numpy

        value = getattr(numpy, name)
        setattr(self, name, value)
        return value

    def __repr__(self):
        return "<numpy, imported on first use>"


np = _Numpy()
