#!/usr/bin/env bash
# vksky post chain measurements (branch post): per-pass medians of --bench 60 (60 frames after warm-up),
# fragment vs compute post, 720p/1080p/2160p, medium / lesson, the fill floor in the same run;
# then compute-vs-fragment image comparison and validation runs on the GPU.
source .gpu-post/env.sh
set -u
O=$OUT
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > $O/gpu.txt 2>&1
vksky --list-devices > $O/devices.txt 2>&1
# warm-up: ~1 s of work
vksky --bench 300 --width 3840 --height 2160 --quality lesson --post-pass compute > /dev/null 2>&1
for size in 1280x720 1920x1080 3840x2160; do
  w=${size%x*}; h=${size#*x}
  for q in medium lesson; do
    for pp in fragment compute; do
      vksky --bench 60 --width $w --height $h --quality $q --post-pass $pp > $O/bench_${q}_${pp}_${size}.txt 2>&1
    done
    vksky --bench 60 --width $w --height $h --quality $q --post-pass compute --bloom-downsample levels > $O/bench_${q}_levels_${size}.txt 2>&1
  done
  vksky --bench 60 --width $w --height $h --sky-mode fill --sky-pass compute --post-pass compute --no-bloom > $O/bench_fill_${size}.txt 2>&1
  vksky --bench 60 --width $w --height $h --sky-mode fill --sky-pass compute --post-pass compute > $O/bench_fillpost_${size}.txt 2>&1
  # the default (--quality auto: medium at the default view)
  vksky --bench 60 --width $w --height $h > $O/bench_default_${size}.txt 2>&1
done
# the single pass's cost by chain length (1080p medium)
for m in 1 2 3 4; do
  vksky --bench 60 --width 1920 --height 1080 --quality medium --post-pass compute --bloom-mips $m > $O/bench_spd_mips${m}_1920x1080.txt 2>&1
  vksky --bench 60 --width 1920 --height 1080 --quality medium --post-pass compute --bloom-downsample levels --bloom-mips $m > $O/bench_levels_mips${m}_1920x1080.txt 2>&1
done
# repeat 1080p medium twice more (run-to-run spread)
for r in 2 3; do for pp in fragment compute; do
  vksky --bench 60 --width 1920 --height 1080 --quality medium --post-pass $pp > $O/bench_medium_${pp}_1920x1080_r$r.txt 2>&1
done
  vksky --bench 60 --width 1920 --height 1080 --quality medium --post-pass compute --bloom-downsample levels > $O/bench_medium_levels_1920x1080_r$r.txt 2>&1
done
# compute vs fragment on the GPU (validation + sync validation on every render)
for case in "1920 1080 3 lesson" "3840 2160 8 medium" "97 61 5 lesson"; do
  set -- $case
  for pp in fragment compute; do
    extra=""
    vksky --validate --post-pass $pp --width $1 --height $2 --sun-elevation $3 --quality $4 --render $O/c_$pp.exr --render $O/c_$pp.png > $O/val_${pp}_$1.txt 2>&1; echo "rc=$?" >> $O/val_${pp}_$1.txt
    vksky --validate --post-pass $pp --width $1 --height $2 --sun-elevation $3 --quality $4 --no-bloom --render $O/c_$pp-nb.exr >> $O/val_${pp}_$1.txt 2>&1; echo "rc=$?" >> $O/val_${pp}_$1.txt
  done
  post_compare $O/c_fragment.exr $O/c_compute.exr $O/c_fragment-nb.exr $O/c_compute-nb.exr $O/c_fragment.png $O/c_compute.png 0.02 0.02 2 0.25 > $O/compare_$1x$2.txt 2>&1; echo "rc=$?" >> $O/compare_$1x$2.txt
done
rm -f $O/c_*.exr $O/c_*.png
vksky --validate --bench 5 --width 1920 --height 1080 --post-pass compute > $O/val_bench_compute.txt 2>&1; echo "rc=$?" >> $O/val_bench_compute.txt
for s in "1 1" "7 3" "2 600"; do set -- $s; vksky --validate --post-pass compute --width $1 --height $2 --render $O/t.exr >> $O/val_tiny.txt 2>&1; echo "$1x$2 rc=$?" >> $O/val_tiny.txt; done
rm -f $O/t.exr
# the per-level compute downsample against the fragment chain too
for pp in fragment levels; do
  a="--post-pass compute --bloom-downsample levels"; [ $pp = fragment ] && a="--post-pass fragment"
  vksky --validate $a --width 1920 --height 1080 --sun-elevation 3 --quality lesson --render $O/c_$pp.exr --render $O/c_$pp.png > $O/val_lv_$pp.txt 2>&1; echo "rc=$?" >> $O/val_lv_$pp.txt
  vksky --validate $a --width 1920 --height 1080 --sun-elevation 3 --quality lesson --no-bloom --render $O/c_$pp-nb.exr >> $O/val_lv_$pp.txt 2>&1; echo "rc=$?" >> $O/val_lv_$pp.txt
done
post_compare $O/c_fragment.exr $O/c_levels.exr $O/c_fragment-nb.exr $O/c_levels-nb.exr $O/c_fragment.png $O/c_levels.png 0.02 0.02 2 0.25 > $O/compare_levels_1920x1080.txt 2>&1; echo "rc=$?" >> $O/compare_levels_1920x1080.txt
rm -f $O/c_*.exr $O/c_*.png
echo done > $O/done.txt
cd $O && tar czf /tmp/all.tgz *.txt && rm -f *.txt && mv /tmp/all.tgz $O/all.tgz
