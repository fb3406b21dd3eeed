/* --help from the flag table (help.h). A flag's help text in the table is "METAVAR  description" for flags that take
 * a value and "description" for switches; here the metavar joins the flag in the first column. */
#include "app/cli/help.h"
#include <stdbool.h>
#include <string.h>

#define FLAG_COLUMN 2      /* "  --flag METAVAR" */
#define TEXT_COLUMN 28     /* descriptions start here */

typedef struct help_group {
    const char *title;
    const char *const *flags;   /* NULL-terminated */
} help_group;

static const char *const output_flags[] = {"--render", "--width", "--height", "--exposure", "--tonemap", "--no-bloom",
                                           "--bloom-mips", "--bloom-res", "--bloom-downsample", "--scene",
                                           "--list-scenes", "--dump-scene", "--projection", "--quiet",
                                           "--animate", "--frame-count", "--frame-range",
                                           "--skip-existing", "--threads", "--exr-compression", "--units",
                                           "--auto-exposure", "--exr-type", "--no-dither",
                                           NULL};
static const char *const camera_flags[] = {"--altitude", "--yaw", "--pitch", "--fov", NULL};
static const char *const sun_flags[] = {"--sun-elevation", "--sun-azimuth", "--date", "--time", "--utc-offset",
                                        "--latitude", "--longitude", "--elevation-m", "--sun-illuminance",
                                        "--sun-angular-radius", "--limb-darkening", "--no-sun-disc",
                                        "--sun-lux", NULL};
static const char *const atmosphere_flags[] = {"--rayleigh-scale", "--mie-scale", "--ozone-scale", "--mie-g",
                                               "--mie-phase", "--ground-albedo", "--no-multiscatter", "--sun-visibility",
                                               NULL};
static const char *const quality_flags[] = {"--quality", "--max-error", "--max-color-error",
                                            "--steps", "--max-steps", "--steps-ramp",
                                            "--sample-offset", "--step-distribution", "--sky-mode", "--sky-pass",
                                            "--post-pass",
                                            "--skyview-lut", "--skyview-steps", "--transmittance-lut",
                                            "--transmittance-steps", "--multiscatter-lut", "--multiscatter-dirs",
                                            "--multiscatter-steps", "--lut-format", "--render-scale", NULL};
static const char *const diagnostics_flags[] = {"--reference", "--path-trace", "--samples", "--spectral", "--irradiance", "--tilt", "--tilt-azimuth", "--bench", "--async-luts", "--frames",
                                                "--screenshot", "--validate", "--trace-barriers", "--trace-passes",
                                                "--timings", "--no-cache",
                                                "--list-devices", "--device", "--help", "--version", NULL};
static const help_group groups[] = {
    {"output", output_flags},       {"camera", camera_flags},   {"sun", sun_flags},
    {"atmosphere", atmosphere_flags}, {"quality", quality_flags}, {"diagnostics", diagnostics_flags},
};
#define GROUP_COUNT ((int)(sizeof groups / sizeof groups[0]))

const char *help_group_of(const char *flag_name)
{
    for (int g = 0; g < GROUP_COUNT; ++g)
        for (const char *const *f = groups[g].flags; *f; ++f)
            if (!strcmp(*f, flag_name)) return groups[g].title;
    return NULL;
}

/* `text` wrapped into lines of at most `width` characters, each after `indent` spaces (the first line's indent is
 * already printed by the caller). Breaks at spaces; a word longer than a line is cut. */
static void wrapped(FILE *out, const char *text, int indent, int width)
{
    bool first = true;
    while (*text) {
        while (*text == ' ') ++text;
        int n = (int)strlen(text);
        if (n > width) {
            n = width;
            while (n > 0 && text[n] != ' ') --n;
            if (n == 0) n = width;
        }
        if (!first) fprintf(out, "%*s", indent, "");
        fprintf(out, "%.*s\n", n, text);
        text += n;
        first = false;
    }
    if (first) fputc('\n', out);
}

static void print_flag(FILE *out, const help_entry *f)
{
    const char *help = f->help;
    while (*help == ' ') ++help;
    char head[64];
    int len;
    if (f->takes_value) {   /* the first word is the metavar */
        size_t m = strcspn(help, " ");
        len = snprintf(head, sizeof head, "%*s%s %.*s", FLAG_COLUMN, "", f->name, (int)m, help);
        help += m;
    } else {
        len = snprintf(head, sizeof head, "%*s%s", FLAG_COLUMN, "", f->name);
    }
    fputs(head, out);
    /* A head wider than the column: the description starts on the next line, in the same column. */
    if (len > TEXT_COLUMN - 3) fprintf(out, "\n%*s", TEXT_COLUMN, "");
    else fprintf(out, "%*s", TEXT_COLUMN - len, "");
    wrapped(out, help, TEXT_COLUMN, HELP_COLUMNS - TEXT_COLUMN);
}

void help_print(FILE *out, const help_entry *flags, int count)
{
    fprintf(out, "usage: vksky [options]                             interactive window (F1 lists the keys)\n"
                 "       vksky --render FILE.exr|FILE.png [options]  headless render\n"
                 "       vksky --bench N [options]                   benchmark\n"
                 "       vksky --scene NAME|FILE.json [options]      a shipped scene (--list-scenes) or a file\n"
                 "       vksky --scene FRAME.exr [options]           the scene an EXR by vksky was made from\n"
                 "       vksky --frame-count N --animate PARAM=FROM:TO --render 'f_%%04d.exr'  a sequence\n");
    for (int g = 0; g <= GROUP_COUNT; ++g) {
        bool any = false;
        for (int i = 0; i < count; ++i) {
            const char *group = help_group_of(flags[i].name);
            if (g < GROUP_COUNT ? group != groups[g].title : group != NULL) continue;
            if (!any) fprintf(out, "\n%s:\n", g < GROUP_COUNT ? groups[g].title : "other");
            any = true;
            print_flag(out, &flags[i]);
        }
    }
}

void help_print_section(FILE *out, const char *title, const char *preamble, const help_entry *flags, int count)
{
    fprintf(out, "\n%s:\n%s", title, preamble ? preamble : "");
    for (int i = 0; i < count; ++i) print_flag(out, &flags[i]);
}
