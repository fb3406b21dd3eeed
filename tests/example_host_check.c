/* The example host's picture (examples/sky_host.c --offscreen, the scene of examples/sky_host_scene.h) against
 * independent computations:
 *  (a) its sky pixels (alpha 0: no geometry) equal `vksky --render` of the same view (HOST and CLI EXRs), within 2e-3
 *      relative: both are fp16 (2^-11) of the same march along rays built from two ray matrices (the library's from
 *      the host's matrices, the CLI's from yaw and pitch) that agree to float rounding. Rows below 1 degree of
 *      elevation are left out: the CLI resolves the horizon's coverage there, the host's ground covers it;
 *  (b) each mirror pair of boxes (albedos a1, a2, Lambert radiance L = a / pi x E cos(sun elevation), E the scene's
 *      sun) gives T = (o1 - o2) / (L1 - L2) and S = o2 - L2 T at its face's centre; against the CPU reference along
 *      the camera -> face segment (ref_radiance_to_point, converged): T within 5e-3 (fp16 of o1, o2 near 1.7 and
 *      0.3: < 1e-3; the march's steps), S within 6 % (the "high" preset's LUTs and march; test_aerial measures the
 *      pass within 2 % with converged LUTs); and the far pair is hazier than the near: smaller T, larger S, and its
 *      pixel further on the way from its own radiance to the sky behind it (the CLI's pixel there).
 *  (c) with HOST.png (the same frame written --offscreen W H OUT.png): each pixel is the window's tone map of the EXR's
 *      pixel (exposure 1, Reinhard x / (1 + x), then the sRGB transfer function of IEC 61966-2-1, computed here in
 *      double) within 1 of 255, alpha 255.
 *   example_host_check HOST.exr CLI.exr [HOST.png] */
#include "../examples/sky_host_scene.h"
#include "io/exr_read.h"
#include "io/png_io.h"
#include "reference/ref_atmosphere.h"
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

static int failures;
#define CHECK(cond, ...)                                                                                             \
    do {                                                                                                             \
        if (!(cond)) {                                                                                               \
            ++failures;                                                                                              \
            fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                                          \
            fprintf(stderr, __VA_ARGS__);                                                                            \
            fputc('\n', stderr);                                                                                     \
        }                                                                                                            \
    } while (0)
static const double DEG = 3.14159265358979323846 / 180.0;

static float *read_rgba(const char *path, int *w, int *h)
{
    io_exr_info info;
    char err[256];
    if (io_exr_read_info(path, &info, err, sizeof err) != 0) {
        fprintf(stderr, "example_host_check: %s: %s\n", path, err);
        exit(1);
    }
    *w = info.width, *h = info.height;
    io_exr_info_free(&info);
    float *px = malloc(sizeof(float) * 4 * (size_t)*w * *h);
    const char *names[4] = {"R", "G", "B", "A"};
    if (!px || io_exr_read_channels(path, names, 4, px, err, sizeof err) != 0) {
        fprintf(stderr, "example_host_check: %s: %s\n", path, px ? err : "out of memory");
        exit(1);
    }
    return px;
}

/* The pixel whose ray (the CLI's convention, ref_pixel_dir) is closest to the local direction v. */
static void pixel_of(const double v[3], int w, int h, int *px, int *py)
{
    double best = -2.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double d[3];
            ref_pixel_dir(x, y, w, h, SCENE_YAW_DEG * DEG, SCENE_PITCH_DEG * DEG, SCENE_FOV_DEG * DEG, d);
            double c = d[0] * v[0] + d[1] * v[1] + d[2] * v[2];
            if (c > best) best = c, *px = x, *py = y;
        }
}

typedef struct pair_result { double T[3], S[3], haze; } pair_result;

/* A mirror pair: boxes b (x < 0) and b + 1 (x > 0) at the same distance. */
static pair_result measure_pair(const float *host, const float *cli, int w, int h, int b, const model_atmosphere *a)
{
    const scene_box *p = &SCENE_BOXES[b], *q = &SCENE_BOXES[b + 1];
    /* The face centre seen from the camera, in the local frame (north, up, east) = world (-z, y, x). */
    double v[3] = {p->distance_m, 0.5 * p->height_m - SCENE_CAMERA_HEIGHT_M, p->x_m}, n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; ++i) v[i] /= n;
    int x = 0, y = 0;
    pixel_of(v, w, h, &x, &y);
    int xm = w - 1 - x;   /* the mirror pixel: the same air */
    double d[3];
    ref_pixel_dir(x, y, w, h, SCENE_YAW_DEG * DEG, SCENE_PITCH_DEG * DEG, SCENE_FOV_DEG * DEG, d);
    double t_km = p->distance_m / d[0] * 1e-3;   /* to the face's plane along the pixel's ray */
    double sun[3];
    ref_dir(SCENE_SUN_AZIMUTH_DEG * DEG, SCENE_SUN_ELEVATION_DEG * DEG, sun);
    ref_aerial ref;
    ref_radiance_to_point(a, SCENE_CAMERA_HEIGHT_M * 1e-3, d, sun, t_km, ref_quality_converged(), &ref);
    const float *o1 = host + 4 * ((size_t)y * w + x), *o2 = host + 4 * ((size_t)y * w + xm), *sky = cli + 4 * ((size_t)y * w + x);
    CHECK(o1[3] == 1.0f && o2[3] == 1.0f, "pair %d: pixels (%d, %d) and (%d, %d) are not geometry", b, x, y, xm, y);
    pair_result r;
    double cos_sun = cos(SCENE_SUN_ELEVATION_DEG * DEG), moved2 = 0.0, way2 = 0.0;
    for (int c = 0; c < 3; ++c) {
        double l1 = p->albedo / (180.0 * DEG) * a->sun_illuminance[c] * cos_sun, l2 = q->albedo / (180.0 * DEG) * a->sun_illuminance[c] * cos_sun;
        r.T[c] = (o1[c] - o2[c]) / (l1 - l2);
        r.S[c] = o2[c] - l2 * r.T[c];
        double S_ref = ref.rayleigh[c] + ref.mie[c];
        CHECK(fabs(r.T[c] - ref.transmittance[c]) <= 5e-3, "pair at %.0f m, channel %d: T %.5f, the reference %.5f",
              p->distance_m, c, r.T[c], ref.transmittance[c]);
        CHECK(fabs(r.S[c] - S_ref) <= 0.06 * S_ref, "pair at %.0f m, channel %d: S %.5f, the reference %.5f",
              p->distance_m, c, r.S[c], S_ref);
        moved2 += (o1[c] - l1) * (o1[c] - l1);
        way2 += (sky[c] - l1) * (sky[c] - l1);
    }
    /* The share of the way from the box's own radiance to the sky behind it (the CLI's pixel) that the air has moved
     * its pixel: 0 in vacuum, 1 lost in the haze. */
    r.haze = sqrt(moved2 / way2);
    printf("pair at %5.0f m (pixel %d, %d | %d): T %.4f %.4f %.4f (ref %.4f %.4f %.4f), S %.4f %.4f %.4f (ref %.4f %.4f "
           "%.4f), moved toward the sky %.3f\n", p->distance_m, x, y, xm, r.T[0], r.T[1], r.T[2], ref.transmittance[0],
           ref.transmittance[1], ref.transmittance[2], r.S[0], r.S[1], r.S[2], ref.rayleigh[0] + ref.mie[0],
           ref.rayleigh[1] + ref.mie[1], ref.rayleigh[2] + ref.mie[2], r.haze);
    return r;
}

static double srgb_encode(double linear)
{
    double c = fmin(fmax(linear, 0.0), 1.0);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

/* (c): the PNG against the tone map of the EXR's pixels. */
static void check_png(const char *path, const float *host, int w, int h)
{
    int pw = 0, ph = 0;
    uint8_t *px = NULL;
    char err[256];
    if (io_read_png(path, &pw, &ph, &px, err, sizeof err) != 0) {
        CHECK(0, "%s: %s", path, err);
        return;
    }
    CHECK(pw == w && ph == h, "the PNG is %dx%d, the EXR %dx%d", pw, ph, w, h);
    double worst = 0.0;
    for (int i = 0; pw == w && ph == h && i < w * h; ++i) {
        for (int c = 0; c < 3; ++c) {
            double x = host[4 * i + c], want = 255.0 * srgb_encode(x / (1.0 + x));
            worst = fmax(worst, fabs(px[4 * i + c] - want));
            CHECK(fabs(px[4 * i + c] - want) <= 1.0, "PNG pixel %d channel %d: %u, the tone map of the EXR's %g is %.2f",
                  i, c, px[4 * i + c], x, want);
        }
        CHECK(px[4 * i + 3] == 255, "PNG pixel %d: alpha %u", i, px[4 * i + 3]);
    }
    printf("png: %dx%d, the tone map of the EXR's pixels within %.2f of 255 (bound 1)\n", pw, ph, worst);
    free(px);
}

int main(int argc, char **argv)
{
    if (argc != 3 && argc != 4) {
        fprintf(stderr, "usage: example_host_check HOST.exr CLI.exr [HOST.png]\n");
        return 2;
    }
    int w, h, cw, ch;
    float *host = read_rgba(argv[1], &w, &h), *cli = read_rgba(argv[2], &cw, &ch);
    CHECK(w == cw && h == ch, "sizes differ: %dx%d and %dx%d", w, h, cw, ch);
    if (failures) return 1;
    model_atmosphere earth;
    model_atmosphere_earth(&earth);

    /* (a) the sky. */
    int sky = 0;
    double worst = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float *p = host + 4 * ((size_t)y * w + x), *q = cli + 4 * ((size_t)y * w + x);
            double d[3];
            ref_pixel_dir(x, y, w, h, SCENE_YAW_DEG * DEG, SCENE_PITCH_DEG * DEG, SCENE_FOV_DEG * DEG, d);
            if (p[3] != 0.0f || d[1] < sin(1.0 * DEG)) continue;
            for (int c = 0; c < 3; ++c) {
                double e = fabs(p[c] - q[c]) / fmax(fabs(q[c]), 1e-6);
                worst = fmax(worst, e);
                CHECK(e <= 2e-3, "sky pixel (%d, %d) channel %d: host %g, vksky --render %g", x, y, c, p[c], q[c]);
            }
            ++sky;
        }
    printf("sky: %d pixels, largest relative difference from vksky --render %.2e (bound 2e-3)\n", sky, worst);
    CHECK(sky >= w * h / 4, "only %d sky pixels", sky);

    /* (b) the boxes. */
    pair_result near = measure_pair(host, cli, w, h, 0, &earth), far = measure_pair(host, cli, w, h, 2, &earth);
    for (int c = 0; c < 3; ++c)
        CHECK(far.T[c] < near.T[c] && far.S[c] > near.S[c], "channel %d: the far pair is not hazier (T %.4f vs %.4f, "
              "S %.4f vs %.4f)", c, far.T[c], near.T[c], far.S[c], near.S[c]);
    CHECK(far.haze > near.haze, "the far box has moved no further toward the sky's colour (%.3f) than the near one "
          "(%.3f)", far.haze, near.haze);
    if (argc == 4) check_png(argv[3], host, w, h);
    free(host), free(cli);
    if (failures) fprintf(stderr, "example_host_check: %d failure(s)\n", failures);
    return failures ? 1 : 0;
}
