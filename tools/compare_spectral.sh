#!/usr/bin/env bash
# tools/compare_spectral.sh OLD_VKSKY NEW_VKSKY: --spectral renders of two builds compared (issue 25s: the spectral
# path moved onto include/vksky.h must give the serial loop's pixels): EXRs by their pixels, bit for bit (OpenImageIO),
# PNGs byte for byte. Stills with 8, 12 and 24 wavelengths (four and three to a pass), a map in one band, PNGs with auto
# exposure, sequences (the sun, the view and a medium animated; a frame range), on one renderer for every group and on
# a renderer per group (VKSKY_SPECTRAL_SHARED=0, a GPU's choice). Validation on. Exit 0: all identical; 1: some differ (listed); 2: usage.
set -u
OLD=${1:?usage: compare_spectral.sh OLD_VKSKY NEW_VKSKY}
NEW=${2:?usage: compare_spectral.sh OLD_VKSKY NEW_VKSKY}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
size=(--width 64 --height 36)
cases=(
  "s8|--render FILE.exr --render FILE.png ${size[*]} --spectral 8 --pitch 30"
  "s8_horizon|--render FILE.exr --render FILE.png ${size[*]} --spectral 8 --sun-elevation 2"
  "s24|--render FILE.exr --render FILE.png ${size[*]} --spectral 24 --sun-elevation -3 --pitch 20"
  "s24_ground|--render FILE.exr --render FILE.png ${size[*]} --spectral 24 --ground-albedo 0.3,0.2,0.1 --pitch -10"
  "s12_exposure|--render FILE.png ${size[*]} --spectral 12 --exposure 12 --pitch 25"
  "map|--render FILE.exr --projection equirect --width 64 --spectral 8"
  "mars|--render FILE.exr --render FILE.png ${size[*]} --scene mars --spectral 8 --pitch 30"
  "seq|--render FILE_%d.exr --render FILE_%d.png ${size[*]} --spectral 8 --frame-count 3 --animate sun-elevation=-2:20"
  "seq_yaw|--render FILE_%d.exr ${size[*]} --spectral 12 --pitch 30 --frame-count 3 --animate yaw=0:90 --animate mie-scale=1:3"
  "seq_groups|VKSKY_SPECTRAL_SHARED=0 --render FILE_%d.exr --render FILE_%d.png ${size[*]} --spectral 8 --frame-count 3 --animate sun-elevation=-2:20"
  "seq_yaw_groups|VKSKY_SPECTRAL_SHARED=0 --render FILE_%d.exr ${size[*]} --spectral 12 --pitch 30 --frame-count 3 --animate yaw=0:90 --animate mie-scale=1:3"
  "seq_range|--render FILE_%d.exr --render FILE_%d.png ${size[*]} --spectral 24 --frame-count 4 --frame-range 1:2 --animate sun-elevation=1:6"
)
fail=0
for c in "${cases[@]}"; do
  name=${c%%|*} args=${c#*|}
  for tag in old new; do
    bin=$OLD; [ $tag = new ] && bin=$NEW
    mkdir -p "$work/$tag"
    # shellcheck disable=SC2086 # the argument list is word-split on purpose
    env=(); case $args in VKSKY_*) env=("${args%% *}"); args=${args#* } ;; esac   # a leading VAR=VALUE: the run's
    env "${env[@]}" "$bin" --validate ${args//FILE/$work/$tag/$name} >"$work/$tag/$name.stdout" 2>"$work/$tag/$name.raw"
    echo $? >"$work/$tag/$name.status"
    sed "s|$work/$tag/||g" "$work/$tag/$name.raw" >"$work/$tag/$name.stderr" && rm "$work/$tag/$name.raw"
  done
done
for f in "$work"/old/*; do
  n=$(basename "$f") g=$work/new/$n
  [ -e "$g" ] || { echo "differs: $n missing from the new build"; fail=1; continue; }
  case $n in
    *.exr) /usr/bin/python3 - "$f" "$g" <<'PY' || { echo "differs: $n (pixels)"; fail=1; }
import sys
import OpenImageIO as oiio
a, b = (oiio.ImageBuf(p) for p in sys.argv[1:3])
same = (a.spec().width, a.spec().height, a.spec().channelnames) == (b.spec().width, b.spec().height, b.spec().channelnames)
sys.exit(0 if same and a.get_pixels(oiio.FLOAT).tobytes() == b.get_pixels(oiio.FLOAT).tobytes() else 1)
PY
    ;;
    *.stderr) grep -qi "validation" "$g" && { echo "validation message: $n"; fail=1; }
              cmp -s "$f" "$g" || echo "note: $n differs (stderr)" ;;
    *) cmp -s "$f" "$g" || { echo "differs: $n"; fail=1; } ;;
  esac
done
n=$(ls "$work/old" | wc -l)
[ $fail -eq 0 ] && echo "compare_spectral: $n outputs identical"
exit $fail
