#!/bin/bash
# One vksky sequence over GNU parallel: the same parts as vksky-array.sbatch, PARTS jobs at once on this machine (or
# on others with parallel's --sshlogin, given in VKSKY_PARALLEL_OPTS; each then needs vksky and the output directory).
#
#   tools/farm/vksky-parallel.sh 4 --animate time=5:7 --frame-count 240 --render 'sunrise_%04d.exr'
#
# Every job runs with --skip-existing, so running the same line again after an interruption renders only what is
# missing. VKSKY names the vksky binary (default: vksky on PATH). Exit status: 0 when every part succeeded.
set -eu
parts=${1:?usage: vksky-parallel.sh PARTS VKSKY_FLAGS...}
shift
count=
prev=
for a in "$@"; do
    case $a in --frame-count=*) count=${a#*=} ;; esac
    [ "$prev" = --frame-count ] && count=$a
    prev=$a
done
case $parts$count in *[!0-9]* | '') echo "vksky-parallel: expected PARTS and --frame-count N as whole numbers" >&2; exit 2 ;; esac
ranges=()
for ((k = 0; k < parts; ++k)); do
    first=$((k * count / parts)) last=$(((k + 1) * count / parts - 1))
    [ "$last" -ge "$first" ] && ranges+=("$first:$last")
done
# -q: each argument passed as it is (quoted for parallel's shell); --halt now,fail=1: one failed part stops the others
# (the frames they wrote stay whole) and parallel exits non-zero.
# shellcheck disable=SC2086 # VKSKY_PARALLEL_OPTS is a list of parallel's own options
printf '%s\n' "${ranges[@]}" | parallel --will-cite -q --halt now,fail=1 -j "$parts" ${VKSKY_PARALLEL_OPTS:-} \
    "${VKSKY:-vksky}" "$@" --frame-range {} --skip-existing
