/* Sequences (issue 14 item 4): the frames --animate, --frame-count and --frame-range ask for, rendered by one
 * renderer in one process. A frame's options are the command line's with each animated flag set to its value for
 * that frame (frame i of N at t = i / (N - 1), linear from FROM to TO; options_frame: values, not text): so frame i is
 * exactly what a single render with those flags makes, whichever job of a split sequence renders it. */
#ifndef VKSKY_APP_SEQUENCE_H
#define VKSKY_APP_SEQUENCE_H
#include "app/cli/options_struct.h"
#include "app/runs/sequence_frames.h"
#include "sky/frame.h"
#include <stdio.h>

/* Before any GPU work: a quality chosen by the scene (auto, --max-error) is chosen once for every scene class the
 * sequence's frames pass through (base is parsed again under it); every frame of the range parses, keeps what the
 * renderer is made for (size, LUTs, bloom) and has writable output files. 0 ok, 2 bad (one line printed; nothing
 * written). */
int sequence_check(options *base);

typedef void (*sequence_render_fn)(sky_renderer *r, const frame_desc *f);
/* Render the range's frames with r (made for base), writing each frame's outputs; the LUTs are recomputed only when a
 * frame changes their inputs (counted; stderr: a line per frame and a summary in a sequence, not with --quiet). With
 * slots >= 2, a sequence of two frames or more is pipelined (app/runs/frame_ring.h: frame N+1 renders while frame N is
 * written; the same files, bytes and order); trace: the ring's waits (--trace-barriers; NULL: none). `render` is the
 * serial loop's (the tests' VKSKY_FRAMES). 0 ok, 1 failed. */
int sequence_render(const options *base, sky_renderer *r, sequence_render_fn render, int slots, FILE *trace);
#endif
