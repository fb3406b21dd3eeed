/* The EXR header of a render (exr_header.h). */
#include "app/runs/exr_header.h"
#include "app/scene/scene_dump.h"
#include "app/scene/light.h"
#include "sky/view_params.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ITU-R BT.709 primaries and the D65 white point (CIE 1931 xy). */
static const float rec709_d65[8] = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};

/* worldToCamera (rows: p' = p M): camera axes in the columns, then the camera's position moved to the origin. */
static void world_to_camera(const sky_view *v, double m[16])
{
    double axes[3][3];   /* right, up, forward: camera x, y, z */
    sky_view_basis(v, axes[2], axes[0], axes[1]);
    const double eye[3] = {0.0, v->altitude_km, 0.0};
    memset(m, 0, 16 * sizeof m[0]);
    for (int c = 0; c < 3; ++c) {
        double t = 0.0;
        for (int r = 0; r < 3; ++r) {
            m[4 * r + c] = axes[c][r];
            t -= eye[r] * axes[c][r];
        }
        m[12 + c] = t;
    }
    m[15] = 1.0;
}

/* Camera -> NDC (rows): a camera point (x, y, z) lands at NDC x = (x / (z tx) + 1) / 2, y = (1 - y / (z ty)) / 2,
 * where tx, ty are the half-extents of the image plane at z = 1 (the sky pass's ray matrix, view_params.c); w = z. */
static void camera_to_ndc(const sky_view *v, int width, int height, double p[16])
{
    double ty = tan(0.5 * v->fov_deg * 3.14159265358979323846 / 180.0), tx = ty * width / height;
    memset(p, 0, 16 * sizeof p[0]);
    p[0] = 0.5 / tx;              /* x' = x / (2 tx) + z / 2 */
    p[8] = 0.5;
    p[5] = -0.5 / ty;             /* y' = -y / (2 ty) + z / 2 */
    p[9] = 0.5;
    p[14] = 1.0;                  /* z' = 1: z'/w = 1/z, a depth that falls with distance */
    p[11] = 1.0;                  /* w = z */
}

static void multiply(const double a[16], const double b[16], double out[16])
{
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            double s = 0.0;
            for (int k = 0; k < 4; ++k) s += a[4 * r + k] * b[4 * k + c];
            out[4 * r + c] = s;
        }
}

static char *scene_json(const options *o)
{
    char *text = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&text, &size);
    if (!f) return NULL;
    int rc = scene_dump(o, f);
    if (fclose(f) != 0 || rc != 0) {
        free(text);
        return NULL;
    }
    return text;
}

/* Quote a word for a POSIX shell when it needs it ('...' with ' as '\''). */
static size_t quoted(const char *w, char *out)
{
    bool plain = *w != '\0';
    for (const char *c = w; *c; ++c)
        plain = plain && (strchr("-_=+:,./%@", *c) || (*c >= '0' && *c <= '9') || (*c >= 'a' && *c <= 'z') ||
                          (*c >= 'A' && *c <= 'Z'));
    size_t n = 0;
    if (plain) {
        n = strlen(w);
        if (out) memcpy(out, w, n);
        return n;
    }
    if (out) out[n] = '\'';
    ++n;
    for (const char *c = w; *c; ++c) {
        if (*c == '\'') {
            if (out) memcpy(out + n, "'\\''", 4);
            n += 4;
        } else {
            if (out) out[n] = *c;
            ++n;
        }
    }
    if (out) out[n] = '\'';
    return n + 1;
}

char *exr_header_command_line(int argc, char **argv)
{
    char *text = NULL;   /* pass 0 measures, pass 1 writes */
    for (int pass = 0; pass < 2; ++pass) {
        size_t n = 0;
        char *out = pass ? text : NULL;
        n += quoted("vksky", out ? out + n : NULL);
        for (int i = 1; i < argc; ++i) {
            /* Flags that never change the image or the file's bytes (which frames a job renders, how many
             * threads encode): left out, so that every job and every thread count writes the same file. */
            if (!strcmp(argv[i], "--frame-range") || !strcmp(argv[i], "--threads")) {
                ++i;
                continue;
            }
            if (!strncmp(argv[i], "--frame-range=", 14) || !strncmp(argv[i], "--threads=", 10)) continue;
            if (!strcmp(argv[i], "--skip-existing")) continue;   /* how a job resumed, not what the frame is */
            if (!strcmp(argv[i], "--timings")) continue;   /* a report on stderr (issue 27), not the image */
            if (out) out[n] = ' ';
            ++n;
            n += quoted(argv[i], out ? out + n : NULL);
        }
        if (pass) {
            out[n] = '\0';
            return out;
        }
        text = malloc(n + 1);
        if (!text) return NULL;
    }
    return NULL;
}

int exr_header_build(exr_header *h, const options *o, int frame)
{
    memset(h, 0, sizeof *h);
    memcpy(h->chromaticities, rec709_d65, sizeof rec709_d65);
    double to_camera[16], to_ndc_from_camera[16], to_ndc[16];
    world_to_camera(&o->view, to_camera);
    camera_to_ndc(&o->view, o->width, o->height, to_ndc_from_camera);
    multiply(to_camera, to_ndc_from_camera, to_ndc);
    for (int i = 0; i < 16; ++i) h->world_to_camera[i] = (float)to_camera[i], h->world_to_ndc[i] = (float)to_ndc[i];
    h->scene_json = scene_json(o);
    h->command_line = exr_header_command_line(o->argc, o->argv);
    if (!h->scene_json || !h->command_line) {
        exr_header_free(h);
        return 1;
    }
    snprintf(h->software, sizeof h->software, "vksky %s", VKSKY_VERSION);
    int n = 0;
    h->strings[n++] = (io_exr_string_attr){"owner", h->software};
    h->strings[n++] = (io_exr_string_attr){"software", h->software};
    h->strings[n++] = (io_exr_string_attr){EXR_HEADER_SCENE, h->scene_json};
    h->strings[n++] = (io_exr_string_attr){EXR_HEADER_COMMAND_LINE, h->command_line};
    h->meta = (io_exr_meta){.chromaticities = h->chromaticities, .world_to_camera = h->world_to_camera,
                            .world_to_ndc = h->world_to_ndc, .strings = h->strings,
                            .int_name = frame >= 0 ? EXR_HEADER_FRAME : NULL, .int_value = frame};
    /* The sun (direction, illuminance above the air and at the camera) and what the pixels' numbers mean. In relative
     * units only the pixels' unit is named: the sun attributes are the environment maps' (io/exr_stream.c), and a
     * relative render's header stays as it was. */
    light_sky_attrs(o, &h->sky);
    h->sky.has_sun = o->units == OPTIONS_UNITS_PHOTOMETRIC;
    h->meta.sky = &h->sky;
    const sun_place *p = &o->place;
    if (sun_place_any(p)) {
        /* OpenEXR's capture attributes: capDate "YYYY:MM:DD hh:mm:ss" local, utcOffset = UTC - local in seconds,
         * the place in degrees and metres. */
        snprintf(h->cap_date, sizeof h->cap_date, "%04d:%02d:%02d %02d:%02d:%02d", p->when.year % 10000,
                 p->when.month % 100, p->when.day % 100, p->when.hour % 100, p->when.minute % 100,
                 (int)p->when.second % 100);
        h->strings[n++] = (io_exr_string_attr){"capDate", h->cap_date};
        const char *names[4] = {"utcOffset", "latitude", "longitude", "altitude"};
        const float values[4] = {(float)(-3600.0 * p->when.utc_offset_h), (float)p->where.latitude_deg,
                                 (float)p->where.longitude_deg, (float)p->where.elevation_m};
        for (int i = 0; i < 4; ++i) h->meta.float_names[i] = names[i], h->meta.float_values[i] = values[i];
    }
    h->meta.string_count = n;
    return 0;
}

void exr_header_free(exr_header *h)
{
    free(h->scene_json);
    free(h->command_line);
    h->scene_json = h->command_line = NULL;
}
