# SPDX-License-Identifier: MIT
"""libtangent: the compiled module libtangent._libtangent (python/module.cpp), re-exported.
Type checkers read __init__.pyi beside this file (py.typed marks the package as typed)."""
from . import _libtangent
from ._libtangent import *  # noqa: F401,F403  (every public name of the compiled module)
from ._libtangent import __version__

__doc__ = _libtangent.__doc__
__all__ = [name for name in dir(_libtangent) if not name.startswith("_")]

# The exceptions are raised and caught as libtangent.Error and libtangent.InputError: name them
# so in tracebacks and for pickle (Dask sends them between processes).
Error.__module__ = InputError.__module__ = __name__  # noqa: F405
