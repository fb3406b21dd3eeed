#!/usr/bin/env bash
# tools/bench_compare.sh OLD NEW SCENE WxH FRAMES ROUNDS [flags...]: two vksky builds benchmarked in alternation (old, new, old, ...);
# prints each build's median sky and frame GPU ms over the rounds (docs/perf/profile_change.txt)
old=$1 new=$2 scene=$3 size=$4 frames=$5 rounds=$6; shift 6
w=${size%x*}; h=${size#*x}
tmp=$(mktemp)
for r in $(seq "$rounds"); do
  for b in old new; do
    exe=$old; [ $b = new ] && exe=$new
    "$exe" --scene "$scene" --bench "$frames" --width "$w" --height "$h" "$@" | awk -v b=$b '$1=="pass" && $2=="sky" {s=$4} $1=="frame" {f=$3} END {print b, s, f}' >> "$tmp"
  done
done
med() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
for b in old new; do
  echo "$b sky median $(awk -v b=$b '$1==b{print $2}' "$tmp" | med) ms, frame median $(awk -v b=$b '$1==b{print $3}' "$tmp" | med) ms; sky rounds: $(awk -v b=$b '$1==b{printf "%s ", $2}' "$tmp")"
done
rm -f "$tmp"
