/* vksky: a physically based sky (Hillaire 2020) over raw Vulkan. */
#include "app/cli/options_throughput.h"
#include "app/runs/composite_app.h"
#include "app/runs/headless.h"
#include "app/runs/stop.h"
#include "app/cli/options.h"
#include "app/quality/quality.h"
#include "app/window/window.h"
#include "app/runs/reference_run.h"
#include "app/scene/scene_dump.h"
#include "app/scene/scene_find.h"
#include "app/runs/sequence.h"
#include "app/runs/startup.h"
#include "app/runs/spectral_render.h"
#include <stdlib.h>

static int run(options *o, int argc, char **argv)
{
    composite_options co;   /* its flags leave argv here; the shared table never sees them */
    if (composite_options_extract(&co, &argc, argv) != 0) return 2;
    if (options_parse(o, argc, argv) != 0) return 2;
    if (o->help) {
        options_print_help(stdout);
        composite_options_print_help(stdout);
        stop_print_help(stdout);
        return 0;
    }
    if (o->version) {
        printf("vksky %s\n", VKSKY_VERSION);
        return 0;
    }
    if (o->dump_scene) return scene_dump(o, stdout);   /* the effective scene as JSON; nothing else runs */
    options_throughput_install(o);   /* --threads, --exr-compression: how every file of the run is encoded */
    if (o->list_scenes) return scene_list(stdout);
    if (o->list_devices) return gpu_list_devices(stdout) == 0 ? 0 : 1;
    if (o->path_trace && !o->reference) {
        fprintf(stderr, "vksky: --path-trace: only with --reference\n");
        return 2;
    }
    if (o->irradiance && !o->reference) {
        fprintf(stderr, "vksky: --irradiance: only with --reference\n");
        return 2;
    }
    if (o->reference && o->spectral > 0 && o->spectral < 3) {
        fprintf(stderr, "vksky: --spectral: %d wavelengths with --reference; expected 0 (RGB) or 3 to 120\n",
                o->spectral);
        return 2;
    }
    if (o->reference) {
        if (o->bench_frames) {
            fprintf(stderr, "vksky: --bench: not with --reference\n");
            return 2;
        }
        return reference_run(o);
    }
    if ((co.input || co.aovs) && sequence_active(o)) {
        fprintf(stderr, "vksky: %s: not with %s (one image; a sequence renders plain sky frames)\n",
                o->animate_count ? "--animate" : o->frame_range_set ? "--frame-range" : "--frame-count",
                co.input ? "--composite" : "--aovs");
        return 2;
    }
    if (o->max_color_error > 0.0) {   /* the colour axis of the trade: the fewest wavelengths that keep the promise */
        if (o->spectral || o->reference) {
            fprintf(stderr, "vksky: --max-color-error: not with %s; give one or the other\n",
                    o->reference ? "--reference" : "--spectral");
            return 2;
        }
        unsigned classes = o->quality_classes ? o->quality_classes
                                             : quality_class_bit(o->view.altitude_km, o->view.sun_elevation_deg);
        char names[96];
        double measured;
        int n = spectral_pick(o->max_color_error, classes, &measured);
        quality_class_names(classes, names, sizeof names);
        if (n < 0) {
            fprintf(stderr, "vksky: --max-color-error: no measured colour setting reaches CIEDE2000 %g on a %s scene "
                            "(the best: %.2f); try a larger budget\n", o->max_color_error, names, measured);
            return 2;
        }
        o->spectral = n;
        char flag[80];
        snprintf(flag, sizeof flag, "--max-color-error %g (picked --spectral %d)", o->max_color_error, n);
        if (spectral_render_check(o, flag)) return 2;
        printf("vksky: --max-color-error %g: picked --spectral %d (measured worst CIEDE2000 %.2f on the '%s' scene)\n",
               o->max_color_error, n, measured, names);
    }
    spectral_auto(o, NULL);   /* --quality auto's colour: spectral where RGB's is far off */
    if (spectral_render_check(o, "--spectral")) return 2;   /* the GPU's --spectral: EXR renders only */
    /* The composite keeps the lesson's scale (docs/units.md: the layers add up with the render's own units): its
     * header says so (vksky:units). */
    if (co.input || co.aovs) o->units = OPTIONS_UNITS_RELATIVE;
    if (co.input) return composite_run(o, &co);
    if (co.aovs) return composite_aovs_run(o, &co);
    if (o->output_count == 0 && o->bench_frames == 0) return window_run(o);
    if (o->frames || o->screenshot) {
        fprintf(stderr, "vksky: %s: only for the interactive window (not with --render or --bench)\n",
                o->frames ? "--frames" : "--screenshot");
        return 2;
    }
    return headless_run(o);
}

int main(int argc, char **argv)
{
    startup_begin();
    options o = {0};
    int rc = run(&o, argc, argv);
    startup_exit(rc);   /* one image left to the exit: no atexit handlers (startup.h) */
    options_release(&o);
    return rc;
}
