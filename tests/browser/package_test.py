# SPDX-License-Identifier: MIT
"""The npm package in headless Chromium, installed from its packed tarball into a new project.

Usage: package_test.py WORK_DIR TARBALL ARRAYS_TOOL ESBUILD

(b) native ES modules from a local http server: an import map names the package's "browser"
    export (read from its package.json), the page and a module worker import it;
(c) an esbuild browser bundle of the same page and worker (esbuild resolves the "browser"
    condition; a bundle that reaches for Node's fs/path fails to build).
Both compute the tangents of a quad and of a generated sphere (seam, mirrored half, slivers)
indexed and de-indexed; every corner must have the bits the C++ library gives on the same arrays
(tangent-arrays-tool).
(d) the threaded build (`libtangent-wasm/threads`, its "browser" export) on a page served
    cross-origin isolated (COOP/COEP): the same cases and a sphere of 51,200 triangles large
    enough that the core and the de-indexed sharing split their work, on all of maxThreads
    (at least 2); the same bits.
Exits 0 when all agree, 1 otherwise.
"""
import array
import base64
import json
import math
import pathlib
import random
import shutil
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import chromium  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
PAGE_TIMEOUT_S = 60


def quad():
    # Two triangles, UV origin in the top-left as glTF has it.
    return ([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0], [0, 0, 1] * 4, [0, 1, 1, 1, 1, 0, 0, 0], [0, 1, 2, 0, 2, 3])


def sphere(segments, seed):
    """A bumpy UV sphere with a seam, u mirrored on one half, and a few slivers."""
    rand = random.Random(seed)
    positions, normals, uvs = [], [], []
    for j in range(segments + 1):
        for i in range(segments + 1):
            u, v = i / segments, j / segments
            phi, theta = 2 * math.pi * u, math.pi * v
            r = 1 + 0.05 * rand.random()
            p = [r * math.sin(theta) * math.cos(phi), r * math.cos(theta), -r * math.sin(theta) * math.sin(phi)]
            length = math.sqrt(sum(c * c for c in p))
            positions += p
            normals += [c / length for c in p]
            uvs += [u if u < 0.5 else 1 - u, v]
    indices = []
    for j in range(segments):
        for i in range(segments):
            a = j * (segments + 1) + i
            b, c = a + 1, a + segments + 1
            indices += [a, c + 1, b, a, c, c + 1]
    triangles = len(indices) // 3
    for k in range(3):  # a line, a point
        t = rand.randrange(triangles)
        indices[3 * t + 2] = indices[3 * t + 1]
        t = rand.randrange(triangles)
        indices[3 * t + 1] = indices[3 * t + 2] = indices[3 * t]
    return positions, normals, uvs, indices


def write_case(folder, positions, normals, uvs, indices):
    folder.mkdir(parents=True)
    for name, code, values in (("positions.f32", "f", positions), ("normals.f32", "f", normals), ("uvs.f32", "f", uvs),
                               ("indices.u32", "I", indices)):
        (folder / name).write_bytes(array.array(code, values).tobytes())


def library(tool, folder, positions, normals, uvs, indices, origin):
    """The C++ library's tangent per corner (float32 xyzw bytes) on these arrays."""
    write_case(folder, positions, normals, uvs, indices)
    subprocess.run([tool, str(folder), "mikktspace", origin], check=True, stdout=subprocess.DEVNULL)
    return (folder / "tangents.f32").read_bytes()


def deindexed(positions, normals, uvs, indices):
    pick = lambda values, width: [x for v in indices for x in values[width * v:width * v + width]]  # noqa: E731
    return pick(positions, 3), pick(normals, 3), pick(uvs, 2), list(range(len(indices)))


def run_page(browser, url, label):
    page = browser.open(url)
    state = page.wait_for("document.body && document.body.dataset.state", PAGE_TIMEOUT_S)
    if state != "done":
        raise RuntimeError(f"{label}: {state}\npage console:\n  " + "\n  ".join(page.console))
    return json.loads(page.evaluate("document.body.dataset.result"))


def compare(label, result, references):
    failures = 0
    for name, expected in references.items():
        for kind in ("indexed", "deindexed"):
            ours = base64.b64decode(result[name][kind])
            theirs = expected[kind]
            corners = len(theirs) // 16
            same = sum(ours[16 * c:16 * c + 16] == theirs[16 * c:16 * c + 16] for c in range(corners))
            ok = len(ours) == len(theirs) and same == corners
            print(f"{'ok  ' if ok else 'FAIL'} {label}: {name} {kind}: {same} of {corners} corners bit-identical to the C++ library")
            failures += not ok
    return failures


def main():
    work, tarball, tool, esbuild = (pathlib.Path(a).resolve() for a in sys.argv[1:5])
    shutil.rmtree(work, ignore_errors=True)
    project = work / "project"
    project.mkdir(parents=True)
    subprocess.run(["npm", "init", "-y"], cwd=project, check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["npm", "install", "--prefer-offline", "--no-audit", "--no-fund", "--loglevel=error", str(tarball)],
                   cwd=project, check=True)

    cases = {"quad": quad(), "sphere": sphere(24, 7)}
    references = {}
    for name, mesh in cases.items():
        write_case(project / "cases" / name, *mesh)
        references[name] = {"indexed": library(tool, work / "library" / name / "indexed", *mesh, "top-left"),
                            "deindexed": library(tool, work / "library" / name / "deindexed", *deindexed(*mesh), "bottom-left")}
    (project / "cases.json").write_text(json.dumps(list(cases)))
    large = sphere(160, 9)
    write_case(project / "cases" / "large", *large)
    references["large"] = {"indexed": library(tool, work / "library" / "large" / "indexed", *large, "top-left"),
                           "deindexed": library(tool, work / "library" / "large" / "deindexed", *deindexed(*large), "bottom-left")}
    (project / "threads.json").write_text(json.dumps([*cases, "large"]))
    for name in ("cases.mjs", "package_page.mjs", "package_worker.mjs", "threads_page.mjs"):
        shutil.copy(HERE / name, project / name)

    # (b) Native: the import map a user writes, from the installed package's "browser" export.
    installed = project / "node_modules" / "libtangent-wasm"
    browser_entry = json.loads((installed / "package.json").read_text())["exports"]["."]["browser"]
    module_path = "./node_modules/libtangent-wasm/" + browser_entry.removeprefix("./")
    (project / "native_worker.mjs").write_text(
        (HERE / "package_worker.mjs").read_text().replace("'libtangent-wasm'", f"'{module_path}'"))  # workers have no import map
    (project / "native.html").write_text(
        '<!doctype html><html><head><meta charset="utf-8"><title>native ESM</title>'
        f'<script type="importmap">{json.dumps({"imports": {"libtangent-wasm": module_path}})}</script>'
        '<script type="module" src="./package_page.mjs"></script></head>'
        '<body data-worker="./native_worker.mjs"></body></html>\n')

    # (c) Bundled for the browser by esbuild.
    subprocess.run([str(esbuild), "package_page.mjs", "package_worker.mjs", "--bundle", "--platform=browser", "--format=esm",
                    "--outdir=bundle", "--log-level=warning"], cwd=project, check=True)
    bundle = (project / "bundle" / "package_page.js").read_text()
    if "tangent_wasm.cjs" in bundle or "__dirname" in bundle:
        print("FAIL the esbuild bundle took the Node build")
        return 1
    (project / "bundled.html").write_text(
        '<!doctype html><html><head><meta charset="utf-8"><title>esbuild bundle</title>'
        '<script type="module" src="./bundle/package_page.js"></script></head>'
        '<body data-worker="./bundle/package_worker.js"></body></html>\n')

    # (d) The threaded build on a cross-origin isolated page, by its own import map.
    threads_entry = json.loads((installed / "package.json").read_text())["exports"]["./threads"]["browser"]
    threads_path = "./node_modules/libtangent-wasm/" + threads_entry.removeprefix("./")
    (project / "threads.html").write_text(
        '<!doctype html><html><head><meta charset="utf-8"><title>threads</title>'
        f'<script type="importmap">{json.dumps({"imports": {"libtangent-wasm/threads": threads_path}})}</script>'
        '<script type="module" src="./threads_page.mjs"></script></head><body></body></html>\n')

    failures = 0
    with chromium.serve(project) as base, chromium.Browser() as browser:
        for page, label in (("native.html", "native ESM"), ("bundled.html", "esbuild bundle")):
            result = run_page(browser, base + page, label)
            plain = {name: references[name] for name in cases}
            failures += compare(f"{label}, main thread", result["mainThread"], plain)
            failures += compare(f"{label}, module worker", result["worker"], plain)
    with chromium.serve(project, isolated=True) as base, chromium.Browser() as browser:
        result = run_page(browser, base + "threads.html", "threaded build")
        ok = result["isolated"] is True and result["maxThreads"] >= 2
        print(f"{'ok  ' if ok else 'FAIL'} threaded build: crossOriginIsolated {result['isolated']}, maxThreads {result['maxThreads']}")
        failures += not ok
        failures += compare(f"threaded build, {result['maxThreads']} threads", result["cases"], references)
    print("all passed" if failures == 0 else f"{failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
