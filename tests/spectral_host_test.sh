#!/usr/bin/env bash
# --spectral N through include/vksky.h (issue 25s, app/runs/spectral_host.c). Every run has --validate (validation +
# synchronization validation): any message fails it.
#  - a sequence on a renderer per group (VKSKY_SPECTRAL_SHARED=0: every group of a frame in one command buffer, each
#    renderer keeping its LUTs, a GPU's choice) writes the same files, byte for byte, as on one renderer given each
#    group's scene in turn (=1: a submission per group, the LUTs computed per group, lavapipe's choice): two ways of
#    submitting the same passes, with the sun animated (LUTs kept) and with a medium animated (LUTs recomputed);
#  - per group, a sequence that moves only the sun computes the medium's LUTs once ("LUTs reused" after frame 0), and
#    one that animates the aerosol computes them every frame;
# Usage: spectral_host_test.sh path/to/vksky
set -u
VKSKY=$(readlink -f "${1:?usage: spectral_host_test.sh path/to/vksky}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
size=(--width 48 --height 27)

run() { # tag shared args...
  local tag=$1 shared=$2; shift 2
  mkdir -p "$work/$tag"
  # Relative paths: the EXR header records the command line, the same in both directories.
  (cd "$work/$tag" && VKSKY_SPECTRAL_SHARED=$shared "$VKSKY" --validate "${size[@]}" "$@" --render f_%d.exr \
      --render f_%d.png >"$work/$tag.out" 2>"$work/$tag.err") || fail "$tag: exit $?: $(tail -1 "$work/$tag.err")"
  grep -qi validation "$work/$tag.err" && fail "$tag: validation message: $(grep -i validation "$work/$tag.err" | head -1)"
}
sums() { (cd "$work/$1" && md5sum f_*); }

run sun_groups 0 --spectral 8 --frame-count 3 --animate sun-elevation=-2:20
run sun_shared 1 --spectral 8 --frame-count 3 --animate sun-elevation=-2:20
[ "$(sums sun_groups)" = "$(sums sun_shared)" ] || fail "sun animated: a renderer per group and one renderer differ"
[ "$(grep -c 'LUTs reused' "$work/sun_groups.err")" = 2 ] ||
  fail "sun animated, a renderer per group: the medium's LUTs not kept: $(cat "$work/sun_groups.err")"
grep -q "LUTs computed 1 time$" "$work/sun_groups.err" || fail "sun animated: summary: $(tail -1 "$work/sun_groups.err")"

run mie_groups 0 --spectral 8 --pitch 30 --frame-count 2 --animate yaw=0:90 --animate mie-scale=1:3
run mie_shared 1 --spectral 8 --pitch 30 --frame-count 2 --animate yaw=0:90 --animate mie-scale=1:3
[ "$(sums mie_groups)" = "$(sums mie_shared)" ] || fail "aerosol animated: a renderer per group and one renderer differ"
grep -q "LUTs computed 2 times$" "$work/mie_groups.err" ||
  fail "aerosol animated: the LUTs not computed every frame: $(tail -1 "$work/mie_groups.err")"

[ "$(ls "$work"/*/f_* | wc -l)" = 20 ] || fail "files: $(ls "$work"/*/)"
[ $fails -eq 0 ] && echo "spectral_host: ok"
exit $((fails > 0))
