/* Sequences (--animate, --frame-count, --frame-range) and --skip-existing as a host of include/vksky.h (issue 25
 * item 1): each frame's animated values set on the command line's scene value (vksky_scene_set_values: numbers, no
 * argv parsed again, no scene file read again, no device probed again), the renderer given that scene
 * (vksky_renderer_set_scene), the view and exposure per frame (vksky_frame_view), the pixels through the host's
 * readback ring (app/runs/host_ring.h) or one frame at a time. The same files, bytes, lines and traces as
 * app/runs/sequence.c's loops. No src/sky or src/lib header (tests/layering_test.sh). */
#ifndef VKSKY_APP_SEQUENCE_HOST_H
#define VKSKY_APP_SEQUENCE_HOST_H
#include <volk.h>
#include <vksky.h>
#include "app/cli/options_struct.h"
#include "app/runs/host_async.h"

/* The frames of base's range (or its one frame, --skip-existing) with r, a readback renderer made from `scene` (the
 * command line's, vksky_scene_from_args: its values are set per frame); pipelined through the ring of
 * VKSKY_READBACK_SLOTS slots (default 2; 0 or 1: one frame at a time). One frame at a time with `async` (--async-luts:
 * each frame's LUT passes on the compute queue first; NULL: none) and under the tests' VKSKY_FRAMES loop.
 * trace: --trace-barriers's stream (NULL: none). 0 ok, 1 failed. */
int sequence_host_render(const options *base, vksky_context *ctx, vksky_scene *scene, vksky_renderer *r,
                         host_async *async, FILE *trace);
#endif
