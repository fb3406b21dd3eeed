#!/usr/bin/env bash
# tools/first_image.sh VKSKY [RUNS] [WIDTH HEIGHT]: the first image's latency (issue 27's goal: a 1920x1080 EXR in
# <= 0.25 s wall with warm caches). One warm-up run fills the pipeline and LUT caches (in a cache directory of its
# own, XDG_CACHE_HOME), then RUNS runs (default 6) of `VKSKY --render f.exr --width W --height H --timings`, the
# validation layer off (VKSKY_VALIDATION unset: the goal is the user's run, not the checked one). Prints each run's
# --timings stage table as one row, then the median of each stage and of the wall time seen from here (fork, exec and
# the process's exit included), and `exit` = wall - the table's total: what the process spends after its report
# (exit handlers, the drivers' unload, the kernel closing the device).
#
#   tools/first_image.sh build/vksky 6
#   ARGS="--exr-compression zip:6" tools/first_image.sh build/vksky 6    # extra flags for every run
#   VKSKY_TEARDOWN=1 tools/first_image.sh build/vksky 6                  # the full teardown, for an A/B of the cut
#
# Exit 0 (a benchmark, not a test: it checks nothing but that every run succeeded), 1 when a run fails, 2 on usage.
set -u
VKSKY=${1:?usage: first_image.sh VKSKY [RUNS] [WIDTH HEIGHT]}
RUNS=${2:-6}
W=${3:-1920}
H=${4:-1080}
case "$RUNS$W$H" in *[!0-9]*) echo "first_image.sh: RUNS, WIDTH and HEIGHT must be positive integers" >&2; exit 2 ;; esac
[ -x "$VKSKY" ] || { echo "first_image.sh: $VKSKY is not an executable" >&2; exit 2; }
unset VKSKY_VALIDATION VKSKY_LUT_CACHE
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export XDG_CACHE_HOME=$work/cache
read -r -a extra <<<"${ARGS:-}"

run() {   # run OUT_PREFIX: one render; its stderr into OUT_PREFIX.err, its wall ms into OUT_PREFIX.wall
    local start end
    start=$(date +%s%N)
    "$VKSKY" --render "$work/f.exr" --width "$W" --height "$H" --timings "${extra[@]}" >"$1.out" 2>"$1.err" ||
        { echo "first_image.sh: run failed: $(cat "$1.err")" >&2; exit 1; }
    end=$(date +%s%N)
    echo $(((end - start) / 1000)) | awk '{printf "%.1f\n", $1 / 1000}' >"$1.wall"
}

echo "# $("$VKSKY" --version) ${W}x$H EXR ${ARGS:-}; $(nproc) cores; $(date -u +%FT%TZ)"
"$VKSKY" --list-devices 2>/dev/null | sed 's/^/# /'
run "$work/warm"
grep -q 'LUT cache  hit' "$work/warm.err" && echo "# note: the warm-up found caches already (none expected)"
stages="exec options probe instance device cache pipelines setup frame encode write teardown total"
printf '%-4s' run
for s in $stages wall exit; do printf ' %9s' "$s"; done
printf '\n'
for i in $(seq 1 "$RUNS"); do
    run "$work/r$i"
    grep -q 'LUT cache  hit' "$work/r$i.err" || echo "# run $i: the LUT cache was not hit (caches not warm)"
    awk -v i="$i" -v stages="$stages" -v wall="$(cat "$work/r$i.wall")" '
        { v[$1] = $2 }
        END {
            n = split(stages, s, " "); printf "%-4s", i
            for (k = 1; k <= n; ++k) printf " %9s", (s[k] in v) ? v[s[k]] : "-"
            printf " %9.1f %9.1f\n", wall, wall - v["total"]
        }' "$work/r$i.err"
done | tee "$work/rows"
# Medians per column (the row's first field is the run number).
awk '{ for (k = 2; k <= NF; ++k) col[k, NR] = $k; nf = NF; nr = NR }
     END {
         printf "%-4s", "med"
         for (k = 2; k <= nf; ++k) {
             m = 0
             for (r = 1; r <= nr; ++r) if (col[k, r] != "-") a[++m] = col[k, r] + 0
             for (x = 2; x <= m; ++x) for (y = x; y > 1 && a[y - 1] > a[y]; --y) { t = a[y]; a[y] = a[y - 1]; a[y - 1] = t }
             if (m == 0) printf " %9s", "-"
             else printf " %9.1f", (m % 2) ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2
         }
         printf "\n"
     }' "$work/rows"
echo "# one run's table:"
sed 's/^/# /' "$work/r1.err"
