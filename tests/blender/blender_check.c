/* blender_check: what tests/blender/blender_test.sh asserts about a composite of a real Blender render (issue 28).
 *
 *   blender_check camera RENDER.exr LAYER SPHERES.txt YAW PITCH FOV CX,CY,CZ
 *     Each sphere of SPHERES.txt ("x y z r" per line, Blender's world) projected by vksky's camera convention (yaw
 *     from +Y toward +X, pitch above the horizon, vertical fov; docs/aerial_perspective.md "Conventions"), computed
 *     here on its own, against the alpha-weighted centroid of the pixels whose Position lies on that sphere in
 *     Blender's render: within 0.35 px (the export and the convention agree with Blender's camera).
 *   blender_check edges OUT.exr RENDER.exr LAYER SKY.exr
 *     Every edge pixel (0 < alpha < 1) of the composite against its coverage-correct value built from pixels no
 *     edge handling touches: beauty T + alpha S with T and S of the nearest fully covered pixel (alpha 1, a
 *     position), plus (1 - alpha) x a plain sky render of the same camera (SKY.exr): no edge pixel's luminance below
 *     0.5x, the mean within 5 %.
 * Exit 0 ok, 1 a failed check or an unreadable file. */
#include "io/exr_read.h"
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static float *read_all(const char *path, const char *const *names, int count, int *w, int *h)
{
    io_exr_info info;
    char err[512];
    if (io_exr_read_info(path, &info, err, sizeof err) != 0) {
        fprintf(stderr, "blender_check: %s\n", err);
        return NULL;
    }
    *w = info.width, *h = info.height;
    io_exr_info_free(&info);
    float *out = malloc((size_t)*w * *h * count * sizeof(float));
    if (!out || io_exr_read_channels(path, names, count, out, err, sizeof err) != 0) {
        fprintf(stderr, "blender_check: %s\n", out ? err : "out of memory");
        free(out);
        return NULL;
    }
    return out;
}

/* LAYER.Combined.RGBA and LAYER.Position.XYZ, 7 floats per pixel. */
static float *read_render(const char *path, const char *layer, int *w, int *h)
{
    static const char *const pass[7] = {"Combined.R", "Combined.G", "Combined.B", "Combined.A",
                                        "Position.X", "Position.Y", "Position.Z"};
    char buf[7][300];
    const char *names[7];
    for (int k = 0; k < 7; ++k) snprintf(buf[k], sizeof buf[k], "%s.%s", layer, pass[k]), names[k] = buf[k];
    return read_all(path, names, 7, w, h);
}

static double luminance(const float *rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static int check_camera(char **argv)
{
    int w, h;
    float *in = read_render(argv[2], argv[3], &w, &h);
    FILE *f = fopen(argv[4], "r");
    double yaw = atof(argv[5]) * (3.14159265358979323846 / 180.0), pitch = atof(argv[6]) * (3.14159265358979323846 / 180.0), fov = atof(argv[7]) * (3.14159265358979323846 / 180.0);
    double cam[3];
    if (!in || !f || sscanf(argv[8], "%lf,%lf,%lf", &cam[0], &cam[1], &cam[2]) != 3) {
        fprintf(stderr, "blender_check: cannot read %s or %s\n", argv[2], argv[4]);
        return 1;
    }
    /* Blender's world: north +Y, east +X, up +Z. */
    double fw[3] = {cos(pitch) * sin(yaw), cos(pitch) * cos(yaw), sin(pitch)};
    double right[3] = {cos(yaw), -sin(yaw), 0.0};   /* forward x up, normalised: azimuth + 90 */
    double up[3] = {right[1] * fw[2] - right[2] * fw[1], right[2] * fw[0] - right[0] * fw[2],
                    right[0] * fw[1] - right[1] * fw[0]};
    double ty = tan(0.5 * fov), tx = ty * w / h, worst = 0.0;
    int spheres = 0, bad = 0;
    double c[3], r;
    while (fscanf(f, "%lf %lf %lf %lf", &c[0], &c[1], &c[2], &r) == 4) {
        double d[3] = {c[0] - cam[0], c[1] - cam[1], c[2] - cam[2]};
        double z = dot(d, fw), px = (dot(d, right) / (z * tx) + 1.0) * 0.5 * w, py = (1.0 - dot(d, up) / (z * ty)) * 0.5 * h;
        double sx = 0.0, sy = 0.0, sa = 0.0;
        for (long i = 0; i < (long)w * h; ++i) {
            const float *p = in + 7 * i;
            double q[3] = {p[4] - c[0], p[5] - c[1], p[6] - c[2]};
            if (!(fabs(sqrt(dot(q, q)) - r) < 0.01 * r)) continue;
            sx += p[3] * ((double)(i % w) + 0.5), sy += p[3] * ((double)(i / w) + 0.5), sa += p[3];
        }
        if (sa < 4.0) continue;   /* hidden or too small to measure */
        double e = hypot(sx / sa - px, sy / sa - py);
        printf("blender_check: sphere at %.0f m: vksky's projection (%.2f, %.2f), Blender's centroid (%.2f, %.2f): "
               "%.3f px\n", sqrt(dot(d, d)), px, py, sx / sa, sy / sa, e);
        worst = fmax(worst, e), ++spheres, bad += !(e < 0.35);
    }
    fclose(f);
    free(in);
    printf("blender_check: %d spheres, worst %.3f px\n", spheres, worst);
    return bad || spheres < 2;
}

static int check_edges(char **argv)
{
    static const char *const out_names[] = {"R", "G", "B", "transmittance.R", "transmittance.G", "transmittance.B",
                                            "rayleigh.R", "rayleigh.G", "rayleigh.B", "mie.R", "mie.G", "mie.B"};
    static const char *const rgb[] = {"R", "G", "B"};
    int w, h, wi, hi, ws, hs;
    float *o = read_all(argv[2], out_names, 12, &w, &h), *in = read_render(argv[3], argv[4], &wi, &hi);
    float *sky = read_all(argv[5], rgb, 3, &ws, &hs);
    if (!o || !in || !sky || w != wi || h != hi || w != ws || h != hs) {
        fprintf(stderr, "blender_check: unreadable files or sizes that differ\n");
        return 1;
    }
    long edges = 0, dark = 0, lone = 0;
    double sum_out = 0.0, sum_ref = 0.0, worst = INFINITY;
    for (long i = 0; i < (long)w * h; ++i) {
        float a = in[7 * i + 3];
        if (!(a > 0.0f && a < 1.0f)) continue;
        int x = (int)(i % w), y = (int)(i / w);
        long best = -1;
        int best_d2 = 1 << 30;
        for (int dy = -4; dy <= 4; ++dy)
            for (int dx = -4; dx <= 4; ++dx) {
                int xx = x + dx, yy = y + dy, d2 = dx * dx + dy * dy;
                if (xx < 0 || yy < 0 || xx >= w || yy >= h || d2 >= best_d2) continue;
                const float *q = in + 7 * ((size_t)yy * w + xx);
                bool has = isfinite(q[4]) && isfinite(q[5]) && isfinite(q[6]) && (q[4] != 0 || q[5] != 0 || q[6] != 0);
                if (q[3] >= 0.999f && has) best = (long)yy * w + xx, best_d2 = d2;
            }
        if (best < 0) {
            ++lone;
            continue;
        }
        const float *n = o + 12 * best;
        float ref[3];
        for (int c = 0; c < 3; ++c)
            ref[c] = in[7 * i + c] * n[3 + c] + a * (n[6 + c] + n[9 + c]) + (1.0f - a) * sky[3 * i + c];
        double lo = luminance(o + 12 * i), lr = luminance(ref), ratio = lr > 0.0 ? lo / lr : 1.0;
        ++edges, sum_out += lo, sum_ref += lr;
        if (ratio < worst) worst = ratio;
        if (!(ratio >= 0.5)) {
            if (dark < 5)
                fprintf(stderr, "blender_check: edge pixel (%d, %d), alpha %.3f: %.4g, coverage-correct %.4g (%.2fx)\n",
                        x, y, a, lo, lr, ratio);
            ++dark;
        }
    }
    double mean = sum_ref > 0.0 ? sum_out / sum_ref : 0.0;
    printf("blender_check: %ld edge pixels (%ld without a covered neighbour, not counted): darkest %.3fx their "
           "coverage-correct value, mean %.4fx\n", edges, lone, worst, mean);
    free(o);
    free(in);
    free(sky);
    return dark > 0 || edges < 20 || fabs(mean - 1.0) > 0.05;
}

int main(int argc, char **argv)
{
    if (argc == 9 && !strcmp(argv[1], "camera")) return check_camera(argv);
    if (argc == 6 && !strcmp(argv[1], "edges")) return check_edges(argv);
    fprintf(stderr, "usage: blender_check camera RENDER.exr LAYER SPHERES.txt YAW PITCH FOV CX,CY,CZ\n"
                    "       blender_check edges OUT.exr RENDER.exr LAYER SKY.exr\n");
    return 1;
}
