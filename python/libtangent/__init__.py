# SPDX-License-Identifier: MIT
"""libtangent: the compiled module libtangent._libtangent (python/module.cpp), re-exported.
Type checkers read __init__.pyi beside this file (py.typed marks the package as typed).

compute_tangents(), bake(), bake_tree(), check() and check_tree() take their keyword arguments from the option
table every front end shares (option_table(); the `tangent` command's options, spelled
snake_case): their signatures and the "Options" part of their docstrings are made from it here."""
import functools
import inspect
import textwrap

from . import _libtangent
from ._libtangent import *  # noqa: F401,F403  (every public name of the compiled module)
from ._libtangent import __version__

__doc__ = _libtangent.__doc__
__all__ = [name for name in dir(_libtangent) if not name.startswith("_")]

# The exceptions are raised and caught as libtangent.Error and libtangent.InputError: name them
# so in tracebacks and for pickle (Dask sends them between processes).
Error.__module__ = InputError.__module__ = __name__  # noqa: F405


def _option_help(row):
    """One option's line of a docstring: its help, choices (default marked) or default."""
    text = row["help"]
    if row["kind"] == "choice":
        names = " | ".join(name + (" (default)" if name == row["default"] else "") for name in row["choices"])
        text = f"{names}; {text}"
    elif row["kind"] == "list":
        text = f"{text}: a list of {', '.join(row['choices'])}"
    elif row["kind"] in ("number", "integer") and row["default"] is not None:
        text = f"{text} (default {row['default']:g})"
    return f"{row['python']}: {text}"


def _with_table_options(function, command, positional):
    """`function` (compiled, taking **options) with the table's keyword-only options of
    `command` in its signature and docstring."""
    rows = [row for row in option_table() if command in row["commands"] and "python" in row["front_ends"]]  # noqa: F405
    parameters = [inspect.Parameter(name, inspect.Parameter.POSITIONAL_OR_KEYWORD) for name in positional]
    parameters += [inspect.Parameter(row["python"], inspect.Parameter.KEYWORD_ONLY, default=row["default"]) for row in rows]

    @functools.wraps(function)
    def wrapper(*args, **options):
        return function(*args, **options)

    wrapper.__signature__ = inspect.Signature(parameters)
    head, _, tail = function.__doc__.partition("\n\n")
    # pybind11 leads the docstring with its own signature line (**kwargs): leave it out.
    body = tail if head.startswith(function.__name__ + "(") else function.__doc__
    wrapper.__doc__ = body.rstrip() + "\n\nOptions (keyword only; the `tangent` command's, spelled snake_case):\n" + \
        "\n".join(textwrap.fill(_option_help(row), 96, initial_indent="  ", subsequent_indent="    ") for row in rows) + "\n"
    wrapper.__module__ = __name__
    return wrapper


compute_tangents = _with_table_options(_libtangent.compute_tangents, "compute_tangents",
                                       ["positions", "normals", "uvs", "indices"])
bake = _with_table_options(_libtangent.bake, "bake", ["input", "output"])
bake_tree = _with_table_options(_libtangent.bake_tree, "bake_tree", ["input_folder", "output_folder"])
check = _with_table_options(_libtangent.check, "check", ["path"])
check_tree = _with_table_options(_libtangent.check_tree, "check", ["folder"])
