#!/usr/bin/env bash
# The layout, checked (docs/architecture.md): each module of src/ includes only the modules below it, no two
# source units include each other (directly or around a circle), no two files of src/reference call each other
# (directly or around a circle), no binding number outside shaders/glsl/bindings.h, no barrier recorded outside the
# frame functions, and no file in src/ is longer than a newcomer reads in one sitting (600 lines).
#
#   app -> sky -> gpu          app -> io        app -> reference -> model        sky -> model
#
# A unit is a .c file and its .h (src/app/scene/scene.c and src/app/scene/scene.h are the unit app/scene/scene); a unit
# includes another when either of its files names the other's header; a header without a .c is not a unit. A module's
# files may sit in folders of their own at any depth (src/app/cli/...): the module is the first directory under src/,
# and every rule holds in every folder. Usage: layering_test.sh SRC_DIR
set -u
SRC=${1:?usage: layering_test.sh path/to/src}
cd "$SRC" || exit 2
shopt -s globstar nullglob   # **/*.c: every file of every module, in subfolders too
fail=0

# What each module may include besides itself (module names are the directories under src/).
allowed() {
  case $1 in
    model) echo "" ;;
    gpu) echo "" ;;
    io) echo "" ;;
    reference) echo "model" ;;
    sky) echo "gpu model" ;;
    app) echo "sky gpu io reference model" ;;
    lib) echo "app sky gpu io reference model" ;;   # libvksky (include/vksky.h) over the renderer, the scene loader
    *) echo "UNKNOWN" ;;
  esac
}

# Every quoted include of every file: "file included" (system <...> includes are not layering).
edges=$(mktemp)
trap 'rm -f "$edges"' EXIT
for f in **/*.c **/*.h; do
  sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$f" | while read -r inc; do
    echo "$f $inc"
  done
done >"$edges"

while read -r f inc; do
  mod=${f%%/*}
  [ "$(allowed "$mod")" = UNKNOWN ] && { echo "layering: $f: module '$mod' is not in the layering table"; fail=1; continue; }
  case $inc in
    */*) target=${inc%%/*} ;;
    # Unqualified names: the C/GLSL shared layouts (shaders/glsl/shared.h, host_frame_push.h) and the SPIR-V headers generated at
    # build time (build/shaders/*_{comp,frag,vert}.h and shader_key.h, their hash), both for the renderer only.
    shared.h|host_frame_push.h|shader_key.h|sky_shader_key.h|*_comp.h|*_frag.h|*_vert.h) target=shaders ;;
    *) target=UNQUALIFIED ;;
  esac
  if [ "$target" = shaders ]; then
    [ "$mod" = sky ] || [ "$mod" = app ] || { echo "layering: $f includes $inc: shader layouts are the renderer's"; fail=1; }
    continue
  fi
  [ "$target" = "$mod" ] && continue
  case " $(allowed "$mod") " in
    *" $target "*) ;;
    *) echo "layering: $f includes $inc: $mod may include only: $mod $(allowed "$mod")"; fail=1 ;;
  esac
done <"$edges"

# Circles between units: tsort reports a loop in the unit graph. Only headers with a .c of the same name are units
# (something that calls); header-only files (a module's internal header, shared layouts) carry types and inline
# helpers, not calls, and are left out.
loops=$(awk '{ a = $1; sub(/\.[ch]$/, "", a); b = $2; sub(/\.[ch]$/, "", b); if (b ~ /\// && a != b) print a, b }' "$edges" \
        | while read -r a b; do [ -f "$a.c" ] && [ -f "$b.c" ] && echo "$a $b"; done \
        | tsort 2>&1 >/dev/null | grep -v '^tsort: -: input contains a loop:$')
if [ -n "$loops" ]; then
  echo "layering: include circle between units:"; echo "$loops" | sed 's/^tsort: /  /'
  fail=1
fi

# Circles of calls between the files of a module whose files share one internal header (src/reference: every file
# includes ref_internal.h, so the include graph above cannot see who calls whom). A file calls another when its
# code (comments stripped by the preprocessor, no includes expanded) names a function the other defines at file
# scope (not static); tsort reports a loop. E.g. multiscatter.c calling sun_table_eval while psi_table.c calls
# multiscatter_row would be one if both lived in psi_table.c.
calls=$(mktemp)
trap 'rm -f "$edges" "$calls"' EXIT
for mod in reference; do
  for def in "$mod"/*.c; do
    # File-scope definitions: a line at column 0 that is not static, a preprocessor line or a declaration (';').
    names=$(grep -E '^[A-Za-z_][A-Za-z0-9_ *]*[ *]([a-z_][a-z0-9_]*)\(' "$def" | grep -Ev '^(static|typedef|extern)\b|;[[:space:]]*$' \
            | sed -E 's/^[A-Za-z_][A-Za-z0-9_ *]*[ *]([a-z_][a-z0-9_]*)\(.*/\1/' | sort -u)
    [ -n "$names" ] || continue
    pattern="\\b($(echo "$names" | paste -sd'|'))[[:space:]]*\\("
    for caller in "$mod"/*.c; do
      [ "$caller" = "$def" ] && continue
      ${CC:-cc} -fpreprocessed -dD -E -P "$caller" 2>/dev/null | grep -Eq "$pattern" && echo "$caller $def"
    done
  done
done >"$calls"
loops=$(tsort "$calls" 2>&1 >/dev/null | grep -v '^tsort: .*: input contains a loop:$')
if [ -n "$loops" ]; then
  echo "layering: call circle between files (each calls a function the other defines):"; echo "$loops" | sed 's/^tsort: /  /'
  fail=1
fi

# Bindings defined once (shaders/glsl/bindings.h, for C and GLSL): no shader declares a binding by number, no C call
# writes a descriptor to a numbered binding, no set layout is built from a bare list of types.
if [ -d ../shaders/glsl ]; then
  literal=$(grep -nE 'binding[[:space:]]*=[[:space:]]*[0-9]' ../shaders/glsl/* | grep -v '^../shaders/glsl/bindings.h:')
  literal+=$(grep -nE '(gpu_write_(uniform|sampled|storage)|write_image)\([^,]+,[^,]+,[[:space:]]*[0-9]' **/*.c)
  if [ -n "$literal" ]; then
    echo "layering: binding numbers outside shaders/glsl/bindings.h (name them there):"; echo "$literal" | sed 's/^/  /'
    fail=1
  fi
fi

# The spine: barriers are recorded only by the frame functions (src/sky/frame.c and its LUT half frame_luts.c, the composite's frame in
# src/sky/composite.c, the library's SCENE_LINEAR frame in src/sky/host_frame.c); src/gpu/barrier.c builds them. Any other file that records one breaks the claim that a
# learner reads one function per kind of frame and sees every barrier.
stray=$(grep -nE 'gpu_barrier_(add_[a-z_]+|flush)\(|vkCmdPipelineBarrier2?\(' **/*.c | grep -vE '^(sky/frame\.c|sky/frame_luts\.c|sky/composite\.c|sky/host_frame\.c|gpu/barrier\.c):')
if [ -n "$stray" ]; then
  echo "layering: a barrier recorded outside the frame functions (sky/frame.c, sky/frame_luts.c, sky/composite.c, sky/host_frame.c):"; echo "$stray" | sed 's/^/  /'
  fail=1
fi

# No private side door (issue 25 item 1): the command-line tool's run paths that are hosts of include/vksky.h include
# no src/sky header and no src/lib header; they reach the renderer only through the public API. One line per
# converted path (docs/library.md, "The command-line tool as a host").
api_hosts=(app/runs/headless_api.c app/runs/headless_api.h)   # `--render`: one perspective frame, or a map in one band
api_hosts+=(app/runs/sequence_host.c app/runs/sequence_host.h app/runs/host_ring.c app/runs/host_ring.h
           app/runs/sequence_frames.h app/runs/bench_host.c app/runs/bench_host.h)   # sequences, --skip-existing,
                                                                                  # the readback ring, --bench (25h)
api_hosts+=(app/runs/tiles.c app/runs/tiles.h app/runs/bench_report.c app/runs/bench_report.h   # bands, --bench's report,
           app/runs/host_async.c app/runs/host_async.h)                                       # --async-luts (25i)
api_hosts+=(app/window/window.c app/window/window.h app/window/window_app.h app/window/window_api.c   # the window
            app/window/window_input.c app/window/window_input.h app/window/camera.c app/window/camera.h   # (25m)
            app/window/swapchain.c app/window/swapchain.h)
api_hosts+=(app/runs/spectral_host.c app/runs/spectral_host.h)   # --spectral N of one image (25s)
api_hosts+=(app/runs/host_print.h)   # the hosts' message and trace callbacks (25o)
api_hosts+=(app/runs/headless.c app/runs/headless.h app/runs/spectral_render.c   # the last side doors closed:
            app/runs/spectral_render.h app/runs/host_device.h)                   # every headless run, --spectral (issue 25)
api_hosts+=(app/runs/composite_app.c app/runs/composite_app.h app/runs/composite_bands.c   # --composite, --aovs
            app/runs/composite_bands.h app/runs/composite_layers.c app/runs/composite_layers.h   # (25x)
            app/runs/composite_spectral.c app/runs/composite_spectral.h   # --composite --spectral N (issue 32)
            app/runs/composite_camera.c app/runs/composite_camera.h)
for f in "${api_hosts[@]}"; do
  [ -f "$f" ] || { echo "layering: $f: listed as an API host but missing"; fail=1; continue; }
  door=$(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"(sky|lib)/' "$f")
  if [ -n "$door" ]; then
    echo "layering: $f is a host of include/vksky.h and includes the renderer directly:"; echo "$door" | sed 's/^/  /'
    fail=1
  fi
done

# File length.
for f in **/*.c **/*.h; do
  n=$(wc -l <"$f")
  [ "$n" -le 600 ] || { echo "layering: $f has $n lines (at most 600: split it along its seams)"; fail=1; }
done

[ $fail -eq 0 ] && echo "layering: $(wc -l <"$edges") includes in $(ls **/*.c **/*.h | wc -l) files follow the layering; no circles (includes; calls within reference/: $(wc -l <"$calls") edges); no file over 600 lines"
exit $fail
