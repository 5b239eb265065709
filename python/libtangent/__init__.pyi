# SPDX-License-Identifier: MIT
"""Type stubs of the package libtangent, whose __init__.py re-exports the compiled module
libtangent._libtangent (python/module.cpp): see help(libtangent)."""
import os
from typing import Any, Optional, TypedDict, Union

import numpy as np
import numpy.typing as npt

PathLike = Union[str, os.PathLike[str]]

__version__: str

class Error(RuntimeError):
    """Base class of libtangent's errors (I/O failures)."""

class InputError(Error):
    """A file libtangent refuses: the message names the file and the element."""

class TangentResult(TypedDict):
    tangents: npt.NDArray[np.float32]       # (corners, 4): x, y, z, w
    corner_vertex: npt.NDArray[np.uint32]   # (corners,)
    report: dict[str, Any]

def compute_tangents(
    positions: npt.ArrayLike,
    normals: npt.ArrayLike,
    uvs: npt.ArrayLike,
    indices: npt.ArrayLike,
    *,
    method: str = "mikktspace",
    weighting: str = "angle",
    threads: int = 0,
    uv_origin: str = "top-left",
) -> TangentResult: ...

def bake(
    input: PathLike,
    output: PathLike,
    *,
    method: str = "mikktspace",
    weighting: str = "angle",
    threads: int = 0,
    all: bool = False,
    overwrite: bool = False,
    asset_root: Optional[PathLike] = None,
    tangent_format: str = "float",
    normals: str = "flat",
    crease_angle: float = 60.0,
    keep_external: bool = False,
) -> dict[str, Any]: ...

def check(
    path: PathLike,
    *,
    method: str = "mikktspace",
    tolerance: float = 1.0,
    all: bool = False,
    asset_root: Optional[PathLike] = None,
    only: Optional[list[str]] = None,
    ignore: list[str] = ...,
    allow_missing: bool = False,
    orthogonal_tolerance: Optional[float] = None,
    reference_tolerance: Optional[float] = None,
    reference: Optional[str] = None,
    min_coverage: float = 0.5,
) -> dict[str, Any]: ...

def bake_tree(
    input_folder: PathLike,
    output_folder: PathLike,
    *,
    method: str = "mikktspace",
    weighting: str = "angle",
    threads: int = 0,
    all: bool = False,
    overwrite: bool = False,
    asset_root: Optional[PathLike] = None,
    force: bool = False,
    tangent_format: str = "float",
    normals: str = "flat",
    crease_angle: float = 60.0,
    keep_external: bool = False,
) -> list[dict[str, Any]]: ...

def release_cached_workspaces() -> None: ...
def cached_workspace_bytes() -> int: ...
def find_inputs(folder: PathLike) -> list[str]: ...

def input_digest(input: PathLike, *, asset_root: Optional[PathLike] = None) -> str: ...
def manifest_digest(input: PathLike, *, asset_root: Optional[PathLike] = None, previous: Optional[dict[str, Any]] = None,
                    verify: bool = False) -> tuple[str, list[dict[str, Any]]]: ...
