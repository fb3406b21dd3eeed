/* vksky error metrics: one place for every accuracy number (relative luminance error, CIEDE2000, the CPU tone
 * map that turns reference radiance into display pixels, the sky mask). No Vulkan, only libm.
 *
 * Images are row-major, top row first, interleaved RGBA (float: scene-linear; 8-bit: sRGB-encoded display
 * values). Masks are w*h bytes, nonzero = pixel counts; a NULL mask means every pixel counts.
 */
#ifndef VKSKY_METRICS_H
#define VKSKY_METRICS_H

#include "reference/ref_atmosphere.h"
#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Luminance of scene-linear Rec.709/sRGB primaries: 0.2126 R + 0.7152 G + 0.0722 B. */
double metrics_luminance_rgb(const double rgb[3]);

typedef struct metrics_luminance {
    double mean, p95, max; /* of the per-pixel relative luminance error */
    int count;             /* pixels that counted (0: mean = p95 = max = 0) */
} metrics_luminance;

/* Relative luminance error e_i = |Lt_i - Lr_i| / max(Lr_i, floor) over the pixels where mask[i] != 0 (mask NULL:
 * all); L is the luminance above of the RGB channels (alpha ignored). p95 is the nearest-rank percentile: the
 * ceil(0.95 n)-th smallest e_i (1-based), so at least 95 % of the pixels have e_i <= p95 and p95 is always one of
 * the e_i. Non-finite e_i (a NaN/Inf pixel in either image) count as +Inf, so they show in p95/max and make the
 * mean +Inf rather than vanish.
 * floor: keeps near-black reference pixels (earth shadow, deep twilight) from dominating a relative error.
 * The recommended value, and what floor <= 0 selects, is 1e-4 x the reference's maximum luminance over the counted
 * pixels: at any exposure that does not clip the brightest pixel, a pixel 10^4 times darker is below the first
 * non-zero 8-bit sRGB code (1/255/12.92 = 3.0e-4 of full scale), so its relative error cannot be seen; with the
 * floor its error is measured relative to that level instead. */
metrics_luminance metrics_relative_luminance(const float *test_rgba, const float *ref_rgba, const unsigned char *mask,
                                             int w, int h, double floor);

/* CIEDE2000 colour difference (Sharma, Wu, Dalal 2005; kL = kC = kH = 1) between two CIELAB colours. */
double metrics_ciede2000(const double lab1[3], const double lab2[3]);

/* 8-bit sRGB (IEC 61966-2-1 decode) -> CIE XYZ (sRGB primaries, D65) -> CIELAB with the D65 white of that matrix
 * (its row sums, so sRGB white is exactly L = 100, a = b = 0). */
void metrics_srgb8_to_lab(const unsigned char rgb[3], double lab[3]);

/* Mean CIEDE2000 between two 8-bit sRGB RGBA images over the masked pixels (alpha ignored); 0 if none count. */
double metrics_ciede2000_mean(const unsigned char *a_rgba8, const unsigned char *b_rgba8, const unsigned char *mask,
                              int w, int h);

/* The renderer's tone map on the CPU (shaders/glsl/tonemap_common.glsl without bloom): colour = min(rgb, 65504),
 * x = colour * 2^exposure_ev, operator 0 clamp(x, 0, 1) / 1 Reinhard x / (1 + x) / 2 ACES fitted (Narkowicz:
 * x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clamped to [0, 1]), then the sRGB encode (12.92 x below
 * 0.0031308, else 1.055 x^(1/2.4) - 0.055), then 8-bit round (floor(255 v + 0.5), v clamped to [0, 1], as the
 * UNORM store does). Alpha is written as 255. NaN and negatives (a spectral sum's out-of-gamut colour) map to 0. */
void metrics_tonemap_srgb8(const float *rgba, int w, int h, double exposure_ev, int op, unsigned char *out_rgba8);
/* The same with the GPU tone map's dither (shaders/glsl/dither.glsl's law) when `dither`: triangular noise of +-1 LSB
 * seeded by each pixel's position in the whole image, the block's top-left pixel at (x0, y0) there (a band's first
 * row; the GPU's TonemapPush.dither offset). */
void metrics_tonemap_srgb8_dithered(const float *rgba, int w, int h, double exposure_ev, int op, bool dither, int x0,
                                    int y0, unsigned char *out_rgba8);

/* Sky mask: 1 where the view ray of pixel (x, y) (docs/model.md image convention, ref_pixel_dir) does NOT hit the
 * ground from the camera altitude (the inclusive ground test of docs/model.md, cancellation-free), else 0. */
void metrics_sky_mask(const model_atmosphere *a, double altitude, int w, int h, double yaw_rad, double pitch_rad,
                      double fov_y_rad, unsigned char *mask);

#ifdef __cplusplus
}
#endif

#endif /* VKSKY_METRICS_H */
