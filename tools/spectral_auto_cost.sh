#!/usr/bin/env bash
# tools/spectral_auto_cost.sh VKSKY [RUNS] [OUTDIR]: what --quality auto's colour costs a still (issue 32;
# docs/spectral.md "Auto by the device's kind"). For the default 1920x1080 view (afternoon: auto picks 16 wavelengths
# on a GPU) and the same view at noon (sun 60 deg: 8), an EXR and an auto-exposed PNG, each rendered under auto and
# with --spectral 0 (RGB), warm (the LUT and pipeline caches filled by a first run), RUNS times (default 7), alternating;
# prints the median wall time of the whole process per case and the ratio auto / RGB, measured in the same run. Then one
# validated run of each auto case (any validation message is printed). The device is the first one vksky lists.
set -u
VKSKY=${1:?usage: spectral_auto_cost.sh VKSKY [RUNS] [OUTDIR]}
RUNS=${2:-7}
OUT=${3:-$(mktemp -d)}
mkdir -p "$OUT"
"$VKSKY" --list-devices | head -1
now() { date +%s.%N; }
declare -A times
cases=("afternoon exr" "afternoon png" "noon exr" "noon png")
args_of() {   # args_of VIEW FORMAT COLOUR
    local view=()
    [ "$1" = noon ] && view=(--sun-elevation 60)
    local colour=()
    [ "$3" = rgb ] && colour=(--spectral 0)
    echo "${view[*]} ${colour[*]} --render $OUT/$1_$3.$2"
}
for c in "${cases[@]}"; do
    set -- $c
    for colour in auto rgb; do "$VKSKY" $(args_of "$1" "$2" "$colour") >"$OUT/warm.log" 2>&1; done
done
for ((r = 0; r < RUNS; ++r)); do
    for c in "${cases[@]}"; do
        set -- $c
        for colour in auto rgb; do
            t0=$(now)
            "$VKSKY" $(args_of "$1" "$2" "$colour") >"$OUT/run.log" 2>&1 || { echo "FAIL: $c $colour"; cat "$OUT/run.log"; }
            t1=$(now)
            times["$1 $2 $colour"]+="$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }') "
        done
    done
done
median() { tr ' ' '\n' | grep . | sort -n | awk '{v[NR]=$1} END {print v[int((NR + 1) / 2)]}'; }
printf '%-16s %10s %10s %8s  %s\n' case "auto s" "RGB s" ratio "auto's pick"
for c in "${cases[@]}"; do
    set -- $c
    a=$(echo "${times["$1 $2 auto"]}" | median)
    b=$(echo "${times["$1 $2 rgb"]}" | median)
    pick=$("$VKSKY" $(args_of "$1" "$2" auto) 2>/dev/null | sed -n 's/.*picked --spectral \([0-9]*\).*/--spectral \1/p')
    printf '%-16s %10.3f %10.3f %8.2f  %s\n' "$c" "$a" "$b" "$(awk -v a="$a" -v b="$b" 'BEGIN { print a / b }')" "${pick:-RGB}"
done
for c in "${cases[@]}"; do
    set -- $c
    "$VKSKY" $(args_of "$1" "$2" auto) --validate >"$OUT/validate.log" 2>&1 || echo "FAIL: $c --validate: exit $?"
    grep -iE "validation|VUID|SYNC-HAZARD" "$OUT/validate.log" && echo "FAIL: $c: validation messages"
done
echo "validated: ${#cases[@]} auto cases"
