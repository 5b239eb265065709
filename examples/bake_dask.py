#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Bake a folder tree of glTF/OBJ/PLY/OFF files on Dask's distributed scheduler.

    python3 examples/bake_dask.py INPUT_FOLDER OUTPUT_FOLDER [--workers N] [--scheduler ADDRESS]
                                   [--report report.json] [--method mikktspace] [--all] [--force]

Without --scheduler a LocalCluster of --workers processes (default 2, one thread each) runs on
this machine. With --scheduler tcp://host:8786 the files go to a running cluster (started with
`dask scheduler` and `dask worker tcp://host:8786 --nthreads 1` on each machine); every worker
must have the libtangent module and see INPUT_FOLDER and OUTPUT_FOLDER at the same paths (a
shared file system).

Each file is one task: libtangent.bake() with the GIL released, one thread per task (Dask
runs several tasks per worker in parallel). The output tree, OUTPUT_FOLDER/tangent-manifest.json
and the report are those of `tangent bake INPUT_FOLDER --recursive --out-dir OUTPUT_FOLDER`,
so a re-run (by either) skips what is unchanged, and one failure never stops the rest.
Exit code 1 when a file failed.
"""
import argparse
import json
import os
import pathlib
import sys

import libtangent

MANIFEST = "tangent-manifest.json"


def output_path(input_folder, output_folder, input_path):
    """The same relative path under the output folder; OBJ/PLY/OFF become .glb (as the CLI)."""
    relative = pathlib.Path(input_path).relative_to(input_folder)
    if relative.suffix.lower() in (".obj", ".ply", ".off"):
        relative = relative.with_suffix(".glb")
    return pathlib.Path(output_folder) / relative


def bake_one(input_path, output, options, previous, force, output_folder):
    """One task: skip when the manifest's record matches, else bake. Runs on a worker."""
    digest, stamps = libtangent.manifest_digest(input_path, asset_root=options.get("asset_root"), previous=previous)
    entry = {"input": str(input_path), "output": str(output), "digest": digest, "stamps": stamps}
    # Skipped while every file the last bake wrote is still there (the .bin, image copies too).
    written = [pathlib.Path(output_folder) / name for name in previous.get("written", [])] if previous else []
    if (not force and previous and previous.get("digest") == digest
            and (not previous.get("ok") or (os.path.exists(output) and all(p.exists() for p in written)))):
        entry["written"] = previous.get("written", [])
        entry.update(status="ok" if previous.get("ok") else "failed", unchanged=True)
        if not previous.get("ok"):
            entry["error"] = previous.get("error", "")
        return entry
    entry["unchanged"] = False
    try:
        report = libtangent.bake(input_path, output, threads=1, **options)
        entry["status"] = "ok"
        entry.update({k: v for k, v in report.items() if k not in ("input", "output", "status")})
    except libtangent.Error as error:
        entry.update(status="failed", error=str(error))
    return entry


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input_folder")
    parser.add_argument("output_folder")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster)")
    parser.add_argument("--report", help="write the per-file report (JSON) here")
    parser.add_argument("--force", action="store_true", help="bake everything, whatever the manifest says")
    # bake()'s options, from the option table the `tangent` command's come from (threads: each
    # worker runs one thread).
    baked = [row for row in libtangent.option_table()
             if "bake" in row["commands"] and "python" in row["front_ends"] and row["python"] != "threads"]
    for row in baked:
        if row["kind"] == "flag":
            parser.add_argument("--" + row["name"], action="store_true", help=row["help"])
        else:
            kind = {"integer": int, "number": float}.get(row["kind"], str)
            parser.add_argument("--" + row["name"], type=kind, choices=row["choices"] or None, default=row["default"],
                                help=row["help"])
    args = parser.parse_args(argv)

    from dask.distributed import Client, LocalCluster  # Debian: python3-distributed

    input_folder = pathlib.Path(args.input_folder).resolve()
    output_folder = pathlib.Path(args.output_folder).resolve()
    output_folder.mkdir(parents=True, exist_ok=True)
    options = {row["python"]: getattr(args, row["python"]) for row in baked}
    # The manifest's options record, as bake_tree() writes it: what changes outputs.
    manifest_options = libtangent.manifest_options(**options)
    manifest_path = output_folder / MANIFEST
    previous = {}
    if manifest_path.is_file():  # a FIFO or a folder there is not read (libtangent.write_file refuses it below)
        try:
            old = json.loads(manifest_path.read_text())
            if old.get("schema") == "libtangent-manifest/1" and old.get("options") == manifest_options:
                previous = old.get("files", {})
        except (ValueError, OSError):
            previous = {}

    inputs = [p for p in libtangent.find_inputs(input_folder)
              if not pathlib.Path(p).resolve().is_relative_to(output_folder)]
    cluster = None if args.scheduler else LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                                                       dashboard_address=None)
    with Client(args.scheduler or cluster) as client:
        futures = []
        for path in inputs:
            key = pathlib.Path(path).relative_to(input_folder).as_posix()
            output = output_path(input_folder, output_folder, path)
            futures.append(client.submit(bake_one, path, str(output), options, previous.get(key), args.force,
                                         str(output_folder), pure=False))
        entries = client.gather(futures)
    if cluster is not None:
        cluster.close()

    files = {}
    for entry in entries:
        key = pathlib.Path(entry["input"]).relative_to(input_folder).as_posix()
        record = {"digest": entry["digest"], "output": pathlib.Path(entry["output"]).relative_to(output_folder).as_posix(),
                  "ok": entry["status"] == "ok", "stamps": entry.pop("stamps")}
        # The files the bake wrote (or found in place), as the CLI's manifest lists them.
        written = entry.get("written")
        if written is None:
            written = [pathlib.Path(f).relative_to(output_folder).as_posix() for f in entry.get("filesWritten", [])]
        if entry["status"] == "ok" and written:
            record["written"] = written
        if entry["status"] != "ok":
            record["error"] = entry.get("error", "")
        files[key] = record
    manifest = {"schema": "libtangent-manifest/1", "options": manifest_options, "files": files}
    # Both written as the CLI writes them (whole or not at all, never through a link to another
    # kind of file, nor over a FIFO or a device): libtangent.write_file.
    try:
        libtangent.write_file(manifest_path, (json.dumps(manifest, indent=2) + "\n").encode())
        if args.report:
            libtangent.write_file(args.report, (json.dumps(entries, indent=2) + "\n").encode())
    except libtangent.Error as error:
        print("error:", error, file=sys.stderr)
        return 1
    baked = sum(e["status"] == "ok" and not e["unchanged"] for e in entries)
    unchanged = sum(e["unchanged"] for e in entries)
    failed = [e for e in entries if e["status"] != "ok"]
    for entry in failed:
        print("error:", entry["error"], file=sys.stderr)
    print(f"{baked} baked, {unchanged} unchanged, {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
