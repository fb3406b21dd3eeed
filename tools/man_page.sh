#!/usr/bin/env bash
# tools/man_page.sh VKSKY > docs/vksky.1: the man page's OPTIONS section generated from `vksky --help` (grouped, one
# .TP entry per flag), between hand-written sections. tests/man_test.sh checks that the page lists every flag that
# --help lists; rerun this after adding a flag.
set -euo pipefail
VKSKY=${1:?usage: tools/man_page.sh path/to/vksky > docs/vksky.1}
version=$("$VKSKY" --version | awk '{print $2}')
cat <<EOF2
.TH VKSKY 1 "" "vksky $version" "User Commands"
.SH NAME
vksky \\- a physically based sky (Hillaire 2020) rendered with Vulkan
.SH SYNOPSIS
.B vksky
[\\fIoptions\\fR]
.br
.B vksky \\-\\-render
\\fIFILE\\fR.exr|\\fIFILE\\fR.png [\\fIoptions\\fR]
.br
.B vksky \\-\\-scene
\\fINAME\\fR|\\fIFILE\\fR.json [\\fIoptions\\fR]
.br
.B vksky \\-\\-frame\\-count
\\fIN\\fR \\fB\\-\\-animate\\fR \\fIPARAM\\fR=\\fIFROM\\fR:\\fITO\\fR \\fB\\-\\-render\\fR \\fIsky_%04d\\fR.exr [\\fB\\-\\-frame\\-range\\fR \\fIA\\fR:\\fIB\\fR] [\\fIoptions\\fR]
.SH DESCRIPTION
Renders the sky of a planet's atmosphere (Rayleigh, Mie and ozone, multiple scattering) with the LUTs of
Hillaire's 2020 model, in an interactive window or headless into an OpenEXR (scene-linear) or PNG file.
Shipped scenes (\\fBvksky \\-\\-list-scenes\\fR) are found by name; the sun can be placed by angles or by a
date, a time and a place (NREL's Solar Position Algorithm).
A sequence (\\fB\\-\\-animate\\fR, \\fB\\-\\-frame\\-count\\fR) renders its frames in one process and
recomputes the LUTs only when their inputs change; \\fB\\-\\-frame\\-range\\fR splits it across render-farm
jobs with the same files as a whole run. An EXR's header records the camera (worldToCamera, worldToNDC), the
colour space (chromaticities), the scene and the command line: \\fBvksky \\-\\-scene\\fR \\fIFRAME\\fR.exr
renders it again.
Bad input prints one line naming the flag and what it accepts, and exits with status 2.
.SH OPTIONS
EOF2
"$VKSKY" --help | awk '
    function esc(t) { gsub(/\\/, "\\e", t); gsub(/-/, "\\-", t); sub(/^[.\047]/, "\\\\\\&&", t); return t }
    function flush() { sub(/^ +/, "", text); if (entry != "") print entry "\n" esc(text); entry = "" }
    /^[a-z]+:$/ { flush(); g = substr($0, 1, length($0) - 1); print ".SS " toupper(substr(g, 1, 1)) substr(g, 2); next }
    /^  --/ {
        flush()
        line = substr($0, 3); head = line; sub(/  .*$/, "", head)
        text = substr(line, length(head) + 1); sub(/^ +/, "", text)
        n = split(head, parts, " ")
        entry = n > 1 ? ".TP\n.BI " esc(parts[1]) " \" \" " esc(parts[2]) : ".TP\n.B " esc(parts[1])
        next
    }
    /^          +/ && entry != "" { t = $0; sub(/^ +/, "", t); text = text " " t; next }
    END { flush() }'
cat <<'EOF2'
.SH EXAMPLES
.TP
Render a shipped scene:
.B vksky \-\-scene mars \-\-render mars.exr
.TP
The sky over Golden, Colorado, on 17 October 2003 at 12:30:30 local time (UTC\-7), looking south:
.B vksky \-\-date 2003\-10\-17 \-\-time 12:30:30 \-\-utc\-offset \-7 \-\-latitude 39.742476 \-\-longitude \-105.1786 \-\-elevation\-m 1830 \-\-yaw 180 \-\-render golden.png
.SH AZIMUTH
Azimuths (\fB\-\-sun\-azimuth\fR, \fB\-\-yaw\fR) turn clockwise seen from above, like a compass: with
\fB\-\-yaw 0\fR looking north, 90 is east, 180 south, 270 west. A sun placed by date and place uses the
compass azimuth of the Solar Position Algorithm unchanged.
.SH EXIT STATUS
0 success; 1 a failed render or validation message; 2 bad input (one line on stderr);
130 / 143 stopped by SIGINT (Ctrl\-C) / SIGTERM. A stop ends every mode cleanly: the window between frames, a
headless render after the frame on the device, \fB\-\-bench\fR between frames (no figures printed), a sequence
between frames (the frames it finished stay), \fB\-\-reference\fR between pixels; the device is waited for and
everything made is destroyed; no partial output and no temporary file is left (outputs are written to a
temporary and renamed into place when whole). A second signal ends the program at once.
.SH ENVIRONMENT
.TP
.B VKSKY_VALIDATION=1
the same as \fB\-\-validate\fR.
.SH FILES
.TP
.I <prefix>/share/vksky/scenes/*.json
the shipped scenes (schema: README.md there).
.TP
.I <prefix>/share/doc/vksky/
README.md and the design documents.
.SH SEE ALSO
Hillaire, "A Scalable and Production Ready Sky and Atmosphere Rendering Technique", EGSR 2020.
Reda and Andreas, "Solar Position Algorithm for Solar Radiation Applications", NREL/TP\-560\-34302, 2008.
EOF2
