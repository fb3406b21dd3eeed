#!/usr/bin/env bash
# tests/api/api_install.sh BUILD_DIR CONSUMER_DIR: `cmake --install` into a temporary prefix, then a small C host
# (consumer/consumer.c) built against the installed library three ways: with pkg-config (shared), with pkg-config
# --static against libvksky.a, and with find_package(vksky) (target vksky::vksky); each runs and prints the version
# with the ABI checked.
set -u
BUILD=${1:?usage: api_install.sh BUILD_DIR CONSUMER_DIR}
SRC=${2:?usage: api_install.sh BUILD_DIR CONSUMER_DIR}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
P=$work/prefix
cmake --install "$BUILD" --prefix "$P" >"$work/install.log" 2>&1 || { cat "$work/install.log" >&2; echo "FAIL: cmake --install" >&2; exit 1; }
for f in include/vksky.h include/vksky_luts.glsl include/vksky/glsl/geometry.glsl include/vksky/glsl/lut_mapping.glsl lib/libvksky.so lib/libvksky.a lib/pkgconfig/vksky.pc \
         lib/cmake/vksky/vksky-config.cmake lib/cmake/vksky/vksky-config-version.cmake; do
    [ -e "$P/$f" ] || fail "not installed: $f"
done
soname=$(objdump -p "$P/lib/libvksky.so" | awk '/SONAME/ {print $2}')
[ "$soname" = libvksky.so.0 ] || fail "SONAME is '$soname', expected libvksky.so.0"
version=$(sed -n 's/^project(vksky VERSION \([0-9.]*\).*/\1/p' "$(dirname "$0")/../../CMakeLists.txt")
# The ABI the source header declares (the installed library must report the same).
abi=$(sed -n 's/^#define VKSKY_ABI_VERSION \([0-9]*\)u.*/\1/p' "$(dirname "$0")/../../include/vksky.h")   # the header's
[ -n "$abi" ] || fail "no VKSKY_ABI_VERSION in include/vksky.h"

export PKG_CONFIG_PATH=$P/lib/pkgconfig LD_LIBRARY_PATH=$P/lib
[ "$(pkg-config --modversion vksky)" = "$version" ] || fail "pkg-config --modversion vksky: $(pkg-config --modversion vksky)"
# shellcheck disable=SC2046
cc -std=c11 -o "$work/c_pc" "$SRC/consumer.c" $(pkg-config --cflags --libs vksky) || fail "build with pkg-config"
[ "$("$work/c_pc")" = "vksky $version abi $abi" ] || fail "pkg-config consumer printed '$("$work/c_pc")'"
# shellcheck disable=SC2046
cc -std=c11 -o "$work/c_static" "$SRC/consumer.c" $(pkg-config --cflags vksky) "$P/lib/libvksky.a" \
    $(pkg-config --static --libs-only-l vksky | sed 's/-lvksky//') || fail "build against libvksky.a"
ldd "$work/c_static" 2>/dev/null | grep -q libvksky && fail "the static consumer loads libvksky.so"
[ "$("$work/c_static")" = "vksky $version abi $abi" ] || fail "static consumer printed '$("$work/c_static")'"
cmake -S "$SRC" -B "$work/cm" -DCMAKE_PREFIX_PATH="$P" >"$work/cm.log" 2>&1 && cmake --build "$work/cm" >>"$work/cm.log" 2>&1 \
    || { cat "$work/cm.log" >&2; fail "build with find_package(vksky)"; }
[ "$("$work/cm/consumer")" = "vksky $version abi $abi" ] || fail "find_package consumer printed '$("$work/cm/consumer")'"
# A shipped scene by name, found beside the installed library (not the source tree): its installed copy is marked
# with another ground radius, which the consumer must print, from another directory.
sed -i 's/"ground_radius_km": [0-9.]*/"ground_radius_km": 1234.5/' "$P/share/vksky/scenes/mars.json"
radius=$(cd "$work" && "$work/c_pc" mars)
[ "$radius" = 1234500 ] || fail "vksky_scene_load(\"mars\") through the installed library read ground radius '$radius' m, not the installed copy's"
# A host's shader through the installed GLSL include (its LUT mappings: vksky's own shader files, installed).
glslangValidator --quiet -V --target-env vulkan1.3 -I"$P/include" -o "$work/luts_host.spv" "$SRC/luts_host.comp" \
    >"$work/glsl.log" 2>&1 || { cat "$work/glsl.log" >&2; fail "luts_host.comp does not compile against include/vksky_luts.glsl"; }
[ $fails -eq 0 ] && echo "api_install: headers, libvksky.so.0 + .a, vksky.pc and vksky-config.cmake installed; pkg-config (shared, static) and find_package consumers run"
exit $fails
