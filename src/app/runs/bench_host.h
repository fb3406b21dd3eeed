/* --bench N, with --render or alone, as a host of include/vksky.h (issue 25 item 1): per-pass GPU medians from
 * vksky_renderer_get_timings, the LUT passes from frames with frame.force_luts, wall and CPU time per frame; then a
 * sequence's frames to disk, timed (app/runs/sequence_host.c). The same lines as app/runs/headless.c's bench: one
 * report (app/runs/bench_report.h). No src/sky or src/lib header (tests/layering_test.sh). */
#ifndef VKSKY_APP_BENCH_HOST_H
#define VKSKY_APP_BENCH_HOST_H
#include <volk.h>
#include <vksky.h>
#include "app/cli/options_struct.h"
#include "app/runs/host_async.h"

/* The benchmark of o's frame with r (made from `scene`), then its sequence, if any, to disk. r is a readback renderer
 * (--render), or (no outputs) a renderer writing the host's own image: the CLI makes an offscreen 8-bit image of r's
 * size and passes it as the frame's target, as a host engine passes its own. async (NULL: none): --async-luts, the
 * LUT passes on the compute queue (app/runs/host_async.h), timed there (vksky_renderer_get_lut_timings).
 * 0 ok, 1 failed. */
int bench_host_run(const options *o, vksky_context *ctx, vksky_scene *scene, vksky_renderer *r, host_async *async);
#endif
