#!/usr/bin/env bash
# lavapipe 1280x720 on a quiet 2-core machine (nothing else running): --quality cpu (quarter bloom) against --bloom-res half,
# (--frames 120 under Xvfb: steady fps and process CPU ms a frame), interleaved, the load average before each run.
V=${VKSKY:-/work/main/build/vksky}
O=${1:-/tmp/lp/quiet}; mkdir -p $O
cd /tmp/lp
for r in 1 2 3; do
  for c in "cpu|--quality cpu" "cpu_half|--quality cpu --bloom-res half"; do
    n=${c%%|*}; a=${c#*|}
    { echo "== round $r: vksky --bench 30 --width 1280 --height 720 $a"; echo "loadavg_before $(cut -d' ' -f1-3 /proc/loadavg)"; $V --bench 30 --width 1280 --height 720 $a 2>&1; } >> $O/bench_$n.txt
    { echo "== round $r: xvfb-run vksky --width 1280 --height 720 --frames 120 $a"; echo "loadavg_before $(cut -d' ' -f1-3 /proc/loadavg)"; timeout 300 xvfb-run -a -s "-screen 0 1280x720x24" $V --width 1280 --height 720 --frames 120 $a 2>&1 | grep -E 'frames|fps'; } >> $O/window_$n.txt
  done
done
echo done > $O/done.txt
