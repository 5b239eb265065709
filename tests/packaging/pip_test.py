#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The Python package as a pip user gets it, from a copy of the checkout (its tracked and
not-ignored files: no build folder, no venv):
  1. the ```bash blocks of the README's "## Python" section, as written, in the copy: the
     first makes the venv and pip-installs the package (timed; setup.py builds through ccache),
     the others run from that venv (the Dask example);
  2. from the venv, with no PYTHONPATH: the package is the venv's, `__version__` is the CMake
     project version, a small bake, and the README's ```python blocks in order;
  3. mypy --strict (Debian's `mypy`) on a snippet using the stubs passes, and on a snippet with
     type errors fails (so the stubs, not Any, were read);
  4. `python3 -m build --no-isolation --wheel` makes a wheel holding the package alone;
  5. `pip uninstall -y libtangent` leaves the venv's site-packages as a fresh venv's.
The README's ```sh blocks of that section (the build tree and `cmake --install`) are run by
tests/readme/run_python_blocks.py from the build tree.
Usage: pip_test.py SOURCE_DIR WORK_DIR PROJECT_VERSION
Exits 77 (skipped) when mypy is absent outside CI (CI=true: a failure)."""
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tarfile
import time
import zipfile

SKIPPED_EXIT_CODE = 77
source, work, project_version = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2]).resolve(), sys.argv[3]
checkout = work / "src"
venv_python = checkout / ".venv" / "bin" / "python"
# A machine with no package index: pip is given nothing to find packages in.
env = {name: value for name, value in os.environ.items() if not name.startswith("PIP_") and name != "PYTHONPATH"}
env["PATH"] = "/usr/bin:" + env.get("PATH", "")
env["PIP_NO_INDEX"] = "1"


def fail(message):
    sys.exit("FAIL: " + message)


def run(arguments, **options):
    print("$", " ".join(str(a) for a in arguments), flush=True)
    return subprocess.run([str(a) for a in arguments], env=env, check=True, **options)


def copy_checkout():
    """The checkout's files as git lists them (tracked, and new ones not ignored), into CHECKOUT."""
    listed = subprocess.run(["git", "-C", source, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                            check=True, capture_output=True).stdout.decode().split("\0")
    shutil.rmtree(work, ignore_errors=True)
    checkout.mkdir(parents=True)
    archive = work / "checkout.tar"
    with tarfile.open(archive, "w") as tar:
        for name in listed:
            if name and (source / name).is_file():  # a deleted tracked file is listed too
                tar.add(source / name, arcname=name, recursive=False)
    with tarfile.open(archive) as tar:
        tar.extractall(checkout)
    archive.unlink()


def python_section(readme):
    section = re.search(r"^## Python\n(.*?)^## ", readme, flags=re.S | re.M)
    if not section:
        fail("README.md has no '## Python' section")
    return section.group(1)


def site_packages(python):
    return pathlib.Path(subprocess.run([python, "-c", "import sysconfig; print(sysconfig.get_path('purelib'))"], env=env,
                                       check=True, capture_output=True, text=True).stdout.strip())


def files_under(folder):
    return {str(path.relative_to(folder)) for path in folder.rglob("*")}


copy_checkout()
readme = (checkout / "README.md").read_text(encoding="utf-8")
section = python_section(readme)
bash_blocks = re.findall(r"^```bash\n(.*?)^```", section, flags=re.S | re.M)
if not bash_blocks or "pip install" not in bash_blocks[0]:
    fail("the README's Python section does not start with a ```bash block that pip-installs the package")

# 1. The install, as the README writes it, then the other bash blocks from the venv.
for number, block in enumerate(bash_blocks, 1):
    started = time.monotonic()
    run(["bash", "-euo", "pipefail", "-c", block], cwd=checkout)
    print(f"README Python section bash block {number}: {time.monotonic() - started:.1f} s", flush=True)
    if number == 1 and not venv_python.exists():
        fail("the README's install block made no .venv in the checkout")

# 2. The venv's package: version, a small bake, the README's python blocks.
check = f"""
import pathlib, numpy as np, libtangent
assert pathlib.Path(libtangent.__file__).is_relative_to({str(checkout / '.venv')!r}), libtangent.__file__
assert libtangent.__version__ == {project_version!r}, (libtangent.__version__, {project_version!r})
quad = dict(positions=np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], np.float32),
            normals=np.array([[0, 0, 1]] * 4, np.float32), uvs=np.array([[0, 1], [1, 1], [1, 0], [0, 0]], np.float32),
            indices=np.array([[0, 1, 2], [0, 2, 3]], np.uint32))
assert np.allclose(libtangent.compute_tangents(**quad)["tangents"], [1, 0, 0, 1])
report = libtangent.bake("data/demo/demo.gltf", {str(work / 'demo-baked.glb')!r})
assert libtangent.check({str(work / 'demo-baked.glb')!r})["status"] == "clean"
print("venv package", libtangent.__version__, "at", libtangent.__file__, "baked", len(report["primitives"]), "primitives")
"""
run([venv_python, "-c", check], cwd=checkout)
blocks = re.findall(r"^```python\n(.*?)^```", readme, flags=re.S | re.M)
driver = """
import os, sys
os.makedirs("build/python-demo", exist_ok=True)
namespace = {}
for number, block in enumerate(sys.argv[1:], 1):
    print(f"--- README python block {number}", flush=True)
    exec(compile(block, f"README.md python block {number}", "exec"), namespace)
"""
run([venv_python, "-c", driver, *blocks], cwd=checkout)
print(f"{len(blocks)} README python blocks ran from the venv")

# 3. mypy --strict against the installed stubs.
mypy = shutil.which("mypy", path=env["PATH"])
mypy_skipped = None
if mypy is None:
    mypy_skipped = "mypy is absent (Debian package `mypy`): the stubs were not type-checked"
else:
    good = work / "typed_use.py"
    good.write_text("""import numpy as np
import numpy.typing as npt
from typing import Any

import libtangent

positions: npt.NDArray[np.float32] = np.zeros((3, 3), dtype=np.float32)
uvs = np.zeros((3, 2), dtype=np.float32)
result = libtangent.compute_tangents(positions, positions, uvs, np.arange(3, dtype=np.uint32), method="lengyel")
tangents: npt.NDArray[np.float32] = result["tangents"]
report: dict[str, Any] = libtangent.bake("in.gltf", "out.glb", threads=1)
entries: list[dict[str, Any]] = libtangent.bake_tree("in", "out")
version: str = libtangent.__version__
try:
    libtangent.check("in.glb", only=["tangents"])
except libtangent.InputError as error:
    message: str = str(error)
""")
    bad = work / "typed_misuse.py"
    bad.write_text("""import libtangent

tangents: int = libtangent.compute_tangents([], [], [], [])["tangents"]
libtangent.bake("in.gltf", "out.glb", threads="all")
libtangent.no_such_function()
""")
    mypy_args = [mypy, "--strict", "--python-executable", venv_python, "--cache-dir", work / "mypy-cache"]
    run([*mypy_args, good], cwd=work)
    misuse = subprocess.run([str(a) for a in [*mypy_args, bad]], env=env, cwd=work, capture_output=True, text=True)
    print(misuse.stdout, end="")
    if misuse.returncode == 0 or misuse.stdout.count("error:") < 3:
        fail("mypy --strict did not find the three errors of typed_misuse.py: the stubs were not read")
    print("mypy --strict: the stubs type the snippet, and catch its misuse")

# 4. A wheel, from the same checkout (its build folder build-pip/ is reused).
started = time.monotonic()
run(["/usr/bin/python3", "-m", "build", "--no-isolation", "--wheel", "--outdir", work / "dist", checkout], cwd=work)
wheels = list((work / "dist").glob("libtangent-*.whl"))
if len(wheels) != 1:
    fail(f"python3 -m build made {wheels}, not one wheel")
with zipfile.ZipFile(wheels[0]) as wheel:
    names = sorted(wheel.namelist())
package_files = sorted(re.sub(r"\.cpython-.*\.so$", ".so", n) for n in names if not n.startswith(f"libtangent-{project_version}.dist-info/"))
if package_files != ["libtangent/__init__.py", "libtangent/__init__.pyi", "libtangent/_libtangent.so", "libtangent/py.typed"]:
    fail(f"the wheel holds {names}")
print(f"wheel {wheels[0].name} ({wheels[0].stat().st_size // 1024} KiB) in {time.monotonic() - started:.1f} s: {names}")
stray = [p.name for p in checkout.glob("*.egg-info")] + [p.name for p in (checkout / "build").glob("*") if p.name.startswith(("lib.", "bdist.", "temp."))]
if stray:
    fail(f"setuptools left {stray} in the checkout instead of build-pip/")

# 4b. An interpreter without the `wheel` package (as a venv of a non-Debian Python has none and
# no index to fetch it from): setup.py says what is missing and the command that works, instead
# of setuptools' bare "invalid command 'bdist_wheel'".
without_wheel = subprocess.run(
    ["/usr/bin/python3", "-c", "import runpy, sys; sys.modules['wheel'] = sys.modules['wheel.bdist_wheel'] = None; "
     "sys.argv = ['setup.py', 'bdist_wheel']; runpy.run_path('setup.py', run_name='__main__')"],
    cwd=checkout, capture_output=True, text=True, timeout=120)
if without_wheel.returncode == 0 or "needs the `wheel` package" not in without_wheel.stderr or \
        "/usr/bin/python3 -m venv --system-site-packages" not in without_wheel.stderr:
    fail(f"setup.py bdist_wheel without `wheel`: exit {without_wheel.returncode}, {without_wheel.stderr[-2000:]}")
print("setup.py without the wheel package:", without_wheel.stderr.strip().splitlines()[-1][:120])

# 5. Uninstall: the venv's site-packages as a fresh venv's.
installed = site_packages(venv_python)
run([venv_python, "-m", "pip", "uninstall", "-y", "libtangent"], cwd=work)
reference = work / "reference-venv"
run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", reference], cwd=work)
left = sorted(files_under(installed) - files_under(site_packages(reference / "bin" / "python")))
if left:
    fail(f"pip uninstall left {left} in {installed}")
print("pip uninstall left site-packages as a fresh venv's")

if mypy_skipped:
    if os.environ.get("CI") == "true":
        fail("CI=true, so a missing tool is a failure: " + mypy_skipped)
    print("SKIPPED:", mypy_skipped)
    sys.exit(SKIPPED_EXIT_CODE)
print("pip package: installed, used, typed, wheeled and uninstalled")
