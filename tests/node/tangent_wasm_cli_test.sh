#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The package's command, tangent-wasm, as users break it, in a project where the package and
# glTF-Transform are installed (wasm_install_test.sh's): a .gltf written beside its input
# (glTF-Transform alone names the .bin after the input's and writes over it), outputs that are
# the input by a hard link, FIFOs, folders, links to other kinds of file, names of no glTF kind;
# inputs that are FIFOs or name files outside their folder; image files in the way. Each case:
# the exit status, what is said, and that no victim, input or temporary file is changed or left.
# Usage: tangent_wasm_cli_test.sh SOURCE_DIR PROJECT_DIR WORK_DIR GLB
set -euo pipefail
source_dir=$1 project=$2 work=$3 glb=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
cli=("$project/node_modules/.bin/tangent-wasm")
fails=0
bad() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
# expect STATUS PATTERN ARGS...: tangent-wasm ARGS exits STATUS and says PATTERN (a grep -E).
expect() {
  local status=$1 pattern=$2 said got=0
  shift 2
  said=$(timeout 120 "${cli[@]}" "$@" 2>&1) || got=$?
  [ "$got" = "$status" ] || bad "tangent-wasm $* exited $got, not $status: $said"
  grep -qE -- "$pattern" <<<"$said" || bad "tangent-wasm $* did not say /$pattern/: $said"
}
validate() { (cd "$source_dir/tests/node" && node validate.mjs "$work/$1" >/dev/null) || bad "the validator rejects $1"; }
inputs_intact() { (cd demo && md5sum --quiet -c ../demo.md5) || bad "$1"; }
no_temporaries() { if find "$work" -name '.*.tmp-*' | grep -q .; then bad "temporaries left: $(find "$work" -name '.*.tmp-*')"; fi; }

# 1. A .gltf beside its .gltf input, images included: the input's files as they were, the
# output's .bin named after it, every image the input has there kept.
cp -r "$source_dir/data/demo" demo
(cd demo && md5sum ./* >../demo.md5)
expect 0 "wrote .*/demo/out.gltf" demo/scene.gltf demo/out.gltf
inputs_intact "writing beside the input changed the input's files"
[ -f demo/out.bin ] || bad "no out.bin beside out.gltf"
validate demo/out.gltf
expect 1 "exists \(pass --force" demo/cube.gltf demo/out.gltf
expect 0 "wrote" demo/cube.gltf demo/out.gltf --force
inputs_intact "replacing an output beside the input changed the input's files"
validate demo/out.gltf

# 2. The input itself, by its name, another spelling of it, or a hard link: refused.
expect 1 "is the input" demo/cube.gltf demo/cube.gltf --force
expect 1 "is the input" demo/cube.gltf demo/../demo/cube.gltf --force
ln demo/cube.gltf demo/hard.gltf
expect 1 "is the input" demo/cube.gltf demo/hard.gltf --force
inputs_intact "an output that is the input changed it"

# 3. Outputs that are not regular files, or links to another kind of file: refused, untouched.
cp "$glb" in.glb
mkfifo fifo.glb
expect 1 "is a FIFO; not replaced" in.glb fifo.glb --force
[ -p fifo.glb ] || bad "the FIFO was replaced"
mkdir folder.glb
expect 1 "is a folder; not replaced" in.glb folder.glb --force
echo victim >victim.txt
for link in link.glb link.gltf; do
  ln -s victim.txt "$link"
  expect 1 "symbolic link to .*victim.txt, which does not end in" in.glb "$link" --force
  [ "$(cat victim.txt)" = victim ] || bad "$link: the link's target was written"
  [ -L "$link" ] || bad "$link: the link was replaced"
done
[ ! -e link.bin ] || bad "a .bin was written beside a refused link"
expect 2 "does not end in .glb or .gltf" in.glb out.txt
[ ! -e out.txt ] || bad "out.txt was written"
ln -s /dev/null null.glb
expect 1 "symbolic link to /dev/null, which does not end in .glb" in.glb null.glb --force
[ -L null.glb ] && [ -c /dev/null ] || bad "a link to /dev/null was replaced, or /dev/null was"
# A link to a name of the same kind not there yet: written there, the link kept.
ln -s real.glb same.glb
expect 0 "wrote" in.glb same.glb
[ -L same.glb ] && [ -f real.glb ] || bad "a link to an absent .glb was not followed"
validate real.glb
no_temporaries

# 4. Inputs: a FIFO (no reader waits on it), a folder, a buffer outside the asset's folder.
mkfifo input.glb
expect 1 "is a FIFO, not a glTF file" input.glb o.glb
expect 1 "is a folder, not a glTF file" demo o.glb
mkdir escape && sed 's#"uri" *: *"cube.bin"#"uri":"../in.glb"#' demo/cube.gltf >escape/cube.gltf
grep -q '"uri":"../in.glb"' escape/cube.gltf || bad "the escaping test input was not made"
expect 1 'buffers\[0\]\.uri "\.\./in\.glb" is not a file in the asset.s folder' escape/cube.gltf o.glb
[ ! -e o.glb ] || bad "an output was written from a refused input"

# 5. A .glb's embedded images written beside a .gltf; an image file of other bytes in the way is
# an existing output (nothing written without --force, replaced with it).
mkdir images
expect 0 "wrote" in.glb images/a.gltf
validate images/a.gltf
image=$(cd images && ls ./*.png | head -1)
[ -n "$image" ] || bad "no image was written beside images/a.gltf"
mkdir images2 && echo other >"images2/$image"
expect 1 "exists \(pass --force" in.glb images2/a.gltf
[ ! -e images2/a.gltf ] && [ ! -e images2/a.bin ] || bad "a refused .gltf output wrote some of its files"
[ "$(cat "images2/$image")" = other ] || bad "a refused output replaced an image"
expect 0 "wrote" in.glb images2/a.gltf --force
cmp -s "images/$image" "images2/$image" || bad "--force did not replace the image in the way"
no_temporaries

[ $fails = 0 ] || { echo "tangent-wasm: $fails failure(s)" >&2; exit 1; }
echo "tangent-wasm command: ok"
