# SPDX-License-Identifier: MIT
"""The example page (wasm/examples/gltf-tangents) in headless Chromium, as a user builds it.

Usage: example_test.py SOURCE_DIR WORK_DIR TARBALL ARRAYS_TOOL GLB...

The example is copied into a new project whose libtangent-wasm is the packed tarball (the other
dependencies as the example's package-lock.json pins them), built by its own `npm run build` (esbuild) and
served on 127.0.0.1. The page bakes the demo quad (data/demo/quad.gltf with its .bin and images)
loaded by ?url= and chosen as files, each GLB chosen as a file, and copies of the quad and the first
GLB compressed by gltfpack -c (EXT_meshopt_compression, which the page reads through the npm
meshoptimizer decoder its package-lock pins, served with the page); what its download link holds
goes to tests/node/baked_vs_library.mjs: every corner's tangent must have the C++ library's bits,
the validator must find no error. A file that is not glTF must end in "error: FILE: ...".
"""
import base64
import json
import pathlib
import os
import shutil
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import chromium  # noqa: E402

PAGE_TIMEOUT_S = 120
# The page's state once it is done with a file ("ready" or "error: ..."); falsy before.
STATE = "!['busy', 'waiting'].includes(document.body.dataset.state) && document.body.dataset.state"
WAITING = "document.body.dataset.state === 'waiting'"
QUAD_FILES = ("quad.gltf", "quad.bin", "bumps_normal.png", "white.png", "specular_regions.png")
BAKED = ("fetch(document.getElementById('download').href).then((r) => r.arrayBuffer()).then((b) => {"
         " let s = ''; const u = new Uint8Array(b);"
         " for (let i = 0; i < u.length; i += 0x8000) s += String.fromCharCode(...u.subarray(i, i + 0x8000));"
         " return btoa(s); })")


def wait_state(page, label):
    state = page.wait_for(STATE, PAGE_TIMEOUT_S)
    if state != "ready":
        raise RuntimeError(f"{label}: {state}\npage console:\n  " + "\n  ".join(page.console))
    status = page.evaluate("document.getElementById('status').textContent")
    print(f"ok   {label}: {status}")
    return base64.b64decode(page.evaluate(BAKED))


def main():
    source, work, tarball, tool = (pathlib.Path(a).resolve() for a in sys.argv[1:5])
    glbs = [pathlib.Path(a).resolve() for a in sys.argv[5:]]
    example = source / "wasm" / "examples" / "gltf-tangents"
    shutil.rmtree(work, ignore_errors=True)
    project, out = work / "project", work / "out"
    project.mkdir(parents=True)
    out.mkdir()
    for name in ("index.html", "main.mjs", "package.json", "package-lock.json"):
        shutil.copy(example / name, project / name)
    manifest = json.loads((project / "package.json").read_text())
    manifest["dependencies"]["libtangent-wasm"] = f"file:{tarball}"
    (project / "package.json").write_text(json.dumps(manifest, indent=2))
    subprocess.run(["npm", "install", "--prefer-offline", "--no-audit", "--no-fund", "--loglevel=error"], cwd=project, check=True)
    subprocess.run(["npm", "run", "--silent", "build", "--", "--log-level=warning"], cwd=project, check=True)
    assets = project / "assets"
    assets.mkdir()
    for name in QUAD_FILES:
        shutil.copy(source / "data" / "demo" / name, assets / name)
    # meshopt-compressed copies (gltfpack from Debian; without it they are left out, and CI=true fails).
    if shutil.which("gltfpack"):
        for original in [assets / "quad.gltf", *glbs[:1]]:
            packed = work / f"{original.stem}.meshopt.glb"
            subprocess.run(["gltfpack", "-i", str(original), "-o", str(packed), "-c", "-noq"], check=True, capture_output=True)
            if b"EXT_meshopt_compression" not in packed.read_bytes()[:4096]:
                print(f"FAIL gltfpack -c wrote {packed.name} without EXT_meshopt_compression")
                return 1
            glbs.append(packed)
    elif os.environ.get("CI") == "true":
        print("FAIL (CI=true): gltfpack is not installed: no meshopt-compressed file tried")
        return 1
    else:
        print("SKIP meshopt-compressed files: gltfpack is not installed (scripts/install-deps.sh installs it)")
    not_gltf = work / "not-gltf.glb"
    not_gltf.write_bytes(b"glTF\x02\x00\x00\x00 this is not a binary glTF")

    baked = []
    with chromium.serve(project) as base, chromium.Browser() as browser:
        page = browser.open(base + "index.html?url=assets/quad.gltf")
        baked.append(("quad-url.glb", wait_state(page, "quad.gltf by ?url=")))
        page = browser.open(base + "index.html")
        page.wait_for(WAITING, PAGE_TIMEOUT_S)
        page.set_input_files("#files", [assets / name for name in QUAD_FILES])
        baked.append(("quad-files.glb", wait_state(page, "quad.gltf with its files, chosen")))
        for glb in glbs:
            page = browser.open(base + "index.html")
            page.wait_for(WAITING, PAGE_TIMEOUT_S)
            page.set_input_files("#files", [glb])
            baked.append((glb.name, wait_state(page, f"{glb.name}, chosen")))
        page = browser.open(base + "index.html")
        page.wait_for(WAITING, PAGE_TIMEOUT_S)
        page.set_input_files("#files", [not_gltf])
        state = page.wait_for(STATE, PAGE_TIMEOUT_S)
        if not state.startswith(f"error: {not_gltf.name}: "):
            print(f"FAIL a file that is not glTF gave state {state!r}")
            return 1
        print(f"ok   a file that is not glTF: {state}")

    for name, data in baked:
        (out / name).write_bytes(data)
    compare = subprocess.run(["node", "baked_vs_library.mjs", str(tool), str(work / "library"), *(str(out / n) for n, _ in baked)],
                             cwd=source / "tests" / "node")
    return compare.returncode


if __name__ == "__main__":
    sys.exit(main())
