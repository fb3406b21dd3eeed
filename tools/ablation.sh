#!/usr/bin/env bash
# tools/ablation.sh VKSKY [WIDTHxHEIGHT] [FRAMES]: what each scene preset and each feature costs.
# Prints a Markdown table: GPU ms per frame (median, `vksky --bench`) and submit-to-fence wall ms, for each shipped
# scene and for the default scene with one feature turned off (or on). The LUT passes are listed apart: they run
# only when the atmosphere changes.
set -euo pipefail
vksky=${1:?usage: ablation.sh path/to/vksky [WxH] [frames]}
size=${2:-1280x720}
frames=${3:-30}
here=$(cd "$(dirname "$0")/.." && pwd)
w=${size%x*}; h=${size#*x}
run() {  # label, flags...
    local label=$1; shift
    local out
    out=$("$vksky" --bench "$frames" --width "$w" --height "$h" "$@")
    local frame lut sky
    frame=$(awk '$1 == "frame" { print $3 " | " $5 }' <<<"$out")
    lut=$(awk '$1 == "pass" && $2 ~ /_lut$/ && $2 != "skyview_lut" { s += $4 } END { printf "%.3f", s }' <<<"$out")
    sky=$(awk '$1 == "pass" && ($2 == "sky" || $2 == "skyview_lut") { s += $4 } END { printf "%.3f", s }' <<<"$out")
    echo "| $label | $sky | $frame | $lut |"
}
echo "| configuration | sky ms | frame GPU ms | frame wall ms | LUTs (once) ms |"
echo "|---|---|---|---|---|"
for f in "$here"/scenes/*.json; do s=$(basename "$f" .json); run "scene $s" --scene "$f"; done
base=(--scene "$here/scenes/earth-clear.json")
run "earth-clear, no bloom" "${base[@]}" --no-bloom
run "earth-clear, no multi-scattering" "${base[@]}" --no-multiscatter
run "earth-clear, no sun disc" "${base[@]}" --no-sun-disc
run "earth-clear, no ozone" "${base[@]}" --ozone-scale 0
run "earth-clear, no aerosols (Mie)" "${base[@]}" --mie-scale 0
run "earth-clear, lit ground (albedo 0.3)" "${base[@]}" --ground-albedo 0.3,0.3,0.3
run "earth-clear, sky-view LUT (medium)" "${base[@]}" --quality medium
