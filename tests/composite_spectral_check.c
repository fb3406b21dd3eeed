/* composite_spectral_check RENDER.exr SPECTRAL.exr RGB.exr SUN_EL SUN_AZ BOUND: `vksky --composite` of
 * gen_composite_scene's render (its camera: tests/gen_composite_scene.c, 218.8 m up, Z up, metres) with --spectral N
 * (SPECTRAL.exr) and in RGB (RGB.exr), against the spectral CPU reference at 48 wavelengths (src/reference/spectral.h:
 * the medium per wavelength, the solar spectrum, CIE 1931), which shares no code with the GPU's composite pass: at
 * eight geometry pixels spread over the distances, the converged march camera -> point (ref_radiance_to_point) for
 * every wavelength, turned into the layers' linear Rec.709 here, by the rules docs/aerial_perspective.md ("Spectral
 * colour") states:
 *  - in-scattering S = rayleigh + mie: 20 (the lesson's sun, relative units) x Rec.709(sum_i w_i S_i) / sum_i w_i.Y,
 *    w_i the bin's 683 E cmf weights (ref_spectral_weights): the sun's spectrum at the scene's sun luminance;
 *  - transmittance, channel q: sum_i r_iq T_i / sum_i r_iq, r_i = Rec.709(w_i) (a grey surface in sunlight).
 * Prints per pixel and the worst relative |S - S_ref| / S_ref (per channel) and |T - T_ref| for both files; exit 1
 * when the spectral file's worst exceeds BOUND (relative for S, absolute for T), when RGB's S is not at least twice
 * as far off as the spectral file's (the test would then not show what the spectral path is for), or on bad input. */
#include "io/exr_read.h"
#include "model/spectrum.h"
#include "reference/ref_atmosphere.h"
#include "reference/spectral.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define BINS 48
#define DEG (3.14159265358979323846 / 180.0)
#define PICKS 4
static const double CAMERA_M[3] = {-3.5, -8.5, 218.8};   /* gen_composite_scene's camera (world: Z up, metres) */

static float *read_all(const char *path, const char *const *names, int count, int *w, int *h)
{
    io_exr_info info;
    char err[512];
    if (io_exr_read_info(path, &info, err, sizeof err) != 0) {
        fprintf(stderr, "composite_spectral_check: %s\n", err);
        return NULL;
    }
    *w = info.width, *h = info.height;
    io_exr_info_free(&info);
    float *out = malloc((size_t)*w * *h * count * sizeof(float));
    if (!out || io_exr_read_channels(path, names, count, out, err, sizeof err) != 0) {
        fprintf(stderr, "composite_spectral_check: %s: %s\n", path, out ? err : "out of memory");
        free(out);
        return NULL;
    }
    return out;
}

static int by_distance(const void *a, const void *b)
{
    double x = ((const double *)a)[0], y = ((const double *)b)[0];
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    if (argc != 7) {
        fprintf(stderr, "usage: composite_spectral_check RENDER.exr SPECTRAL.exr RGB.exr SUN_EL SUN_AZ BOUND\n");
        return 1;
    }
    static const char *const in_names[] = {"ViewLayer.Combined.A", "ViewLayer.Position.X", "ViewLayer.Position.Y",
                                           "ViewLayer.Position.Z"};
    static const char *const names[] = {"transmittance.R", "transmittance.G", "transmittance.B", "rayleigh.R",
                                        "rayleigh.G", "rayleigh.B", "mie.R", "mie.G", "mie.B"};
    int w, h, w1, h1, w2, h2;
    float *in = read_all(argv[1], in_names, 4, &w, &h);
    float *layers[2] = {read_all(argv[2], names, 9, &w1, &h1), read_all(argv[3], names, 9, &w2, &h2)};
    if (!in || !layers[0] || !layers[1]) return 1;
    if (w1 != w || h1 != h || w2 != w || h2 != h) {
        fprintf(stderr, "composite_spectral_check: the files differ in size\n");
        return 1;
    }
    double sun_el = atof(argv[4]) * DEG, sun_az = atof(argv[5]) * DEG, bound = atof(argv[6]);

    /* Interior geometry pixels (alpha 1 on the pixel and its four neighbours: no edge repair), by distance. */
    size_t n = (size_t)w * h, count = 0;
    double(*cand)[2] = malloc(n * sizeof *cand);
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            size_t i = (size_t)y * w + x;
            const size_t nb[5] = {i, i - 1, i + 1, i - (size_t)w, i + (size_t)w};
            int ok = 1;
            for (int k = 0; k < 5; ++k) ok = ok && in[4 * nb[k]] == 1.0f && isfinite(in[4 * nb[k] + 1]);
            if (!ok) continue;
            double d2 = 0.0;
            for (int k = 0; k < 3; ++k) d2 += pow(in[4 * i + 1 + k] - CAMERA_M[k], 2.0);
            cand[count][0] = sqrt(d2), cand[count][1] = (double)i;
            ++count;
        }
    if (count < PICKS) {
        fprintf(stderr, "composite_spectral_check: %zu interior geometry pixels; expected %d or more\n", count, PICKS);
        return 1;
    }
    qsort(cand, count, sizeof *cand, by_distance);

    model_atmosphere earth;
    model_atmosphere_earth(&earth);
    ref_spectral s;
    ref_spectral_init(&s, &earth, BINS);
    double wy = 0.0, rgb_w[BINS][3], rgb_sum[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < BINS; ++i) {
        double xyz[3];
        ref_spectral_weights(BINS, i, xyz);
        wy += xyz[1];
        spectrum_xyz_to_rec709(xyz, rgb_w[i]);
        for (int q = 0; q < 3; ++q) rgb_sum[q] += rgb_w[i][q];
    }
    double sun[3];
    ref_dir(sun_az, sun_el, sun);
    ref_quality quality = ref_quality_converged();
    double worst_s[2] = {0.0, 0.0}, worst_t[2] = {0.0, 0.0};
    printf("composite_spectral_check: %d pixels, sun %.2f deg, reference %d wavelengths\n", PICKS, atof(argv[4]), BINS);
    for (int p = 0; p < PICKS; ++p) {
        size_t i = (size_t)cand[(count - 1) * (size_t)p / (PICKS - 1)][1];
        /* World (Z up, metres) -> vksky's local frame (north, up, east) = (y, z, x), as the composite maps it. */
        const float *pos = in + 4 * i + 1;
        double dw[3] = {pos[0] - CAMERA_M[0], pos[1] - CAMERA_M[1], pos[2] - CAMERA_M[2]};
        double v[3] = {dw[1], dw[2], dw[0]};
        double dist = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (int k = 0; k < 3; ++k) v[k] /= dist;
        double t_ref[3] = {0.0, 0.0, 0.0}, xyz_s[3] = {0.0, 0.0, 0.0};
        for (int g = 0; g * 3 < BINS; ++g) {
            model_atmosphere a;
            int idx[3], real = ref_spectral_group(&s, g, &a, idx);
            ref_aerial r;
            ref_radiance_to_point(&a, CAMERA_M[2] * 1e-3, v, sun, dist * 1e-3, quality, &r);
            for (int c = 0; c < real; ++c) {
                double wx[3];
                ref_spectral_weights(BINS, idx[c], wx);
                for (int q = 0; q < 3; ++q) {
                    xyz_s[q] += wx[q] * (r.rayleigh[c] + r.mie[c]);
                    t_ref[q] += rgb_w[idx[c]][q] * r.transmittance[c] / rgb_sum[q];
                }
            }
        }
        double s_ref[3];
        spectrum_xyz_to_rec709(xyz_s, s_ref);
        for (int q = 0; q < 3; ++q) s_ref[q] *= 20.0 / wy;
        printf("  pixel (%zu, %zu) %.2f km: ref S %.4g %.4g %.4g T %.4f %.4f %.4f\n", i % w, i / w, dist * 1e-3,
               s_ref[0], s_ref[1], s_ref[2], t_ref[0], t_ref[1], t_ref[2]);
        for (int f = 0; f < 2; ++f) {
            const float *l = layers[f] + 9 * i;
            double es = 0.0, et = 0.0;
            for (int q = 0; q < 3; ++q) {
                es = fmax(es, fabs(l[3 + q] + l[6 + q] - s_ref[q]) / s_ref[q]);
                et = fmax(et, fabs(l[q] - t_ref[q]));
            }
            printf("    %-8s S %.4g %.4g %.4g (worst %.2f %%) T %.4f %.4f %.4f (worst %.4f)\n", f ? "RGB" : "spectral",
                   l[3] + l[6], l[4] + l[7], l[5] + l[8], 100.0 * es, l[0], l[1], l[2], et);
            worst_s[f] = fmax(worst_s[f], es), worst_t[f] = fmax(worst_t[f], et);
        }
    }
    printf("composite_spectral_check: worst S %.2f %% (RGB %.2f %%), worst T %.4f (RGB %.4f); bound %g\n",
           100.0 * worst_s[0], 100.0 * worst_s[1], worst_t[0], worst_t[1], bound);
    int fail = 0;
    if (worst_s[0] > bound || worst_t[0] > bound) {
        printf("FAIL: the spectral composite is off the 48-wavelength reference by more than %g\n", bound);
        fail = 1;
    }
    if (worst_s[1] < 2.0 * worst_s[0]) {
        printf("FAIL: RGB's in-scattering (%.2f %%) is not twice as far off as the spectral one's: the view shows "
               "nothing the spectral path is for\n", 100.0 * worst_s[1]);
        fail = 1;
    }
    free(cand);
    return fail;
}
