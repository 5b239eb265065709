#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Runs the malformed-input table (make_cases.py) against the `tangent` command.

For every case and each of bake, check and info: the exit code the table gives; a message
naming the input file and containing the case's phrase; no output file and no temporary file
left behind; every file of the case byte for byte unchanged; done within a time limit (a hang
is a failure). Exits 1 listing every failure.

Usage: run_cases.py TANGENT CASES_DIR [--timeout SECONDS]
"""
import hashlib
import json
import os
import subprocess
import sys


def snapshot(folder):
    """name -> sha256 of every regular file (links and folders by name only)."""
    state = {}
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            path = os.path.join(root, name)
            rel = os.path.relpath(path, folder)
            if os.path.islink(path):
                state[rel] = "link:" + os.readlink(path)
            elif os.path.isdir(path):
                state[rel] = "dir"
            else:
                with open(path, "rb") as f:
                    state[rel] = hashlib.sha256(f.read()).hexdigest()
    return state


def main():
    args = sys.argv[1:]
    timeout = 60.0
    if "--timeout" in args:
        i = args.index("--timeout")
        timeout = float(args[i + 1])
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    tangent, cases_dir = args
    with open(os.path.join(cases_dir, "cases.json")) as f:
        cases = json.load(f)
    failures = []
    runs = 0
    for case in cases:
        folder = os.path.abspath(os.path.join(cases_dir, case["name"]))
        source = os.path.join(folder, case["input"])
        output = os.path.join(folder, "out", "baked.glb")
        commands = {
            "bake": [tangent, "bake", source, "-o", output, "--quiet"],
            "check": [tangent, "check", source],
            "info": [tangent, "info", source],
        }
        for command, argv in commands.items():
            expected_exit = case["exit"][command]
            before = snapshot(folder)
            runs += 1
            try:
                done = subprocess.run(argv, capture_output=True, timeout=timeout)
            except subprocess.TimeoutExpired:
                failures.append(f"{case['name']} {command}: no answer within {timeout:.0f} s (hang)")
                continue
            message = (done.stdout + done.stderr).decode(errors="replace")
            after = snapshot(folder)
            where = f"{case['name']} {command}"
            if done.returncode != expected_exit:
                failures.append(f"{where}: exit {done.returncode}, expected {expected_exit}\n    {message.strip()[:400]}")
            if done.returncode < 0:
                failures.append(f"{where}: killed by signal {-done.returncode}")
            if expected_exit != 0:
                if case["input"] not in message:
                    failures.append(f"{where}: the message does not name the file\n    {message.strip()[:400]}")
                for phrase in (case.get("expect"), case.get("expect2")):
                    if phrase and phrase not in message:
                        failures.append(f"{where}: the message lacks '{phrase}'\n    {message.strip()[:400]}")
                created = sorted(set(after) - set(before) - {"out"})
                if created:
                    failures.append(f"{where}: left files behind: {created}")
            if "AddressSanitizer" in message or "runtime error:" in message:
                failures.append(f"{where}: sanitizer report\n    {message.strip()[:800]}")
            changed = sorted(k for k in before if k in after and before[k] != after[k])
            if changed:
                failures.append(f"{where}: changed input files {changed}")
            if command == "bake" and os.path.isdir(os.path.join(folder, "out")):
                for name in os.listdir(os.path.join(folder, "out")):
                    os.remove(os.path.join(folder, "out", name))
                os.rmdir(os.path.join(folder, "out"))
    print(f"malformed inputs: {len(cases)} cases, {runs} runs, {len(failures)} failures")
    for failure in failures:
        print("FAIL " + failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
