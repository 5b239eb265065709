# SPDX-License-Identifier: MIT
"""Output targets that are not regular files, and output folders full of broken neighbours.

One rule for every path `tangent` writes (tangent::output::writeTargetOf): a regular file or a
name not yet there is replaced atomically; a symbolic link is followed and its target written,
the link kept, where the target's name ends in the name's own extension (else refused); a character device, a FIFO with a reader, or a name for a descriptor
(/dev/stdout, /proc/self/fd/N) is written in place and stays what it was; a block device, a
socket, a FIFO nobody reads and a folder are refused, naming the path. The device nodes are
made on a tmpfs mounted in a private mount namespace (never on the machine's own /dev).

Then the search for a free .bin name beside a .gltf output: a neighbour that cannot be read
(empty, truncated, huge, a link loop, a FIFO) never makes it run forever."""
import json
import os
import pathlib
import random
import socket
import subprocess
import threading

import pytest

from conftest import skip_or_fail
from test_outputs import (CLI, PNG, assert_gltf_pair_loads, assert_valid_glb, glb_bytes, gltf_bytes, grid, keeping_images, snapshot,
                          tangent, temporaries, with_external_image, write)


def in_namespace(tmp_path, script, timeout=120):
    """Runs `script` (sh) in a private mount namespace with $N a fresh tmpfs (device nodes work
    there), $A a small asset and $T the CLI: (exit status, stdout, stderr)."""
    nodes = tmp_path / "nodes"
    nodes.mkdir(exist_ok=True)
    doc, blob = grid(4)
    asset = write(tmp_path / "a.glb", glb_bytes(doc, blob))
    probe = subprocess.run(["unshare", "-m", "sh", "-c", f"mount -t tmpfs tmpfs '{nodes}' && mknod '{nodes}/p' c 1 3"],
                           capture_output=True)
    if probe.returncode != 0:
        skip_or_fail("device nodes on a private tmpfs need root and unshare: " + probe.stderr.decode(errors="replace").strip())
    done = subprocess.run(["unshare", "-m", "sh", "-c", f'mount -t tmpfs tmpfs "$N" && cd "$N" && {{ {script}\n}}'],
                          capture_output=True, timeout=timeout,
                          env={**os.environ, "N": str(nodes), "A": str(asset), "T": CLI})
    out, err = done.stdout.decode(errors="replace"), done.stderr.decode(errors="replace")
    assert "AddressSanitizer" not in err and "runtime error:" not in err, err
    return done.returncode, out, err


# Each command that writes a file the user names, with {} for that name.
WRITERS = {
    "bake --report": '"$T" bake "$A" -o "$N/o.glb" --report {}',
    "check -o": '"$T" check "$A" --allow-missing --format json -o {}',
}


@pytest.mark.parametrize("writer", WRITERS)
def test_a_character_device_is_written_in_place_and_stays_a_device(tmp_path, writer):
    command = WRITERS[writer].format('"$N/null"')
    status, out, err = in_namespace(tmp_path, f'mknod -m 666 null c 1 3 && {command}; echo "exit=$?"; stat -c %F null')
    assert "exit=0" in out, (out, err)
    assert out.strip().endswith("character special file"), out


@pytest.mark.parametrize("writer", WRITERS)
def test_a_full_character_device_fails_naming_it_and_stays_a_device(tmp_path, writer):
    command = WRITERS[writer].format('"$N/full"')
    status, out, err = in_namespace(tmp_path, f'mknod -m 666 full c 1 7 && {command}; echo "exit=$?"; stat -c %F full')
    assert "exit=0" not in out, (out, err)
    assert "/full" in err and "No space left on device" in err, err
    assert out.strip().endswith("character special file"), out


@pytest.mark.parametrize("writer", WRITERS)
def test_a_fifo_with_a_reader_gets_the_bytes_and_stays_a_fifo(tmp_path, writer):
    command = WRITERS[writer].format('"$N/fifo"')
    script = (f'mkfifo fifo && (cat fifo > got &) && sleep 0.2 && {command}; echo "exit=$?"; sleep 0.2; '
              'stat -c %F fifo; echo "---"; cat got')
    status, out, err = in_namespace(tmp_path, script)
    head, got = out.split("---\n", 1)
    assert "exit=0" in head and "fifo" in head, (out, err)
    report = json.loads(got)  # the whole report reached the reader
    assert report, got


@pytest.mark.parametrize("writer", WRITERS)
def test_a_fifo_nobody_reads_is_refused_at_once(tmp_path, writer):
    command = WRITERS[writer].format('"$N/fifo"')
    status, out, err = in_namespace(tmp_path, f'mkfifo fifo && {command}; echo "exit=$?"; stat -c %F fifo', timeout=60)
    assert "exit=0" not in out and "fifo" in out, (out, err)
    assert "/fifo" in err and "nobody reads" in err, err


@pytest.mark.parametrize("writer", WRITERS)
def test_a_link_to_a_regular_file_writes_its_target_and_stays_a_link(tmp_path, writer):
    command = WRITERS[writer].format('"$N/link.json"')
    script = (f'mkdir real && echo old > real/target.json && ln -s real/target.json link.json && {command}; echo "exit=$?"; '
              'readlink link.json; echo "---"; cat real/target.json')
    status, out, err = in_namespace(tmp_path, script)
    head, target = out.split("---\n", 1)
    assert "exit=0" in head and "real/target.json" in head, (out, err)
    assert json.loads(target), target


# A link whose target is not a file of the kind the name asks for (out.glb -> /etc/passwd, run as
# root in a pipeline) is refused: the target keeps its bytes, nothing is created beside it, the
# link stays. So is a link to a name not there yet of another kind, and a name without an
# extension through a link.
LINKED = {**WRITERS, "bake -o": '"$T" bake "$A" -o {} --overwrite -q'}


# (bake -o takes .glb and .gltf names only, so it meets the link to another kind as link.glb)
LINKS = [("link.json", "passwd"), ("link.glb", "passwd"), ("link", "passwd"), ("link.json", "report.txt")]


@pytest.mark.parametrize("writer, link, target", [(w, l, t) for w in WRITERS for l, t in LINKS] + [("bake -o", "link.glb", "passwd")])
def test_a_link_to_a_file_of_another_kind_is_refused_and_the_file_kept(tmp_path, writer, link, target):
    command = LINKED[writer].format(f'"$N/{link}"')
    script = (f'mkdir etc && printf "root:x:0:0::/root:/bin/sh\\n" > etc/{target} && ln -s etc/{target} {link} && '
              f'{command}; echo "exit=$?"; echo ---; readlink {link}; ls etc; cat etc/{target}')
    status, out, err = in_namespace(tmp_path, script)
    head, kept = out.split("---\n", 1)
    assert "exit=0" not in head, (out, err)
    assert f"/{link}: is a symbolic link to " in err and f"/etc/{target}, which does not end in " in err, err
    assert kept.split("\n") == [f"etc/{target}", target, "root:x:0:0::/root:/bin/sh", ""], out


@pytest.mark.parametrize("writer", LINKED)
def test_a_dangling_link_to_a_name_of_another_kind_creates_nothing(tmp_path, writer):
    link = "link.glb" if writer == "bake -o" else "link.json"
    command = LINKED[writer].format(f'"$N/{link}"')
    script = f'mkdir etc && ln -s etc/cron-job {link} && {command}; echo "exit=$?"; echo ---; ls etc | wc -l'
    status, out, err = in_namespace(tmp_path, script)
    head, count = out.split("---\n", 1)
    assert "exit=0" not in head and count == "0\n", (out, err)
    assert f"/{link}: is a symbolic link to " in err and "/etc/cron-job, which does not end in " in err, err


def test_a_glb_output_through_a_link_to_a_glb_replaces_the_target_with_a_glb(tmp_path):
    status, out, err = in_namespace(tmp_path, 'mkdir store && echo old > store/v1.glb && ln -s store/v1.glb o.glb && '
                                              '"$T" bake "$A" -o o.glb --overwrite -q; echo "exit=$?"; readlink o.glb; '
                                              'head -c 4 store/v1.glb; echo; ls store')
    assert out.split("\n")[:4] == ["exit=0", "store/v1.glb", "glTF", "v1.glb"], (out, err)


@pytest.mark.parametrize("name", ["link-to-stdout", "/dev/stdout", "/proc/self/fd/1"])
@pytest.mark.parametrize("writer", WRITERS)
def test_a_name_for_standard_output_writes_to_it(tmp_path, writer, name):
    target = '"$N/link"' if name == "link-to-stdout" else name
    command = WRITERS[writer].format(target)
    script = f'ln -s /proc/self/fd/1 link && {command} > "$N/captured"; echo "exit=$?"; readlink link; cat "$N/captured"'
    status, out, err = in_namespace(tmp_path, script)
    assert "exit=0" in out, (out, err)
    assert "/proc/self/fd/1" in out  # the link is still a link
    captured = out.split("/proc/self/fd/1\n", 1)[1]
    assert json_document_in(captured), captured  # the whole report, among the lines bake prints


def json_document_in(text):
    """The first JSON array or object that starts a line of `text` (None where there is none)."""
    for line_start in [0] + [i + 1 for i, c in enumerate(text) if c == "\n"]:
        if text[line_start:line_start + 1] in ("[", "{"):
            try:
                return json.JSONDecoder().raw_decode(text[line_start:])[0]
            except json.JSONDecodeError:
                continue
    return None


@pytest.mark.parametrize("writer", WRITERS)
def test_a_socket_is_refused_and_stays_a_socket(tmp_path, writer):
    command = WRITERS[writer].format('"$N/sock"')
    script = ("python3 -c 'import socket,time; s=socket.socket(socket.AF_UNIX); s.bind(\"sock\"); time.sleep(30)' & "
              f'sleep 0.5; {command}; echo "exit=$?"; stat -c %F sock; kill $!')
    status, out, err = in_namespace(tmp_path, script)
    assert "exit=0" not in out and "socket" in out, (out, err)
    assert "/sock" in err and "socket" in err, err


@pytest.mark.parametrize("writer", WRITERS)
def test_a_block_device_is_refused_and_never_opened(tmp_path, writer):
    command = WRITERS[writer].format('"$N/block"')
    status, out, err = in_namespace(tmp_path, f'mknod block b 7 200 && {command}; echo "exit=$?"; stat -c %F block')
    assert "exit=0" not in out and "block special file" in out, (out, err)
    assert "/block" in err and "block device" in err, err


@pytest.mark.parametrize("writer", WRITERS)
def test_a_read_only_folder_fails_naming_the_file(tmp_path, writer):
    command = WRITERS[writer].format('"$N/ro/out.json"')
    script = (f'mkdir ro && mount -t tmpfs tmpfs ro && mount -o remount,ro ro && {command}; echo "exit=$?"; ls -A ro | wc -l')
    status, out, err = in_namespace(tmp_path, script)
    assert "exit=0" not in out, (out, err)
    assert "ro/out.json" in err and "Read-only file system" in err, err
    assert out.strip().endswith("0")


def test_a_glb_output_onto_dev_null_like_device_keeps_the_node(tmp_path):
    status, out, err = in_namespace(tmp_path, 'mknod -m 666 sink.glb c 1 3 && "$T" bake "$A" -o "$N/sink.glb"; '
                                              'echo "exit=$?"; stat -c %F sink.glb')
    assert "exit=0" in out and out.strip().endswith("character special file"), (out, err)


# --- the free .bin name beside a .gltf output ------------------------------------------------------

def test_an_empty_glb_beside_a_gltf_output_does_not_stop_the_bake(tmp_path):
    doc, blob = grid(4)
    asset = write(tmp_path / "in" / "a.glb", glb_bytes(doc, blob))
    out = tmp_path / "out"
    write(out / "empty.glb", b"")  # what a failed `tangent bake x -o - > out.glb` leaves
    write(out / "broken.gltf", b'{"buffers": [')
    for run in range(2):  # the second run replaces the first's pair
        done = tangent("bake", asset, out / "o.gltf", timeout=60)
        assert done.returncode == 0, done.stderr
        doc = assert_gltf_pair_loads(out / "o.gltf")
    assert (out / "empty.glb").read_bytes() == b"" and (out / "broken.gltf").read_bytes() == b'{"buffers": ['
    assert temporaries(out) == []


def neighbour(rng, folder, index):
    """One random file beside the output: empty, truncated, huge (sparse), a link loop, a link
    to nowhere, a FIFO, a folder, or valid glTF naming a .bin of the output's stem."""
    kind = rng.choice(["empty", "truncated glb", "truncated gltf", "huge", "loop", "dangling", "fifo", "folder",
                       "names o.bin", "names o.3.bin", "claims a huge chunk"])
    name = folder / f"n{index}{rng.choice(['.gltf', '.glb'])}"
    if kind == "empty":
        name.write_bytes(b"")
    elif kind == "truncated glb":
        name.write_bytes(b"glTF\x02\0\0\0" + bytes(rng.randrange(0, 12)))
    elif kind == "truncated gltf":
        name.write_bytes(b'{"buffers": [{"uri": "o.bin"')
    elif kind == "huge":
        with open(name, "wb") as f:
            f.truncate(3 << 30)  # sparse: no disk used
    elif kind == "loop":
        os.symlink(name.name, name)
    elif kind == "dangling":
        os.symlink("nowhere.gltf", name)
    elif kind == "fifo":
        os.mkfifo(name)
    elif kind == "folder":
        name.mkdir()
    elif kind == "claims a huge chunk":
        name.write_bytes(b"glTF\x02\0\0\0\xff\xff\xff\x7f\xf0\xff\xff\x7fJSON{}")
    else:
        uri = "o.bin" if kind == "names o.bin" else "o.3.bin"
        name.write_text(json.dumps({"asset": {"version": "2.0"}, "buffers": [{"uri": uri, "byteLength": 4}]}))
    return kind


@pytest.mark.parametrize("seed", range(12))
def test_a_folder_of_random_broken_neighbours_never_hangs_a_gltf_output(tmp_path, seed):
    rng = random.Random(seed)
    doc, blob = grid(4)
    asset = write(tmp_path / "in" / "a.glb", glb_bytes(doc, blob))
    out = tmp_path / "out"
    out.mkdir()
    kinds = [neighbour(rng, out, i) for i in range(rng.randrange(1, 6))]
    named = {out / "o.bin"} if "names o.bin" in kinds else set()
    named |= {out / "o.3.bin"} if "names o.3.bin" in kinds else set()
    # Files of the stem's naming that exist already: the bin must go elsewhere, and stay.
    existing = {}
    for n in rng.sample(range(0, 5), rng.randrange(0, 3)):
        path = out / ("o.bin" if n == 0 else f"o.{n}.bin")
        existing[path] = os.urandom(8)
        path.write_bytes(existing[path])
    before = {p: (os.lstat(p).st_mode, os.lstat(p).st_size) for p in out.iterdir()}
    for run in range(2):
        done = tangent("bake", asset, out / "o.gltf", timeout=120)
        assert done.returncode == 0, (kinds, done.stderr)
        written = assert_gltf_pair_loads(out / "o.gltf")
        bin_name = out / written["buffers"][0]["uri"]
        assert bin_name not in existing and bin_name not in named, (kinds, bin_name)
    for path, (mode, size) in before.items():  # every neighbour as it was
        status = os.lstat(path)
        assert (status.st_mode, status.st_size) == (mode, size), (kinds, path)
    for path, data in existing.items():
        assert path.read_bytes() == data, (kinds, path)
    assert temporaries(out) == []


def test_a_gltf_output_through_a_link_puts_its_bin_beside_the_target(tmp_path):
    doc, blob = grid(4)
    asset = write(tmp_path / "in" / "a.glb", glb_bytes(doc, blob))
    (tmp_path / "real").mkdir()
    (tmp_path / "real" / "o.gltf").write_text("{}")
    (tmp_path / "links").mkdir()
    link = tmp_path / "links" / "o.gltf"
    link.symlink_to(tmp_path / "real" / "o.gltf")
    done = tangent("bake", asset, link)
    assert done.returncode == 0, done.stderr
    assert link.is_symlink() and os.readlink(link) == str(tmp_path / "real" / "o.gltf")
    assert_gltf_pair_loads(tmp_path / "real" / "o.gltf")  # its .bin beside it
    assert sorted(p.name for p in (tmp_path / "links").iterdir()) == ["o.gltf"]


# The batch's journal (tangent-manifest.journal in the output folder) is appended to in place:
# a link there was followed and its target truncated and rewritten, a FIFO there hung the run.
# Anything but a regular file stops the run before anything is baked, named; the link's target
# keeps its bytes.
@pytest.mark.parametrize("kind", ["link", "fifo", "folder"])
def test_a_batch_journal_that_is_not_a_regular_file_stops_the_run_naming_it(tmp_path, kind):
    doc, blob = grid(4)
    write(tmp_path / "tree" / "a.glb", glb_bytes(doc, blob))
    (tmp_path / "o").mkdir()
    victim = write(tmp_path / "victim.txt", b"precious\n")
    journal = tmp_path / "o" / "tangent-manifest.journal"
    if kind == "link":
        journal.symlink_to(victim)
    elif kind == "fifo":
        os.mkfifo(journal)
    else:
        journal.mkdir()
    done = tangent("bake", tmp_path / "tree", "--out-dir", tmp_path / "o", "--recursive", "-q", timeout=60)
    err = done.stderr.decode(errors="replace")
    assert done.returncode != 0, err
    assert f"{journal}: is a" in err and "nothing baked" in err, err
    assert victim.read_bytes() == b"precious\n"
    assert sorted(p.name for p in (tmp_path / "o").iterdir()) == ["tangent-manifest.journal"]


# The image copies bake puts beside its output go through the same rule: a link where a copy
# goes, to a file of another kind, was overwritten with the PNG; now the bake is refused naming
# it and writes nothing.
@pytest.mark.parametrize("suffix", [".glb", ".gltf"])
def test_an_image_copy_onto_a_link_to_another_kind_of_file_is_refused(tmp_path, suffix):
    doc, blob = grid(4)
    asset = write(tmp_path / "in" / "in.gltf", gltf_bytes(with_external_image(doc, uri="n.png"), blob))
    write(tmp_path / "in" / "n.png", PNG)
    victim = write(tmp_path / "victim.txt", b"precious\n")
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "n.png").symlink_to(victim)
    done = tangent("bake", asset, "-o", tmp_path / "out" / f"o{suffix}", *keeping_images(suffix))
    err = done.stderr.decode(errors="replace")
    assert done.returncode != 0, err
    assert "/out/n.png: is a symbolic link to " in err and "victim.txt, which does not end in .png" in err, err
    assert victim.read_bytes() == b"precious\n"
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["n.png"]
