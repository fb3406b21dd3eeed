/* Sequences (issue 14 item 4): the frames --animate, --frame-count and --frame-range ask for, rendered by one
 * renderer in one process. A frame's options are the command line's with each animated flag set to its value for
 * that frame (frame i of N at t = i / (N - 1), linear from FROM to TO; options_frame: values, not text): so frame i is
 * exactly what a single render with those flags makes, whichever job of a split sequence renders it. */
#ifndef VKSKY_APP_SEQUENCE_H
#define VKSKY_APP_SEQUENCE_H
#include "app/cli/options_struct.h"
#include "app/runs/sequence_frames.h"
#include <stdio.h>

/* Before any GPU work: a quality chosen by the scene (auto, --max-error) is chosen once for every scene class the
 * sequence's frames pass through (base is parsed again under it); every frame of the range parses, keeps what the
 * renderer is made for (size, LUTs, bloom) and has writable output files. 0 ok, 2 bad (one line printed; nothing
 * written). */
int sequence_check(options *base);

#endif
