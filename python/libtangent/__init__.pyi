# SPDX-License-Identifier: MIT
"""Type stubs of the package libtangent, whose __init__.py re-exports the compiled module
libtangent._libtangent (python/module.cpp): see help(libtangent)."""
import os
from typing import Any, Literal, Optional, Sequence, TypedDict, Union

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
    method: Literal['mikktspace', 'lengyel', 'flat', 'meshopt'] = 'mikktspace',
    weighting: Literal['angle', 'area', 'uniform'] = 'angle',
    threads: int = 0,
    uv_origin: Literal['top-left', 'bottom-left'] = 'top-left',
) -> TangentResult: ...

def bake(
    input: PathLike,
    output: PathLike,
    *,
    method: Literal['mikktspace', 'lengyel', 'flat', 'meshopt'] = 'mikktspace',
    weighting: Literal['angle', 'area', 'uniform'] = 'angle',
    threads: int = 0,
    all: bool = False,
    overwrite: bool = False,
    asset_root: Optional[PathLike] = None,
    keep_external: bool = False,
    tangent_format: Literal['float', 'short', 'byte'] = 'float',
    normals: Literal['flat', 'smooth', 'keep'] = 'flat',
    crease_angle: float = 60.0,
) -> dict[str, Any]: ...

def check(
    path: PathLike,
    *,
    only: Optional[Sequence[str]] = None,
    ignore: Optional[Sequence[str]] = None,
    tolerance: float = 1.0,
    orthogonal_tolerance: Optional[float] = None,
    reference_tolerance: Optional[float] = None,
    min_coverage: float = 0.5,
    allow_missing: bool = False,
    method: Literal['mikktspace', 'lengyel'] = 'mikktspace',
    reference: Literal['mikktspace', 'lengyel/angle', 'lengyel/area', 'lengyel/uniform', 'flat', 'meshopt', 'lengyel'] = 'mikktspace',
    all: bool = False,
    asset_root: Optional[PathLike] = None,
    identify: bool = False,
) -> dict[str, Any]: ...

def check_tree(
    folder: PathLike,
    *,
    only: Optional[Sequence[str]] = None,
    ignore: Optional[Sequence[str]] = None,
    tolerance: float = 1.0,
    orthogonal_tolerance: Optional[float] = None,
    reference_tolerance: Optional[float] = None,
    min_coverage: float = 0.5,
    allow_missing: bool = False,
    method: Literal['mikktspace', 'lengyel'] = 'mikktspace',
    reference: Literal['mikktspace', 'lengyel/angle', 'lengyel/area', 'lengyel/uniform', 'flat', 'meshopt', 'lengyel'] = 'mikktspace',
    all: bool = False,
    asset_root: Optional[PathLike] = None,
    identify: bool = False,
) -> list[dict[str, Any]]: ...

def bake_tree(
    input_folder: PathLike,
    output_folder: PathLike,
    *,
    method: Literal['mikktspace', 'lengyel', 'flat', 'meshopt'] = 'mikktspace',
    weighting: Literal['angle', 'area', 'uniform'] = 'angle',
    threads: int = 0,
    all: bool = False,
    overwrite: bool = False,
    asset_root: Optional[PathLike] = None,
    keep_external: bool = False,
    force: bool = False,
    verify: bool = False,
    tangent_format: Literal['float', 'short', 'byte'] = 'float',
    normals: Literal['flat', 'smooth', 'keep'] = 'flat',
    crease_angle: float = 60.0,
) -> list[dict[str, Any]]: ...

def option_table() -> list[dict[str, Any]]: ...
def manifest_options(**options: Any) -> dict[str, Any]: ...
def release_cached_workspaces() -> None: ...
def cached_workspace_bytes() -> int: ...
def find_inputs(folder: PathLike) -> list[str]: ...
def write_file(path: PathLike, data: bytes) -> None: ...

def input_digest(input: PathLike, *, asset_root: Optional[PathLike] = None) -> str: ...
def manifest_digest(input: PathLike, *, asset_root: Optional[PathLike] = None, previous: Optional[dict[str, Any]] = None,
                    verify: bool = False) -> tuple[str, list[dict[str, Any]]]: ...
