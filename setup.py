# SPDX-License-Identifier: MIT
"""The compiled module libtangent._libtangent, built by the project's CMake for the target
libtangent_python alone (the core, the glTF layer and the module; no tools, viewer, tests or
benchmarks) and copied into the wheel beside python/libtangent (__init__.py, the stubs,
py.typed). The metadata is in pyproject.toml (the package layout is here: setuptools 66 calls
`[tool.setuptools]` beta); the version is CMakeLists.txt's `project(libtangent VERSION ...)`.

The CMake build lives in build-pip/ (override with LIBTANGENT_CMAKE_BUILD_DIR) and is kept
between installs, so that a second `pip install .` rebuilds only what changed; compilations go
through ccache where it is installed, as scripts/build.sh does, so that a fresh build folder or
another checkout reuses the objects of the project's own build. setuptools' own scratch
(build/lib.*, build/bdist.*, *.egg-info) goes under build-pip/ too, away from the CMake tree
build/."""
import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = pathlib.Path(__file__).resolve().parent


def project_version():
    text = (SOURCE / "CMakeLists.txt").read_text(encoding="utf-8")
    match = re.search(r"^project\(libtangent\s+VERSION\s+([0-9][0-9.]*)", text, flags=re.M)
    if not match:
        sys.exit("setup.py: no `project(libtangent VERSION ...)` in CMakeLists.txt")
    return match.group(1)


def cmake_build_dir():
    return pathlib.Path(os.environ.get("LIBTANGENT_CMAKE_BUILD_DIR", SOURCE / "build-pip")).resolve()


def cache_value(build_dir, name):
    cache = build_dir / "CMakeCache.txt"
    if not cache.is_file():
        return None
    match = re.search(rf"^{name}:[A-Z]+=(.*)$", cache.read_text(encoding="utf-8"), flags=re.M)
    return match.group(1) if match else None


class CMakeExtension(Extension):
    def __init__(self, name, target):
        super().__init__(name, sources=[])
        self.target = target


class BuildWithCMake(build_ext):
    def build_extension(self, ext):
        build_dir = cmake_build_dir()
        # The interpreter running the build (a venv's python resolves to the one it was made
        # from): the module is built for its headers and ABI.
        python = os.path.realpath(sys.executable)
        # A build folder configured from another checkout (a moved or copied tree) or for another
        # interpreter is configured afresh; one whose configuring did not finish, again. Else the
        # build itself reruns CMake where a CMakeLists.txt changed.
        home = cache_value(build_dir, "CMAKE_HOME_DIRECTORY")
        stale = home is not None and (pathlib.Path(home).resolve() != SOURCE or cache_value(build_dir, "Python_EXECUTABLE") != python)
        generated = (build_dir / "build.ninja").is_file() or (build_dir / "Makefile").is_file()
        if stale or not generated:
            self.configure(build_dir, python, fresh=home is not None)
        jobs = self.parallel or os.cpu_count() or 1
        subprocess.run(["cmake", "--build", str(build_dir), "--target", ext.target, "--parallel", str(jobs)], check=True)
        built = sorted((build_dir / "python" / "libtangent").glob("_libtangent.*.so"))
        if len(built) != 1:
            sys.exit(f"setup.py: expected one compiled module in {build_dir}/python/libtangent, found {built}")
        destination = pathlib.Path(self.get_ext_fullpath(ext.name))
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], destination)
        # The build keeps its debug information (RelWithDebInfo, the flags of the project's own
        # build, hence the same code and ccache's objects); the wheel does not need it.
        if shutil.which("strip"):
            subprocess.run(["strip", "--strip-debug", str(destination)], check=True)

    def configure(self, build_dir, python, fresh):
        arguments = ["cmake", "-S", str(SOURCE), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=RelWithDebInfo",
                     f"-DPython_EXECUTABLE={python}", "-DTANGENT_BUILD_GLTF=ON", "-DTANGENT_BUILD_PYTHON=ON",
                     "-DTANGENT_BUILD_TOOLS=OFF", "-DTANGENT_BUILD_VIEWER=OFF", "-DTANGENT_BUILD_TESTS=OFF",
                     "-DTANGENT_BUILD_BENCHMARKS=OFF"]
        if fresh:
            arguments.append("--fresh")  # a new cache, as if the folder were empty (CMake 3.24)
        if shutil.which("ninja"):
            arguments += ["-G", "Ninja"]
        if shutil.which("ccache"):
            # As scripts/build.sh: paths relative to the folder above the checkout, so that the
            # objects of other build trees of these sources are reused.
            launcher = f"env;CCACHE_BASEDIR={SOURCE.parent};CCACHE_NOHASHDIR=true;ccache"
            arguments += [f"-DCMAKE_CXX_COMPILER_LAUNCHER={launcher}", f"-DCMAKE_C_COMPILER_LAUNCHER={launcher}"]
        subprocess.run(arguments, check=True)


def require_wheel_support():
    """setuptools before 70.1 builds wheels through the `wheel` package; without it the build
    ends in a bare "invalid command 'bdist_wheel'". Say what is missing and how to get it."""
    if not any(arg.startswith("bdist_wheel") for arg in sys.argv[1:]):
        return
    try:
        import setuptools.command.bdist_wheel  # noqa: F401  (setuptools 70.1 and later)
        return
    except ImportError:
        pass
    try:
        import wheel.bdist_wheel  # noqa: F401
    except ImportError:
        sys.exit(f"setup.py: building libtangent's wheel needs the `wheel` package, which {os.path.realpath(sys.executable)} "
                 "does not have (and no package index is used). Make the venv from Debian's interpreter, which has it "
                 "from python3-wheel: /usr/bin/python3 -m venv --system-site-packages .venv && "
                 ".venv/bin/pip install --no-build-isolation --no-index .")


require_wheel_support()
scratch = cmake_build_dir() / "setuptools"
scratch.mkdir(parents=True, exist_ok=True)
setup(
    version=project_version(),
    packages=["libtangent"],
    package_dir={"libtangent": "python/libtangent"},
    package_data={"libtangent": ["__init__.pyi", "py.typed"]},
    ext_modules=[CMakeExtension("libtangent._libtangent", target="libtangent_python")],
    cmdclass={"build_ext": BuildWithCMake},
    options={"build": {"build_base": str(scratch)}, "egg_info": {"egg_base": str(scratch)}},
)
