#!/usr/bin/env bash
# tools/plot_tradeoff.sh CSV PNG: the Pareto plot of a tools/tradeoff CSV (gnuplot, Debian package gnuplot-nox).
# x: sky GPU ms (median over the scenes), y: mean relative luminance error over the daytime scenes (twilight is
# listed in the README's table: every configuration's twilight error is the model's, not the knobs').
set -euo pipefail
csv=${1:?usage: plot_tradeoff.sh tradeoff.csv out.png}
png=${2:?usage: plot_tradeoff.sh tradeoff.csv out.png}
dat=$(mktemp)
awk -F, 'NR > 1 && $9 != "nan" {
    c = $2; ms[c] = ms[c] " " $6
    if ($3 != "twilight") { err[c] += $9; n[c]++ }
    if (!(c in order)) { order[c] = ++k; names[k] = c }
} END {
    for (i = 1; i <= k; ++i) {
        c = names[i]; m = split(substr(ms[c], 2), v, " ")
        for (a = 2; a <= m; ++a) for (b = a; b > 1 && v[b - 1] + 0 > v[b] + 0; --b) { t = v[b]; v[b] = v[b - 1]; v[b - 1] = t }
        med = m % 2 ? v[(m + 1) / 2] : (v[m / 2] + v[m / 2 + 1]) / 2
        preset = (c == "low" || c == "medium" || c == "high" || c == "ultra")
        printf "%g %g %s %d\n", med, 100 * err[c] / n[c], c, preset
    }
}' "$csv" > "$dat"
device=$(awk -F, 'NR == 2 { gsub(/"/, "", $1); print $1 " at " $4 "x" $5 }' "$csv")
gnuplot <<GP
set terminal pngcairo size 1000,620 font 'sans,10'
set output '$png'
set logscale xy
set grid
set xlabel 'sky GPU time per frame, ms (median over the scene set; sky-view LUT pass included)'
set ylabel 'mean relative luminance error vs the converged reference, %'
set title 'vksky speed/accuracy trade, $device (daytime scenes; presets in red)'
set key off
plot '$dat' using 1:2 with points pt 7 ps 1.2 lc rgb '#4060a0', \
     '' using 1:(\$4 == 1 ? \$2 : 1/0) with points pt 7 ps 2.2 lc rgb '#d04020', \
     '' using 1:2:3 with labels offset 0.7,0.5 left font 'sans,8'
GP
rm -f "$dat"
