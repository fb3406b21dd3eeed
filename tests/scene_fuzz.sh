#!/usr/bin/env bash
# Bad scene files and command lines never crash vksky, and what it accepts it can write back: every shipped scene
# mutated N times (tests/scene_mutate.c, seeds 1..N) and loaded with --dump-scene must
#  - exit 0 or 2, never by a signal or another status;
#  - on 2: print exactly one line on stderr, "vksky: ...", and nothing on stdout;
#  - on 0: print a dump that loads back (exit 0) to the very same dump (accepted scenes round-trip).
# Every 25th accepted mutant is also rendered (16x9, --validate): exit 0, or 2 with one line, and no file left
# behind on 2. Then N random command lines (flags from --help, hostile values) with --dump-scene, the same way.
# Usage: scene_fuzz.sh VKSKY SCENE_MUTATE SCENES_DIR [N]
set -u
VKSKY=${1:?usage: scene_fuzz.sh VKSKY SCENE_MUTATE SCENES_DIR [N]}
MUTATE=${2:?}
SCENES=${3:?}
N=${VKSKY_SCENE_FUZZ_MUTANTS:-${4:-300}}   # the sanitizer run (tests/sanitize.sh) asks for fewer
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0 accepted=0 rejected=0 rendered=0
# (a failing mutant is reproduced by: scene_mutate SCENE SEED > m.json; the test makes a scene's all at once)
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
# FILE holds exactly one line (one newline, at its end), left in $line; and that line starts "vksky: ". What `wc -l`
# = 1 and `grep -q '^vksky: '` said, in bash itself (this loop runs ~3000 times: two fewer processes each, issue 27
# item 5).
one_line() {
    local c=
    IFS= read -r -d '' c <"$1"
    line=${c%$'\n'}
    [ "$line" != "$c" ] && [[ $line != *$'\n'* ]]
}
one_vksky_line() { one_line "$1" && [[ $line == "vksky: "* ]]; }
# FILE1 and FILE2 hold the same bytes: what `cmp -s` said, in bash (the dumps are JSON text: no NUL byte, where read
# would stop).
same_file() {
    local a= b=
    [ -f "$1" ] && [ -f "$2" ] || return 1
    IFS= read -r -d '' a <"$1"
    IFS= read -r -d '' b <"$2"
    [ "$a" = "$b" ]
}
# A --dump-scene of a scene with --quality auto lists the knobs of the measured table for the run's device kind, and
# to know the kind each process made a Vulkan instance (the loader, lavapipe and its LLVM: ~35 ms of CPU, most of this
# test's time over ~3000 dumps). The answer is the same for every dump that names no --device, so it is asked once
# here, the way vksky asks it, and handed to those dumps through VKSKY_QUALITY_TABLE (options.c: device_is_cpu): the
# dumps are byte for byte what the probe gives (checked here), and the checks below are unchanged (issue 27 item 5).
# The fuzzed command lines (which may name --device) still probe; so does every render.
plain=$("$VKSKY" --dump-scene 2>/dev/null) || { echo "FAIL: --dump-scene: exit $?"; exit 1; }
table=
for t in cpu gpu; do
    [ "$(VKSKY_QUALITY_TABLE=$t "$VKSKY" --dump-scene 2>/dev/null)" = "$plain" ] && { table=$t; break; }
done
[ -n "$table" ] || { echo "FAIL: neither VKSKY_QUALITY_TABLE=cpu nor gpu gives the probed dump"; exit 1; }
dump() { VKSKY_QUALITY_TABLE=$table "$VKSKY" "$@" --dump-scene; }
for scene in "$SCENES"/*.json; do
    # A scene's N mutants by one process (the same bytes as `scene_mutate SCENE SEED`, one by one).
    rm -rf "$work/mutants" && mkdir "$work/mutants" && "$MUTATE" "$scene" 1 "$N" "$work/mutants" ||
        { fail "scene_mutate $scene 1 $N"; continue; }
    for seed in $(seq 1 "$N"); do
        mutant=$work/mutants/m$seed.json
        dump --scene "$mutant" >"$work/d1.json" 2>"$work/err"
        rc=$?
        what="${scene##*/} seed $seed"
        if [ $rc -eq 2 ]; then
            rejected=$((rejected + 1))
            one_vksky_line "$work/err" ||
                fail "$what: exit 2 without exactly one 'vksky: ' line: $(head -c 300 "$work/err")"
            [ ! -s "$work/d1.json" ] || fail "$what: exit 2 but printed on stdout"
        elif [ $rc -eq 0 ]; then
            accepted=$((accepted + 1))
            dump --scene "$work/d1.json" >"$work/d2.json" 2>"$work/err" ||
                fail "$what: the dump of an accepted scene does not load: $(head -c 300 "$work/err")"
            same_file "$work/d1.json" "$work/d2.json" || fail "$what: accepted scene does not round-trip"
            if [ $((accepted % 25)) -eq 0 ]; then
                rendered=$((rendered + 1))
                rm -f "$work/out.exr"
                "$VKSKY" --scene "$mutant" --width 16 --height 9 --validate --render "$work/out.exr" 2>"$work/err"
                r=$?
                if [ $r -eq 2 ]; then
                    one_line "$work/err" || fail "$what: render exit 2 without one line"
                    [ -z "$(ls -A "$work" | grep out)" ] || fail "$what: render exit 2 left a file"
                elif [ $r -ne 0 ]; then
                    fail "$what: render exited $r: $(head -c 300 "$work/err")"
                fi
            fi
        else
            fail "$what: exit status $rc (a crash or an unexpected status): $(head -c 300 "$work/err")"
        fi
    done
done
echo "scene_fuzz: $accepted accepted (round-tripped), $rejected rejected with one line, $rendered rendered"
[ $accepted -gt 0 ] && [ $rejected -gt 0 ] || fail "the mutants are all accepted or all rejected: the fuzzer is broken"
# The command line, fuzzed the same way: 1 to 4 flags from --help with hostile values (or none), then
# --dump-scene (which runs nothing else): exit 0 with a dump that round-trips, or 2 with one line.
help=$("$VKSKY" --help) || { echo "FAIL: --help: exit $?"; exit 1; }
flags=($(echo "$help" | grep -oE '^  --[a-z0-9-]+' | tr -d ' ' | grep -vE '^--(help|version|list-devices|dump-scene)$'))
values=(0 -0 1 -1 2 3 10 45 0.5 64 medium skyview 1e309 -1e309 nan inf 1e-320 0x10 1,2,3 1,2 "" " " x 99999999999999999999 16384 16385
        fragment compute auto low ultra f32 aces hg cornette-shanks 1,nan,1 "$work/none/x.exr" "$work/o.exr" --width)
argv_accepted=0 argv_rejected=0
RANDOM=2020
for i in $(seq 1 "$N"); do
    args=()
    # The count is drawn here, in this shell: $RANDOM inside $(...) runs in a subshell, which reseeds it (the count
    # would then differ from run to run) and does not advance this shell's sequence.
    nflags=$((RANDOM % 4 + 1))
    for k in $(seq 1 "$nflags"); do
        args+=("${flags[RANDOM % ${#flags[@]}]}")
        [ $((RANDOM % 5)) -eq 0 ] || args+=("${values[RANDOM % ${#values[@]}]}")
    done
    "$VKSKY" "${args[@]}" --dump-scene >"$work/d1.json" 2>"$work/err"
    rc=$?
    if [ $rc -eq 2 ]; then
        argv_rejected=$((argv_rejected + 1))
        one_vksky_line "$work/err" ||
            fail "argv ${args[*]}: exit 2 without exactly one 'vksky: ' line: $(head -c 300 "$work/err")"
    elif [ $rc -eq 0 ]; then
        argv_accepted=$((argv_accepted + 1))
        dump --scene "$work/d1.json" >"$work/d2.json" 2>/dev/null && same_file "$work/d1.json" "$work/d2.json" ||
            fail "argv ${args[*]}: the dump does not round-trip"
    else
        fail "argv ${args[*]}: exit status $rc: $(head -c 300 "$work/err")"
    fi
done
echo "scene_fuzz: command lines: $argv_accepted accepted, $argv_rejected rejected with one line"
[ $argv_accepted -gt 0 ] && [ $argv_rejected -gt 0 ] || fail "the command lines are all accepted or all rejected"
if [ $fails -ne 0 ]; then echo "scene_fuzz: $fails failure(s)"; exit 1; fi
echo "scene_fuzz: ok"
