/* The app's values (issue 25): what a sequence frame, F5 in the window and the camera make of the command line,
 * checked against independent paths. No GPU.
 *  - A sequence frame (options_frame: the base's values with the animated flags set as numbers) equals a parse of the
 *    command line with the frame's values appended as flags (the way frames were made before: text, parsed again).
 *  - F5 (options_reload) reads the scene file as it is now and keeps the command line's overrides: a --sun-elevation
 *    and a --mie-g given there survive a file that changes both; the file's other changes arrive.
 *  - The loaders (render_values.h): a shipped scene by name gives the numbers its file states (mars.json: the planet's
 *    radius on the camera, the sun, the camera, Mie g) and the values the CLI's --scene gives; a preset by name and
 *    --max-error's pick give the quality the CLI's --quality / --max-error give.
 *  - --dump-scene returns from the parser (main dumps; no exit inside option parsing). */
#include "app/cli/options.h"
#include "app/quality/quality.h"
#include "app/scene/render_values.h"
#include "app/cli/options_sequence.h"
#include "app/runs/sequence.h"
#include "gpu/context.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int failures;
#define CHECK(cond, ...) do { if (!(cond)) { printf("FAIL: "); printf(__VA_ARGS__); printf("\n"); ++failures; } } while (0)

static void write_scene(const char *path, double sun_elevation, double mie_g, double albedo, double rayleigh_r)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        printf("FAIL: cannot write %s\n", path);
        exit(1);
    }
    fprintf(f, "{\"planet\": {\"ground_albedo\": [%g, %g, %g]},\n"
               " \"species\": {\"rayleigh\": {\"scattering\": [%g, 13.558e-3, 33.1e-3]},\n"
               "             \"mie\": {\"phase\": {\"model\": \"henyey-greenstein\", \"g\": %g}}},\n"
               " \"sun\": {\"elevation_deg\": %g, \"azimuth_deg\": 10}}\n",
            albedo, albedo, albedo, rayleigh_r, mie_g, sun_elevation);
    fclose(f);
}

static void check_reload(const char *dir)
{
    char path[512];
    snprintf(path, sizeof path, "%s/vksky_reload_%ld.json", dir, (long)getpid());
    write_scene(path, 20.0, 0.7, 0.1, 5.802e-3);
    char *argv[] = {"vksky", "--scene", path, "--sun-elevation", "5", "--mie-g", "0.6", "--units", "relative"};
    options o, fresh;
    CHECK(options_parse(&o, 9, argv) == 0, "parse of the window's command line failed");
    CHECK(o.view.sun_elevation_deg == 5.0 && o.atmosphere.mie_g == 0.6, "the flags did not override the scene");
    write_scene(path, 40.0, 0.9, 0.5, 7.0e-3);
    CHECK(options_reload(&o, &fresh) == 0, "reload failed");
    CHECK(fresh.view.sun_elevation_deg == 5.0, "F5 dropped --sun-elevation 5: %g", fresh.view.sun_elevation_deg);
    CHECK(fresh.atmosphere.mie_g == 0.6, "F5 dropped --mie-g 0.6: %g", fresh.atmosphere.mie_g);
    CHECK(fresh.units == OPTIONS_UNITS_RELATIVE, "F5 dropped --units relative");
    CHECK(fresh.ground_albedo[1] == 0.5, "F5 kept the old file's albedo: %g", fresh.ground_albedo[1]);
    CHECK(fresh.atmosphere.rayleigh_scattering[0] == 7.0e-3, "F5 kept the old file's Rayleigh: %g",
          fresh.atmosphere.rayleigh_scattering[0]);
    CHECK(fresh.view.sun_azimuth_deg == 10.0, "F5 lost the file's sun azimuth: %g", fresh.view.sun_azimuth_deg);
    /* A broken file: a one-line error, status 2; the caller keeps its scene. */
    FILE *f = fopen(path, "w");
    if (f) fputs("{\"sun\": ", f), fclose(f);
    fprintf(stderr, "(expected below: one line about the broken vksky_reload_*.json)\n");
    CHECK(options_reload(&o, &fresh) == 2, "a broken file did not fail the reload");
    remove(path);
}

static bool same_luts(const sky_lut_quality *a, const sky_lut_quality *b)
{
    return a->transmittance_width == b->transmittance_width && a->transmittance_height == b->transmittance_height &&
           a->transmittance_steps == b->transmittance_steps && a->multiscatter_size == b->multiscatter_size &&
           a->multiscatter_steps == b->multiscatter_steps && a->multiscatter_sqrt_dirs == b->multiscatter_sqrt_dirs &&
           a->lut_f32 == b->lut_f32 && a->skyview_width == b->skyview_width && a->skyview_height == b->skyview_height;
}

static bool same_values(const options *a, const options *b)
{
    return !memcmp(&a->atmosphere, &b->atmosphere, sizeof a->atmosphere) &&
           a->view.sun_elevation_deg == b->view.sun_elevation_deg && a->view.sun_azimuth_deg == b->view.sun_azimuth_deg &&
           a->view.altitude_km == b->view.altitude_km && a->view.fov_deg == b->view.fov_deg &&
           a->view.yaw_deg == b->view.yaw_deg && a->view.exposure_ev == b->view.exposure_ev &&
           a->view.light_scale == b->view.light_scale && a->view.steps == b->view.steps &&
           a->view.skyview_steps == b->view.skyview_steps && a->width == b->width && a->height == b->height &&
           same_luts(&a->lut, &b->lut) && a->render_scale == b->render_scale &&
           a->exposure_ev100 == b->exposure_ev100 && a->view.bloom == b->view.bloom;
}

/* Each frame of `argv`'s sequence against a parse with the frame's values appended as flags. */
static void check_frames(int argc, char **argv, const char *what)
{
    options base;
    if (options_parse(&base, argc, argv) != 0) {
        printf("FAIL: %s: the sequence does not parse\n", what);
        ++failures;
        return;
    }
    int count = base.frame_count > 0 ? base.frame_count : 1;
    for (int i = 0; i < count; ++i) {
        options frame, parsed;
        CHECK(sequence_frame_options(&base, i, &frame) == 0, "%s: frame %d failed", what, i);
        char *args[64], values[16][96];
        int n = 0;
        for (int k = 0; k < argc; ++k) args[n++] = argv[k];
        for (int k = 0; k < base.animate_count; ++k) {
            const options_animation *a = &base.animate[k];
            double t = count > 1 ? (double)i / (double)(count - 1) : 0.0;
            double v = fmin(fmax((1.0 - t) * a->from + t * a->to, fmin(a->from, a->to)), fmax(a->from, a->to));
            if (!strcmp(a->flag_name, "--time")) {
                char text[16];
                sequence_time_text(v, text);
                snprintf(values[k], sizeof values[k], "--time=%s", text);
            } else if (a->integer) {
                snprintf(values[k], sizeof values[k], "%s=%lld", a->flag_name, llround(v));
            } else {
                snprintf(values[k], sizeof values[k], "%s=%.17g", a->flag_name, v);
            }
            args[n++] = values[k];
        }
        CHECK(options_parse_for_classes(&parsed, n, args, base.quality_classes) == 0, "%s: frame %d's flags", what, i);
        CHECK(same_values(&frame, &parsed), "%s: frame %d differs from its flags parsed (sun %g/%g, alt %g/%g, "
              "exposure %g/%g)", what, i, frame.view.sun_elevation_deg, parsed.view.sun_elevation_deg,
              frame.view.altitude_km, parsed.view.altitude_km, frame.view.exposure_ev, parsed.view.exposure_ev);
        options_release(&parsed);
    }
    options_release(&base);
}

static bool same_quality(const render_quality *a, const render_quality *b)
{
    return a->mode == b->mode && a->pass_kind == b->pass_kind && a->steps == b->steps && a->max_steps == b->max_steps &&
           a->skyview_steps == b->skyview_steps && a->steps_ramp_km == b->steps_ramp_km &&
           a->sample_offset == b->sample_offset && a->step_distribution == b->step_distribution &&
           same_luts(&a->lut, &b->lut) && a->render_scale == b->render_scale && a->bloom_mips == b->bloom_mips &&
           a->post_pass == b->post_pass && a->bloom_downsample == b->bloom_downsample &&
           a->bloom_quarter == b->bloom_quarter;
}

static void check_loaders(void)
{
    scene_value s, cs;
    camera_value c, cc;
    render_quality q, cq;
    CHECK(values_load_scene("mars", &s, &c, NULL, NULL) == 0, "mars did not load");
    /* scenes/mars.json's own numbers */
    CHECK(c.ground_radius_km == 3389.5 && s.atmosphere.bottom_radius == 3389.5, "Mars' radius %g", c.ground_radius_km);
    CHECK(s.sun_elevation_deg == 20 && c.yaw_deg == 30 && c.pitch_deg == 10 && c.fov_deg == 75 && c.altitude_km == 0.001,
          "Mars' sun/camera %g %g %g %g %g", s.sun_elevation_deg, c.yaw_deg, c.pitch_deg, c.fov_deg, c.altitude_km);
    CHECK(s.atmosphere.mie_g == 0.7 && s.ground_albedo[0] == 0.25, "Mars' g %g albedo %g", s.atmosphere.mie_g,
          s.ground_albedo[0]);
    options o;
    char *argv[] = {"vksky", "--scene", "mars", "--render", "x.exr", "--units", "relative"};
    CHECK(options_parse(&o, 7, argv) == 0, "--scene mars does not parse");
    values_of(&o, &cs, &cc, NULL, NULL);
    CHECK(!memcmp(&s.atmosphere, &cs.atmosphere, sizeof s.atmosphere) && c.yaw_deg == cc.yaw_deg &&
          c.ground_radius_km == cc.ground_radius_km && s.sun_azimuth_deg == cs.sun_azimuth_deg,
          "the loader and the CLI's --scene differ");
    static const char *const presets[] = {"low", "medium", "high", "ultra", "lesson", "cpu"};
    for (int i = 0; i < 6; ++i) {
        char *pa[] = {"vksky", "--quality", (char *)presets[i], "--render", "x.exr"};
        CHECK(values_quality_preset(presets[i], &q) == 0, "preset %s unknown", presets[i]);
        CHECK(options_parse(&o, 5, pa) == 0, "--quality %s does not parse", presets[i]);
        values_of(&o, NULL, NULL, &cq, NULL);
        CHECK(same_quality(&q, &cq), "preset %s: the loader and --quality differ", presets[i]);
    }
    CHECK(values_quality_preset("bogus", &q) == 2, "an unknown preset loaded");
    double measured = 0;
    /* The table of the device the CLI would run on (issue 31: --max-error reads the running device's table). */
    VkPhysicalDeviceType type;
    bool cpu = gpu_device_type(-1, &type) == 0 && type == VK_PHYSICAL_DEVICE_TYPE_CPU;
    char *pm[] = {"vksky", "--max-error", "0.02", "--sun-elevation", "2", "--render", "x.exr"};
    CHECK(values_quality_pick(0.02, quality_class_bit(0.001, 2.0), cpu, &q, &measured) == 0 && measured <= 0.02,
          "--max-error 0.02 picked nothing within it (%g)", measured);
    CHECK(options_parse(&o, 7, pm) == 0, "--max-error 0.02 does not parse");
    values_of(&o, NULL, NULL, &cq, NULL);
    CHECK(same_quality(&q, &cq), "--max-error: the loader and the CLI differ");
    CHECK(values_quality_pick(1e-9, quality_class_bit(0.001, 2.0), cpu, &q, &measured) == 2, "1e-9 reached");
    /* --dump-scene is parsed, not acted on, by the parser (it used to exit inside it: this process would end here). */
    char *pd[] = {"vksky", "--scene", "mars", "--dump-scene"};
    CHECK(options_parse(&o, 4, pd) == 0 && o.dump_scene, "--dump-scene did not parse into the options");
}

int main(void)
{
    check_loaders();
    const char *dir = getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
    check_reload(dir);
    char *a[] = {"vksky", "--render", "f%d.exr", "--frame-count", "4", "--animate", "sun-elevation=-2:30",
                 "--animate", "rayleigh-scale=0.5:2", "--animate", "exposure=10:12", "--animate", "skyview-steps=8:40"};
    check_frames(13, a, "sun, Rayleigh, exposure, steps");
    char *b[] = {"vksky", "--render", "f%d.exr", "--frame-count", "3", "--scene", "mars", "--animate", "altitude=0.1:20",
                 "--animate", "fov=40:70", "--animate", "mie-g=0.6:0.8", "--units", "relative"};
    check_frames(15, b, "Mars: altitude, fov, mie-g");
    char *c[] = {"vksky", "--render", "f%d.exr", "--frame-count", "5", "--date", "2024-06-21", "--latitude", "40",
                 "--longitude", "-3", "--animate", "time=5.5:8", "--projection", "equirect", "--width", "64"};
    check_frames(17, c, "time, equirect");
    char *d[] = {"vksky", "--render", "f%d.png", "--frame-count", "3", "--max-error", "0.05", "--animate",
                 "sun-lux=50000:100000", "--animate", "sun-azimuth=0:90"};
    check_frames(11, d, "--max-error, sun-lux, azimuth");
    if (failures) printf("%d failure(s)\n", failures);
    else printf("values: all checks passed\n");
    return failures ? 1 : 0;
}
