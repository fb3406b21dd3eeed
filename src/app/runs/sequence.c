/* The frames of a sequence (sequence.h). */
#include "app/runs/sequence.h"
#include "app/scene/render_values.h"
#include "app/runs/exr_header.h"
#include "app/scene/light.h"
#include "app/cli/options.h"
#include "app/cli/options_sequence.h"
#include "app/quality/quality.h"
#include "app/runs/sequence_resume.h"
#include "app/runs/stage_times.h"
#include "app/runs/stop.h"
#include "io/atomic_file.h"
#include "io/encode_settings.h"
#include "io/exr_write.h"
#include "io/png_io.h"
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

bool sequence_active(const options *o) { return o->frame_count > 1 || o->animate_count > 0 || o->frame_range_set; }

static int frame_count(const options *o) { return o->frame_count > 0 ? o->frame_count : 1; }

/* Animation a's value at frame i: linear from FROM to TO, an integer flag's rounded. */
static double animated_value(const options_animation *a, int frame, int count)
{
    double t = count > 1 ? (double)frame / (double)(count - 1) : 0.0;
    double v = (1.0 - t) * a->from + t * a->to;
    double lo = fmin(a->from, a->to), hi = fmax(a->from, a->to);
    v = fmin(fmax(v, lo), hi);   /* rounding never steps outside FROM..TO (and so the flag's range) */
    return a->integer ? (double)llround(v) : v;
}

int sequence_frame_values(const options *base, int frame, const char **names, double *values)
{
    for (int k = 0; k < base->animate_count; ++k) {
        names[k] = base->animate[k].flag_name;
        values[k] = animated_value(&base->animate[k], frame, frame_count(base));
    }
    return base->animate_count;
}

int sequence_frame_options(const options *base, int frame, options *out)
{
    const char *names[OPTIONS_MAX_ANIMATE];
    double values[OPTIONS_MAX_ANIMATE];
    int count = sequence_frame_values(base, frame, names, values);
    int rc = options_frame(base, names, values, count, out);
    /* The run's colour choice (--quality auto's or --max-color-error's, made after the parse: main.c) is every
     * frame's: its header records it and names the sun the spectral image holds (32g). */
    if (rc == 0) out->spectral = base->spectral;
    return rc;
}

/* A --render value's file for a frame: the pattern filled in, or a value without one %d as it is. */
static bool frame_path(const char *output, int frame, char *path, size_t size)
{
    if (sequence_pattern_kind(output) == 1) return sequence_output_path(output, frame, path, size);
    return (size_t)snprintf(path, size, "%s", output) < size;
}

static bool same_luts(const sky_lut_quality *a, const sky_lut_quality *b)
{
    return a->transmittance_width == b->transmittance_width && a->transmittance_height == b->transmittance_height &&
           a->transmittance_steps == b->transmittance_steps && a->multiscatter_size == b->multiscatter_size &&
           a->multiscatter_steps == b->multiscatter_steps && a->multiscatter_sqrt_dirs == b->multiscatter_sqrt_dirs &&
           a->lut_f32 == b->lut_f32 && a->skyview_width == b->skyview_width && a->skyview_height == b->skyview_height;
}

/* A quality chosen by the scene (--quality auto, the default, or --max-error) is chosen once for the whole
 * sequence: for every scene class its frames pass through (all of them, whatever --frame-range renders, so that a
 * split sequence equals the whole), and the base options are parsed again under that choice. Frames then differ
 * only in view, sun and medium values: no preset switch (and no jump in the error) from one frame to the next. */
int sequence_choose_quality(options *base)
{
    if (base->animate_count == 0 || base->quality_classes == 0) return 0;
    unsigned classes = 0;
    for (int i = 0; i < frame_count(base); ++i) {
        options f;   /* the frame's view does not depend on the quality choice it is parsed under */
        if (sequence_frame_options(base, i, &f)) return 2;
        classes |= quality_class_bit(f.view.altitude_km, f.view.sun_elevation_deg);
    }
    int spectral = base->spectral;   /* --quality auto's or --max-color-error's colour pick (main.c), kept */
    options_release(base);   /* parsed again: a new unresolved copy */
    int rc = options_parse_for_classes(base, base->argc, base->argv, classes);
    if (rc == 0) base->spectral = spectral;
    return rc;
}

int sequence_check(options *base)
{
    if (sequence_choose_quality(base)) return 2;
    for (int i = base->frame_first; i <= base->frame_last; ++i) {
        options f;
        if (sequence_frame_options(base, i, &f)) return 2;
        if (f.width != base->width || f.height != base->height || f.render_scale != base->render_scale ||
            f.bloom_mips != base->bloom_mips || f.view.bloom != base->view.bloom ||
            !same_luts(&f.lut, &base->lut)) {
            fprintf(stderr, "vksky: --animate: frame %d changes the image or LUT sizes, the bloom chain or the quality "
                            "preset, which a sequence keeps; expected an animation of view, sun or medium values\n", i);
            return 2;
        }
        for (int k = 0; k < base->output_count; ++k) {
            char path[PATH_MAX], err[512];
            if (!frame_path(base->outputs[k], i, path, sizeof path)) {
                fprintf(stderr, "vksky: --render: '%s' makes a file name longer than %d bytes\n", base->outputs[k],
                        PATH_MAX - 1);
                return 2;
            }
            if (io_check_writable(path, err, sizeof err) != 0) {
                fprintf(stderr, "vksky: --render: %s\n", err);
                return 2;
            }
        }
    }
    return 0;
}

static bool is_exr(const char *path)
{
    size_t n = strlen(path);
    return n > 4 && strcasecmp(path + n - 4, ".exr") == 0;
}

/* The frame's files; EXRs with the header that says how they were made (exr_header.h). */
/* `first` (PATH_MAX bytes) gets the first output's path (the progress line's). Safe on several threads at once (frames
 * encoded together: host_ring.h). */
int sequence_write_outputs(const options *o, const frame_ring_pixels *px, int frame, bool sequence, char *first)
{
    char err[512];
    first[0] = '\0';
    for (int i = 0; i < o->output_count; ++i) {
        char path[PATH_MAX];
        if (!frame_path(o->outputs[i], frame, path, sizeof path)) return 1;   /* checked before */
        if (i == 0) snprintf(first, PATH_MAX, "%s", path);
        int rc;
        if (stop_requested()) return 1;   /* the graceful stop: no further output (one being written is dropped) */
        if (is_exr(path)) {
            exr_header h;
            if (exr_header_build(&h, o, sequence ? frame : -1) != 0) {
                fprintf(stderr, "vksky: %s: out of memory for the EXR header\n", path);
                return 1;
            }
            io_exr_layer layer = {.name = "", .rgba_half = px->linear};
            if (o->units != OPTIONS_UNITS_RELATIVE || o->exr_type == OPTIONS_EXR_FLOAT) {
                /* Photometric or --exr-type float: output units as floats (app/scene/light.h). */
                bool store_float = false;
                stage_mark t0 = stage_mark_now();
                float *scaled = light_exr_pixels(o, px->linear, (size_t)o->width * (size_t)o->height,
                                                 &store_float);
                stage_mark t1 = stage_mark_now();
                stage_add_since(STAGE_CONVERT, t0);
                rc = scaled ? io_write_exr_rgba_f32(path, o->width, o->height, scaled, store_float, &h.meta, err, sizeof err)
                            : (snprintf(err, sizeof err, "%s: out of memory for the EXR's pixels", path), 1);
                stage_add_since(STAGE_WRITE, t1);
                free(scaled);
            } else {
                stage_mark t0 = stage_mark_now();
                rc = io_write_exr_meta(path, o->width, o->height, &layer, 1, &h.meta, err, sizeof err);
                stage_add_since(STAGE_WRITE, t0);
            }
            exr_header_free(&h);
        } else {
            stage_mark t0 = stage_mark_now();
            rc = io_write_png(path, o->width, o->height, px->display, 1, err, sizeof err);
            stage_add_since(STAGE_WRITE, t0);
        }
        if (rc != 0) {
            if (!stop_requested()) fprintf(stderr, "vksky: %s\n", err);   /* else stop_status (app/runs/stop.h) says why */
            return 1;
        }
    }
    return 0;
}

int sequence_write_frame(const options *o, const frame_ring_pixels *px, int frame, bool sequence)
{
    char path[PATH_MAX];
    return sequence_write_outputs(o, px, frame, sequence, path);
}

/* A frame's progress line (not with --quiet). */
void sequence_frame_line(const options *base, int i, int done, const char *path, bool luts)
{
    if (base->quiet) return;
    fprintf(stderr, "vksky: frame %d (%d of %d; %d/%d of this job): %s, LUTs %s\n", i, i + 1, frame_count(base), done,
            base->frame_last - base->frame_first + 1, path, luts ? "computed" : "reused");
}

void sequence_summary_line(const options *base, int done, int skipped, int lut_computations)
{
    if (base->quiet) return;
    char skips[48] = "";   /* resumed: the frames kept count too */
    if (base->skip_existing) snprintf(skips, sizeof skips, ", %d skipped (written before)", skipped);
    fprintf(stderr, "vksky: %d frame%s rendered%s; LUTs computed %d time%s\n", done, done == 1 ? "" : "s", skips,
            lut_computations, lut_computations == 1 ? "" : "s");
}
