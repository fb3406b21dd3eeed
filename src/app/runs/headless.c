/* The headless run (headless.h): the command line's device adopted by a vksky context (app/runs/host_device.c) and
 * every --render and --bench run recorded through include/vksky.h (app/runs/headless_api.c). No src/sky, src/gpu or
 * src/lib header (tests/layering_test.sh). */
#include "app/runs/headless.h"
#include "app/runs/headless_api.h"
#include "app/runs/host_device.h"
#include "app/runs/sequence.h"
#include "app/runs/startup.h"
#include "app/runs/stop.h"
#include "app/runs/tiles.h"

static int run_checked(const options *o);

int headless_run(const options *given)
{
    stop_install();
    /* Refuse bad frames and unwritable outputs before any expensive work (exit 2, nothing written): every frame's
     * options and files, one frame's or a sequence's (whose quality choice may then serve all its frames). A copy of
     * its own: the check may parse the sequence again under that choice. */
    options checked;
    if (options_copy(&checked, given)) return 1;
    int status = sequence_check(&checked) ? 2 : run_checked(&checked);
    options_release(&checked);
    return status;
}

/* main routes here only a run with outputs or --bench (a run with neither is the window's, and --spectral with
 * --bench is refused before: spectral_render_check), so every run here is a host of the API: one perspective frame
 * to files, sequences and --skip-existing (app/runs/sequence_host.c), --async-luts (app/runs/host_async.c), the
 * tests' VKSKY_FRAMES loop, --timings, --bench with --render or alone (app/runs/bench_host.c), environment maps and
 * images in bands (app/runs/tiles.c), --spectral (app/runs/spectral_host.c). */
static int run_checked(const options *o)
{
    if (o->output_count > 0 && o->bench_frames == 0 && tiles_wanted(o) && sequence_active(o)) {
        fprintf(stderr, "vksky: --animate/--frame-count/--frame-range: not with an environment map (--projection) or "
                        "an image over the band budget; render such frames one run each\n");
        return 2;
    }
    host_device *dev = NULL;
    vksky_context *ctx = NULL;
    uint32_t compute_index = 0;
    int status = host_device_open(o, &dev, &ctx, &compute_index);
    if (status != 0) return status;
    status = headless_api_render(o, ctx, compute_index);
    /* keep: one image, validation off: the context, device and instance left to the exit (startup.h). */
    bool keep = startup_keep_for_exit(o, status);
    return host_device_close(dev, keep ? NULL : ctx, status, (host_device_end){.timings = o->timings, .keep = keep});
}
