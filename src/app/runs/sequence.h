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
/* Render the range's frames with r (made for base) one at a time, each by `render` (the tests' VKSKY_FRAMES loop,
 * --spectral's groups), writing each frame's outputs; the LUTs are recomputed only when a frame changes their inputs
 * (counted; stderr: a line per frame and a summary in a sequence, not with --quiet). The runs that are hosts of
 * include/vksky.h render their sequences through app/runs/sequence_host.h (pipelined there); this loop serves what
 * still calls src/sky: --spectral, and --bench's sequence with --async-luts. 0 ok, 1 failed. */
int sequence_render(const options *base, sky_renderer *r, sequence_render_fn render);
#endif
