/* `vksky --render` of one perspective frame, or of an environment map or a large image (vksky_frame_band), as a host
 * of the public API (include/vksky.h; issue 25 item 1, "no
 * private side door"): the command-line tool adopts its own device into a vksky context, builds a renderer from a
 * scene value made of its command line, records each frame into a command buffer of its own, submits and waits, and
 * writes the pixels the renderer read back. No src/sky header is included here (tests/layering_test.sh checks). */
#ifndef VKSKY_APP_RUNS_HEADLESS_API_H
#define VKSKY_APP_RUNS_HEADLESS_API_H
#include <volk.h>
#include <vksky.h>
#include "app/cli/options_struct.h"

/* The frames of `o` (one frame, a sequence's, --bench with --render or alone, an image in bands: app/runs/tiles.c;
 * --spectral: app/runs/spectral_host.c; with --async-luts the LUTs on the device's compute queue, index
 * compute_queue_index in its family: app/runs/host_async.c) on ctx, the command line's device adopted
 * (app/runs/host_device.h), which the caller keeps and destroys after. Returns the run's exit status: 0, or 1 for a
 * runtime failure (the line printed). */
int headless_api_render(const options *o, vksky_context *ctx, uint32_t compute_queue_index);
#endif
