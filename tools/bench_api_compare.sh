#!/usr/bin/env bash
# tools/bench_api_compare.sh OLD_VKSKY NEW_VKSKY [ROUNDS] [flags...]: `--bench` alone before and after it went through
# include/vksky.h (issue 25, app/runs/bench_host.c), on the device the run lands on. First one validated run of each
# build (validation + synchronization validation: any message fails, exit 1), then ROUNDS (default 5) alternating
# rounds of `--bench 60` at 1920x1080 (and --async-luts where the device has a second queue), and per build the
# median over the rounds of each report line's first figure. What to look at: the same lines in both; every pass
# should agree within the rounds' spread. Prints the device and driver.
# The tone map (issue 25u): the old path's own display image took the compute tone map on a GPU; the API's host image
# took the fragment one from 3b6fc0f's --bench (0.497 ms frame / 0.418 tonemap at 1080p on the H100 against 0.107 /
# 0.033), and since issue-25y --bench alone hands the renderer an R8G8B8A8_UNORM storage image with a
# vksky_display_config (AUTO), so the compute tone map again. To see it: OLD = a build of 3b6fc0f (fragment host tone
# map) or of 8c456b0 (the pre-API own display image), NEW = this build; expect NEW's `pass tonemap` near 0.033 ms and
# `frame gpu_ms` near 0.107 ms at 1080p on the H100.
set -u
OLD=${1:?usage: bench_api_compare.sh OLD_VKSKY NEW_VKSKY [ROUNDS] [flags...]}
NEW=${2:?}
ROUNDS=${3:-5}
shift $(( $# >= 3 ? 3 : 2 ))
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
A=(--width 1920 --height 1080 "$@")
"$NEW" --list-devices 2>&1 | head -3
command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
status=0
echo "tone map of NEW's --bench alone: compute on a GPU (vksky_display_config AUTO), fragment on a CPU device"
variants=("")
"$NEW" --bench 1 --width 64 --height 32 --async-luts >/dev/null 2>&1 && variants+=("--async-luts")
for v in "${variants[@]}"; do
    for b in OLD NEW; do
        exe=${!b}
        # shellcheck disable=SC2086
        if ! "$exe" --validate --bench 3 "${A[@]}" $v >"$work/validate.out" 2>"$work/validate.err"; then
            echo "$b $v: the validated run failed: $(tail -2 "$work/validate.err")"; status=1
        fi
    done
    : >"$work/rounds"
    for r in $(seq "$ROUNDS"); do
        for b in OLD NEW; do
            exe=${!b}
            # shellcheck disable=SC2086
            "$exe" --bench 60 "${A[@]}" $v | awk -v b=$b '
                $1 == "pass" {print b, "pass", $2, $4}
                $1 == "frame" && $2 == "gpu_ms" {print b, "frame", "gpu_ms", $3; print b, "frame", "wall_ms", $5}
                $1 == "frame" && $2 == "cpu_ms" {print b, "frame", "cpu_ms", $3}
                $1 == "frame_luts" {print b, "frame_luts", "wall_ms", $3}' >>"$work/rounds"
        done
    done
    echo "== --bench 60 ${A[*]} $v: medians over $ROUNDS rounds (ms)"
    python3 - "$work/rounds" <<'PY'
import sys, statistics, collections
rows = collections.OrderedDict()
for line in open(sys.argv[1]):
    b, kind, name, value = line.split()
    rows.setdefault((kind, name), {}).setdefault(b, []).append(float(value))
print(f"{'line':32s} {'old':>10s} {'new':>10s}")
for (kind, name), v in rows.items():
    med = lambda b: f"{statistics.median(v[b]):10.4f}" if b in v else f"{'-':>10s}"
    print(f"{kind + ' ' + name:32s} {med('OLD')} {med('NEW')}")
PY
done
exit $status
