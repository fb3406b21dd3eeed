/* The rows of the model-error table (docs/model_error.md): camera altitude, sun elevation and view of each row, in the
 * table's order. One list for tools/model_error (which measures them) and tools/color_error (which measures the
 * spectral colour error on the same rows). Header-only: each tool is one source file. */
#ifndef VKSKY_TOOLS_MODEL_ROWS_H
#define VKSKY_TOOLS_MODEL_ROWS_H

/* One row: camera altitude (km), sun elevation, view (azimuth from the sun, elevation), in degrees. */
typedef struct row { double altitude, sun_el; const char *name; double az, el; } row;

/* The limb from 400 km: pitch -19.5 deg grazes the air ~12 km up, ~2200 km (~20 deg of arc) away; the sun's
 * elevation there is the camera's +20 deg looking toward the sun, -20 deg looking away, the same looking across. */
#define MAX_ROWS 64
static int build_rows(row *out)
{
    static const double sun_els[] = {90.0, 45.0, 20.0, 5.0, 2.0, 0.0, -2.0, -4.0, -6.0};
    static const struct { const char *name; double az, el; } ground_views[] = {
        {"zenith", 0.0, 90.0},
        {"toward sun, 2 deg up", 0.0, 2.0},
        {"away from sun, 2 deg up", 180.0, 2.0},
        {"30 deg up, 90 deg az", 90.0, 30.0},
    };
    static const struct { const char *name; double az, el; } air_views[] = {
        {"10 km: zenith", 0.0, 90.0},
        {"10 km: toward sun, level", 0.0, 0.0},
        {"10 km: away from sun, level", 180.0, 0.0},
    };
    static const row orbit[] = {
        {400.0, 0.0, "400 km: nadir, terminator below", 0.0, -90.0},
        {400.0, -4.0, "400 km: nadir, sun -4 below", 0.0, -90.0},
        {400.0, -20.0, "400 km: limb toward sun (sunset there)", 0.0, -19.5},
        {400.0, -16.0, "400 km: limb toward sun (sun +4 there)", 0.0, -19.5},
        {400.0, 20.0, "400 km: limb away from sun (sunset there)", 180.0, -19.5},
        {400.0, 0.0, "400 km: limb across the sun (sunset there)", 90.0, -19.5},
    };
    int n = 0;
    for (unsigned i = 0; i < sizeof sun_els / sizeof *sun_els; ++i)
        for (unsigned j = 0; j < sizeof ground_views / sizeof *ground_views; ++j)
            out[n++] = (row){0.001, sun_els[i], ground_views[j].name, ground_views[j].az, ground_views[j].el};
    for (unsigned i = 3; i < sizeof sun_els / sizeof *sun_els; ++i)
        if (sun_els[i] != 2.0)
            for (unsigned j = 0; j < sizeof air_views / sizeof *air_views; ++j)
                out[n++] = (row){10.0, sun_els[i], air_views[j].name, air_views[j].az, air_views[j].el};
    for (unsigned k = 0; k < sizeof orbit / sizeof *orbit; ++k)
        out[n++] = orbit[k];
    return n;
}

#endif
