/* exr_pixels: a helper of tests/sequences_test.sh that reads EXRs independently of the program's header writer
 * (OpenEXRCore directly for attributes; io_read_exr for pixels).
 *   exr_pixels same A.exr B.exr          exit 0 when both have the same size and bit-identical pixels, else 1
 *   exr_pixels attr A.exr NAME           print the string attribute NAME (exit 1 if absent)
 *   exr_pixels sun A.exr                 print "x y" (pixels, 0 at the left/top edge) of the centroid of the pixels
 *                                        brighter than half the brightest (the sun's disc)
 *   exr_pixels project A.exr AZ EL       print "x y" (pixels) where worldToNDC puts the direction of azimuth AZ and
 *                                        elevation EL (degrees; (cos el cos az, sin el, cos el sin az), +Y up: vksky's
 *                                        documented convention), and "cam X Y Z": worldToCamera's image of it
 *   exr_pixels plain OUT.exr             write a 2x2 grey EXR with no header attributes beyond the required ones
 *   exr_pixels reldiff A.exr B.exr       print the largest |A - B| over the colour channels of any pixel, relative to
 *                                        that pixel's largest |B| channel (issue 32: four-wide vs three-wide) */
#include "io/exr_read.h"
#include "io/exr_write.h"
#include "io/half_float.h"
#include <math.h>
#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int read_pixels(const char *path, int *w, int *h, float **rgba)
{
    char err[512];
    if (io_read_exr(path, "", w, h, rgba, err, sizeof err) != 0) {
        fprintf(stderr, "exr_pixels: %s\n", err);
        return 1;
    }
    return 0;
}

static int open_exr(const char *path, exr_context_t *ctxt)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    if (exr_start_read(ctxt, path, &init) != EXR_ERR_SUCCESS) {
        fprintf(stderr, "exr_pixels: cannot read '%s' as an EXR\n", path);
        return 1;
    }
    return 0;
}

/* Row vector times matrix (Imath's convention). */
static void transform(const float m[16], const double p[4], double out[4])
{
    for (int c = 0; c < 4; ++c) {
        out[c] = 0.0;
        for (int r = 0; r < 4; ++r) out[c] += p[r] * m[4 * r + c];
    }
}

int main(int argc, char **argv)
{
    if (argc == 4 && !strcmp(argv[1], "same")) {
        int w[2], h[2];
        float *px[2] = {NULL, NULL};
        if (read_pixels(argv[2], &w[0], &h[0], &px[0]) || read_pixels(argv[3], &w[1], &h[1], &px[1])) {
            free(px[0]);
            return 1;
        }
        int rc = 0;
        if (w[0] != w[1] || h[0] != h[1]) {
            printf("sizes differ: %dx%d and %dx%d\n", w[0], h[0], w[1], h[1]);
            rc = 1;
        }
        size_t n = rc ? 0 : (size_t)w[0] * (size_t)h[0] * 4;
        for (size_t i = 0; i < n && rc == 0; ++i)
            if (memcmp(&px[0][i], &px[1][i], sizeof(float)) != 0) {
                printf("pixel %zu channel %zu differs: %.9g and %.9g\n", i / 4, i % 4, px[0][i], px[1][i]);
                rc = 1;
            }
        free(px[0]);
        free(px[1]);
        return rc;
    }
    if (argc == 4 && !strcmp(argv[1], "reldiff")) {
        int w[2], h[2];
        float *px[2] = {NULL, NULL};
        if (read_pixels(argv[2], &w[0], &h[0], &px[0]) || read_pixels(argv[3], &w[1], &h[1], &px[1])) {
            free(px[0]);
            return 1;
        }
        int rc = w[0] != w[1] || h[0] != h[1];
        double worst = 0.0;
        for (size_t i = 0, n = rc ? 0 : (size_t)w[0] * (size_t)h[0]; i < n; ++i) {
            const float *a = px[0] + 4 * i, *b = px[1] + 4 * i;
            double scale = fmax(fabs(b[0]), fmax(fabs(b[1]), fabs(b[2])));
            for (int c = 0; c < 3 && scale > 0.0; ++c) worst = fmax(worst, fabs((double)a[c] - b[c]) / scale);
        }
        if (rc) printf("sizes differ: %dx%d and %dx%d\n", w[0], h[0], w[1], h[1]);
        else printf("%.6g\n", worst);
        free(px[0]);
        free(px[1]);
        return rc;
    }
    if (argc == 4 && !strcmp(argv[1], "attr")) {
        exr_context_t ctxt = NULL;
        if (open_exr(argv[2], &ctxt)) return 1;
        const char *s = NULL;
        int32_t len = 0;
        int rc = exr_attr_get_string(ctxt, 0, argv[3], &len, &s) == EXR_ERR_SUCCESS ? 0 : 1;
        if (rc == 0) fwrite(s, 1, (size_t)len, stdout);
        exr_finish(&ctxt);
        return rc;
    }
    if (argc == 3 && !strcmp(argv[1], "sun")) {
        int w, h;
        float *px = NULL;
        if (read_pixels(argv[2], &w, &h, &px)) return 1;
        double top = 0.0;
        for (int i = 0; i < w * h; ++i) top = fmax(top, px[4 * i] + px[4 * i + 1] + px[4 * i + 2]);
        double sx = 0.0, sy = 0.0, sw = 0.0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float *p = px + 4 * ((size_t)y * (size_t)w + (size_t)x);
                double v = p[0] + p[1] + p[2];
                if (v > 0.5 * top) sx += v * (x + 0.5), sy += v * (y + 0.5), sw += v;
            }
        printf("%.3f %.3f\n", sx / sw, sy / sw);
        free(px);
        return 0;
    }
    if (argc == 5 && !strcmp(argv[1], "project")) {
        exr_context_t ctxt = NULL;
        if (open_exr(argv[2], &ctxt)) return 1;
        exr_attr_m44f_t ndc, cam;
        exr_attr_box2i_t window;
        if (exr_attr_get_m44f(ctxt, 0, "worldToNDC", &ndc) != EXR_ERR_SUCCESS ||
            exr_attr_get_m44f(ctxt, 0, "worldToCamera", &cam) != EXR_ERR_SUCCESS ||
            exr_get_display_window(ctxt, 0, &window) != EXR_ERR_SUCCESS) {
            fprintf(stderr, "exr_pixels: '%s' lacks worldToNDC or worldToCamera\n", argv[2]);
            exr_finish(&ctxt);
            return 1;
        }
        exr_finish(&ctxt);
        double az = atof(argv[3]) * 3.14159265358979323846 / 180.0, el = atof(argv[4]) * 3.14159265358979323846 / 180.0;
        double d[4] = {cos(el) * cos(az), sin(el), cos(el) * sin(az), 0.0};   /* a point at infinity: w = 0 */
        double q[4], c[4];
        transform(ndc.m, d, q);
        transform(cam.m, d, c);
        int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
        printf("%.3f %.3f\ncam %.6f %.6f %.6f\n", q[0] / q[3] * w, q[1] / q[3] * h, c[0], c[1], c[2]);
        return 0;
    }
    if (argc == 3 && !strcmp(argv[1], "plain")) {
        uint16_t px[16];
        for (int i = 0; i < 16; ++i) px[i] = io_float_to_half(0.5f);
        io_exr_layer layer = {.name = "", .rgba_half = px};
        char err[512];
        if (io_write_exr(argv[2], 2, 2, &layer, 1, err, sizeof err) != 0) {
            fprintf(stderr, "exr_pixels: %s\n", err);
            return 1;
        }
        return 0;
    }
    fprintf(stderr, "usage: exr_pixels same A B | attr A NAME | sun A | project A AZ EL | plain OUT\n");
    return 2;
}
