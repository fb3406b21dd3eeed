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

/* The frames of `o` (one frame, a sequence's, --bench with --render, an image in bands: app/runs/tiles.c; with
 * --async-luts the LUTs on the device's compute queue: app/runs/host_async.c) on the device `device` describes (the
 * caller's, which it keeps and destroys after), with the features `enabled` on it. Returns the run's exit status: 0,
 * or 1 for a runtime failure (the line printed). */
/* cache_dir: the CLI's cache directory (the LUT cache beside its pipeline cache), or NULL (--no-cache). */
int headless_api_render(const options *o, const vksky_context_desc *device, const vksky_device_requirements *enabled,
                        bool debug_utils,
                        const char *cache_dir);
#endif
