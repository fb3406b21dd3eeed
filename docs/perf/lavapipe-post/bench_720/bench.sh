#!/usr/bin/env bash
# lavapipe 1280x720: interleaved rounds of --bench 30 (process CPU ms a frame, wall ms a frame), the load average before each
V=/work/wt/post/build/vksky
O=${1:-/tmp/lp/out}; mkdir -p $O
cd /tmp/lp
for r in 1 2 3 4 5; do
  for c in "cpu|--quality cpu" "cpu_quarter|--quality cpu --bloom-res quarter" "cpu_nobloom|--quality cpu --no-bloom" "cpu_fill_nobloom|--quality cpu --sky-mode fill --no-bloom" "medium|--quality medium" "low|--quality low"; do
    n=${c%%|*}; a=${c#*|}
    { echo "== round $r: vksky --bench 30 --width 1280 --height 720 $a"; echo "loadavg_before $(cut -d' ' -f1-3 /proc/loadavg)"; $V --bench 30 --width 1280 --height 720 $a 2>&1; } >> $O/$n.txt
  done
done
echo done > $O/done.txt
