#!/usr/bin/env bash
# tests/api/api_exports.sh LIBVKSKY_SO LIBVKSKY_A: the shared library exports only vksky_* (nm -D), and the static
# library's only global definitions are vksky_* too (its objects were linked into one and every hidden symbol made
# local: volk's vk* pointers, the renderer's functions and cJSON's cannot collide with a host's own); every function
# of include/vksky.h is among them.
set -u
SO=${1:?usage: api_exports.sh LIBVKSKY_SO LIBVKSKY_A}
A=${2:?usage: api_exports.sh LIBVKSKY_SO LIBVKSKY_A}
HEADER=$(dirname "$0")/../../include/vksky.h
fails=0
others=$(nm -D --defined-only "$SO" | awk '{print $3}' | grep -v '^vksky_' | grep -v '^$')
[ -z "$others" ] || { echo "FAIL: $SO exports more than vksky_*:"; echo "$others" | head -20; fails=1; }
others=$(nm -g --defined-only "$A" | awk 'NF == 3 {print $3}' | grep -v '^vksky_')
[ -z "$others" ] || { echo "FAIL: $A has global symbols besides vksky_*:"; echo "$others" | head -20; fails=1; }
# Undefined references of the static library are its dependencies (libc, cJSON, OpenEXR, libpng), never volk's.
volk=$(nm -g --undefined-only "$A" | awk '{print $2}' | grep -E '^(volk|vk[A-Z])' || true)
[ -z "$volk" ] || { echo "FAIL: $A refers to outside Vulkan symbols: $volk" | head -5; fails=1; }
for fn in $(grep -o 'vksky_[a-z_0-9]*(' "$HEADER" | tr -d '(' | sort -u); do
  nm -D --defined-only "$SO" | awk '{print $3}' | grep -qx "$fn" || { echo "FAIL: $fn is not exported"; fails=1; }
  nm -g --defined-only "$A" | awk 'NF == 3 {print $3}' | grep -qx "$fn" || { echo "FAIL: $fn is not global in $A"; fails=1; }
done
n=$(nm -D --defined-only "$SO" | grep -c ' vksky_')
[ $fails -eq 0 ] && echo "api_exports: $n symbols, all vksky_*, in both libraries"
exit $fails
