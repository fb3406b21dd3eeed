/* --animate, --frame-count, --frame-range (options_sequence.h). */
#include "app/cli/options_sequence.h"
#include "app/cli/bad_value.h"
#include "app/cli/flags.h"
#include "app/scene/sun_place.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Flags whose value sizes the renderer's images or LUTs (made once for the whole sequence), picks the quality, or is
 * not about the picture: numeric, but not animatable. */
static bool fixed_for_a_sequence(const char *n)
{
    static const char *const names[] = {"--width", "--height", "--render-scale", "--bloom-mips", "--multiscatter-lut",
                                        "--multiscatter-dirs", "--multiscatter-steps", "--transmittance-steps",
                                        "--max-error", "--bench", "--frames", "--device", "--samples",
                                        "--frame-count"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
        if (!strcmp(n, names[i])) return true;
    return false;
}

/* A whole-string finite number. */
static bool number(const char *s, size_t n, double *out)
{
    char buf[64];
    if (n == 0 || n >= sizeof buf) return false;
    memcpy(buf, s, n);
    buf[n] = '\0';
    char *end = NULL;
    errno = 0;
    double v = strtod(buf, &end);
    if (end == buf || *end != '\0' || errno == ERANGE || !isfinite(v)) return false;
    *out = v;
    return true;
}

static int parse_animate(options *o, const char *value)
{
    const char *n = "--animate";
    static const char *const form = "is not PARAM=FROM:TO; expected e.g. sun-elevation=-2:30 or time=5.5:8";
    const char *eq = strchr(value, '=');
    if (!eq || eq == value) return bad_value(n, value, form);
    char name[64] = "--";
    const char *param = !strncmp(value, "--", 2) ? value + 2 : value;
    size_t param_len = (size_t)(eq - param);
    if (eq < param || param_len + 3 > sizeof name) return bad_value(n, value, form);
    memcpy(name + 2, param, param_len);
    name[2 + param_len] = '\0';
    bool time = !strcmp(name, "--time");
    const flag *f = flags_find(name, strlen(name));
    if (!time && (!f || (f->kind != ARG_INT && f->kind != ARG_DOUBLE) || fixed_for_a_sequence(name))) {
        char why[200];
        snprintf(why, sizeof why, "%s; expected a numeric flag without '--' (sun-elevation, sun-azimuth, altitude, "
                 "yaw, pitch, fov, exposure, mie-g, ...) or time", !f ? "names no flag"
                 : (f->kind != ARG_INT && f->kind != ARG_DOUBLE) ? "is not a numeric flag" : "is fixed for a sequence "
                 "(it sizes the renderer or is not about the picture)");
        return bad_value(n, value, why);
    }
    const char *colon = strchr(eq + 1, ':');
    double from, to;
    if (!colon || strchr(colon + 1, ':') || !number(eq + 1, (size_t)(colon - eq - 1), &from) ||
        !number(colon + 1, strlen(colon + 1), &to))
        return bad_value(n, value, form);
    double lo = time ? 0.0 : f->min, hi = time ? 24.0 : f->max;
    if (from < lo || to < lo || from > hi || to > hi || (time && (from >= 24.0 || to >= 24.0))) {
        char why[160];
        snprintf(why, sizeof why, time ? "is outside the day; expected hours FROM and TO in [0, 24) (e.g. time=5.5:8 "
                 "for 05:30 to 08:00)" : "is out of range; expected FROM and TO in [%g, %g]", lo, hi);
        return bad_value(n, value, why);
    }
    /* A PARAM given again replaces its animation (a later flag overrides, as everywhere; the parser's first pass also
     * applies --animate, for an animated time). */
    int slot = o->animate_count;
    for (int i = 0; i < o->animate_count; ++i)
        if (!strcmp(o->animate[i].flag_name, time ? "--time" : f->name)) slot = i;
    if (slot == OPTIONS_MAX_ANIMATE) return bad_value(n, value, "is one too many; at most 16 parameters");
    if (slot == o->animate_count) ++o->animate_count;
    o->animate[slot] = (options_animation){time ? "--time" : f->name, !time && f->kind == ARG_INT,
                                                         from, to};
    if (time) {   /* the sun is given by date and place: until a frame's own time, the first frame's */
        char text[16];
        sequence_time_text(from, text);
        if (sun_place_parse_time(&o->place, "--animate", text)) return 2;
        o->place.from_flags = true;
    }
    return 0;
}

static int parse_range(options *o, const char *value)
{
    const char *n = "--frame-range";
    char *end = NULL;
    errno = 0;
    long a = strtol(value, &end, 10);
    if (end == value || *end != ':' || value[0] == '-' || value[0] == '+') goto malformed;
    const char *second = end + 1;
    long b = strtol(second, &end, 10);
    if (end == second || *end != '\0' || second[0] == '-' || second[0] == '+' || errno == ERANGE) goto malformed;
    if (a > b) return bad_value(n, value, "is empty; expected A:B with A <= B (frames A to B, inclusive, from 0)");
    if (b > 1000000) return bad_value(n, value, "is out of range; expected frames from 0 to --frame-count - 1");
    o->frame_first = (int)a, o->frame_last = (int)b, o->frame_range_set = true;
    return 0;
malformed:
    return bad_value(n, value, "is not a frame range; expected A:B, frames A to B inclusive, from 0 (e.g. 0:99)");
}

int options_sequence_apply(options *o, const char *n, const char *value, double x)
{
    if (!strcmp(n, "--animate")) return parse_animate(o, value);
    if (!strcmp(n, "--frame-count")) return o->frame_count = (int)x, 0;
    if (!strcmp(n, "--frame-range")) return parse_range(o, value);
    if (!strcmp(n, "--skip-existing")) return o->skip_existing = true, 0;
    return -1;
}

bool options_sequence_named(int argc, char **argv)
{
    static const char *const names[] = {"--animate", "--frame-count", "--frame-range"};
    for (int i = 1; i < argc; ++i)
        for (size_t k = 0; k < sizeof names / sizeof names[0]; ++k) {
            size_t n = strlen(names[k]);
            if (!strncmp(argv[i], names[k], n) && (argv[i][n] == '\0' || argv[i][n] == '=')) return true;
        }
    return false;
}

int options_sequence_resolve(options *o)
{
    int count = o->frame_count > 0 ? o->frame_count : 1;
    bool sequence = count > 1 || o->animate_count > 0 || o->frame_range_set;
    if (!o->frame_range_set) o->frame_first = 0, o->frame_last = count - 1;
    if (o->skip_existing && !sequence) {
        fprintf(options_report_stream(),
                "vksky: --skip-existing: only with a sequence (--frame-count, --animate or --frame-range), whose "
                "frames it resumes\n");
        return 2;
    }
    /* With --bench as well, the sequence is the benchmark's frames to disk (issue 27: frames/s). */
    if (sequence && (o->output_count == 0 || o->reference)) {
        fprintf(options_report_stream(),
                "vksky: %s: only with --render (a sequence of frames written to files, --bench: timed; not "
                "with --reference or the window)\n",
                o->animate_count ? "--animate" : o->frame_range_set ? "--frame-range" : "--frame-count");
        return 2;
    }
    if (o->frame_last >= count) {
        char text[48], why[120];
        snprintf(text, sizeof text, "%d:%d", o->frame_first, o->frame_last);
        snprintf(why, sizeof why, "is outside the sequence; expected frames within 0:%d (--frame-count %d)", count - 1,
                 count);
        return bad_value("--frame-range", text, why);
    }
    for (int i = 0; i < o->output_count; ++i) {
        int kind = sequence_pattern_kind(o->outputs[i]);
        if (kind < 0 && sequence)
            return bad_value("--render", o->outputs[i], "has a '%' other than one %d (e.g. %04d) for the frame number; "
                                                  "write %% for a literal '%'");
        if (kind == 0 && count > 1)
            return bad_value("--render", o->outputs[i], "has no frame number; with --frame-count > 1 expected a pattern with "
                                                  "one %d, e.g. sky_%04d.exr");
    }
    return 0;
}

/* The conversion at s (just after a '%'): its width and zero flag and length; false if it is not [0][1-9]?d. */
static bool conversion(const char *s, bool *zero, int *width, size_t *len)
{
    size_t k = 0;
    *zero = s[k] == '0';
    if (*zero) ++k;
    *width = 0;
    if (s[k] >= '1' && s[k] <= '9') *width = s[k++] - '0';
    if (s[k] != 'd') return false;
    *len = k + 1;
    return true;
}

int sequence_pattern_kind(const char *p)
{
    int found = 0;
    for (size_t i = 0; p[i]; ++i) {
        if (p[i] != '%') continue;
        if (p[i + 1] == '%') {
            ++i;
            continue;
        }
        bool zero;
        int width;
        size_t len;
        if (!conversion(p + i + 1, &zero, &width, &len) || found) return -1;
        found = 1;
        i += len;
    }
    return found;
}

bool sequence_output_path(const char *p, int frame, char *out, size_t out_size)
{
    size_t n = 0;
    for (size_t i = 0; p[i]; ++i) {
        char piece[32];
        size_t piece_len = 1;
        piece[0] = p[i];
        if (p[i] == '%' && p[i + 1] == '%') {
            ++i;
        } else if (p[i] == '%') {
            bool zero;
            int width;
            size_t len;
            if (!conversion(p + i + 1, &zero, &width, &len)) return false;
            piece_len = (size_t)snprintf(piece, sizeof piece, zero ? "%0*d" : "%*d", width, frame);
            i += len;
        }
        if (n + piece_len >= out_size) return false;
        memcpy(out + n, piece, piece_len);
        n += piece_len;
    }
    out[n] = '\0';
    return true;
}

void sequence_time_text(double hours, char out[16])
{
    long long ms = llround(hours * 3600000.0);
    if (ms < 0) ms = 0;
    if (ms > 86399999) ms = 86399999;
    snprintf(out, 16, "%02u:%02u:%02u.%03u", (unsigned)(ms / 3600000), (unsigned)(ms / 60000 % 60),
             (unsigned)(ms / 1000 % 60), (unsigned)(ms % 1000));
}
