/* Environment maps (issue 13): the sun lands where the documented mapping (docs/readme/envmap.md) says, in every
 * projection, for several azimuths and elevations (the zenith, just below the horizon); +90 degrees of azimuth move
 * it a quarter of an equirect map's width; the cube map's faces agree with the equirect map along the same
 * directions and meet without seams. The expected positions come from the documented conventions written out
 * here again (OpenEXR's LatLongMap and CubeMap axes, the fisheye's), not from src/sky/projection.c, which is
 * checked against them as well. Every render under validation + synchronization validation. */
#include "gpu_test.h"
#include "sky/projection.h"

static const double PI = 3.14159265358979323846;

/* ---- the documented mapping, independently ---------------------------------------------------- */

static void doc_dir(double az_deg, double el_deg, double d[3])
{
    double az = az_deg * PI / 180, el = el_deg * PI / 180;
    d[0] = cos(el) * cos(az), d[1] = sin(el), d[2] = cos(el) * sin(az);
}

/* Equirect: azimuth 0 a quarter of the width from the left, azimuth grows to the right, the zenith at the top. */
static void doc_equirect(int w, int h, double az, double el, double *x, double *y)
{
    double u = 0.25 + az / 360.0;
    u -= floor(u);
    *x = u * w, *y = (90.0 - el) / 180.0 * h;
}

/* OpenEXR's cube faces (+X -X +Y -Y +Z -Z, top to bottom): each face's top-left corner direction, and the axes
 * along which its pixel x and y grow (read off Imf::CubeMap::direction/pixelPosition). */
static const double face_corner[6][3] = {{1, 1, -1}, {-1, 1, 1}, {-1, 1, 1}, {-1, -1, -1}, {1, 1, 1}, {-1, 1, -1}};
static const double face_right[6][3] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {1, 0, 0}};
static const double face_down[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, -1}, {0, 0, 1}, {0, -1, 0}, {0, -1, 0}};

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void doc_cube(int n, const double d[3], double *x, double *y, int *face_out)
{
    int axis = 0;
    for (int i = 1; i < 3; ++i)
        if (fabs(d[i]) > fabs(d[axis])) axis = i;
    int face = 2 * axis + (d[axis] < 0);
    double m = fabs(d[axis]), s[3] = {d[0] / m, d[1] / m, d[2] / m};
    /* On the face plane: s = corner + (1 + a) right + (1 + b) down ... measured from the corner. */
    double rel[3] = {s[0] - face_corner[face][0], s[1] - face_corner[face][1], s[2] - face_corner[face][2]};
    *x = 0.5 * dot3(rel, face_right[face]) * n;
    *y = (face + 0.5 * dot3(rel, face_down[face])) * n;
    if (face_out) *face_out = face;
}

static void doc_cube_dir(int n, double x, double y, double d[3])
{
    int face = (int)floor(y / n);
    double a = 2.0 * x / n, b = 2.0 * (y / n - face);
    double len = 0;
    for (int i = 0; i < 3; ++i) d[i] = face_corner[face][i] + a * face_right[face][i] + b * face_down[face][i], len += d[i] * d[i];
    for (int i = 0; i < 3; ++i) d[i] /= sqrt(len);
}

/* Fisheye: equidistant, the zenith at the centre, the horizon on the inscribed circle, north (azimuth 0) up, east
 * (90) left: the sky seen from below. */
static void doc_fisheye(int w, double az, double el, double *x, double *y)
{
    double r = (90.0 - el) / 90.0, a = az * PI / 180;
    *x = 0.5 * w * (1.0 - r * sin(a)), *y = 0.5 * w * (1.0 - r * cos(a));
}

/* ---- the C twin against the documented mapping (no GPU) ------------------------------------------ */

static void check_twin(void)
{
    unsigned seed = 12345;
    for (int i = 0; i < 2000; ++i) {
        seed = seed * 1103515245u + 12345u;
        double az = (seed >> 8) % 36000 / 100.0 - 180.0;
        seed = seed * 1103515245u + 12345u;
        double el = (seed >> 8) % 17800 / 100.0 - 89.0;
        double d[3], x, y, ex, ey, back[3];
        doc_dir(az, el, d);
        /* equirect 720 x 360 */
        CHECK(projection_pixel(SKY_PROJECTION_EQUIRECT, 720, 360, d, &x, &y), "equirect pixel");
        doc_equirect(720, 360, az, el, &ex, &ey);
        double dx = fabs(x - ex);
        CHECK(fmin(dx, 720 - dx) < 1e-6 && fabs(y - ey) < 1e-6, "equirect az %g el %g: (%g, %g) vs documented (%g, %g)",
              az, el, x, y, ex, ey);
        projection_dir(SKY_PROJECTION_EQUIRECT, 720, 360, x, y, back);
        CHECK(dot3(back, d) > 1 - 1e-12, "equirect round trip az %g el %g", az, el);
        /* cube, face 100 */
        int face;
        CHECK(projection_pixel(SKY_PROJECTION_CUBEMAP, 100, 600, d, &x, &y), "cube pixel");
        doc_cube(100, d, &ex, &ey, &face);
        CHECK(fabs(x - ex) < 1e-9 && fabs(y - ey) < 1e-9, "cube az %g el %g: (%g, %g) vs documented (%g, %g) face %d", az,
              el, x, y, ex, ey, face);
        projection_dir(SKY_PROJECTION_CUBEMAP, 100, 600, x, y, back);
        CHECK(dot3(back, d) > 1 - 1e-12, "cube round trip az %g el %g", az, el);
        /* fisheye 300 (upper hemisphere only) */
        bool up = projection_pixel(SKY_PROJECTION_FISHEYE, 300, 300, d, &x, &y);
        CHECK(up == (el >= 0), "fisheye has el %g: %d", el, up);
        if (up) {
            doc_fisheye(300, az, el, &ex, &ey);
            CHECK(fabs(x - ex) < 1e-9 && fabs(y - ey) < 1e-9, "fisheye az %g el %g: (%g, %g) vs (%g, %g)", az, el, x, y, ex, ey);
            CHECK(projection_dir(SKY_PROJECTION_FISHEYE, 300, 300, x, y, back) && dot3(back, d) > 1 - 1e-12,
                  "fisheye round trip az %g el %g", az, el);
        }
    }
    /* OpenEXR's corners, literally (Imf::CubeMap on a 4-pixel face: pixel (0,0) -> (1,1,-1), (3,8) -> (1,1,1)). */
    double d[3];
    projection_dir(SKY_PROJECTION_CUBEMAP, 4, 24, 0.0, 0.0, d);
    CHECK(d[0] > 0.57 && d[1] > 0.57 && d[2] < -0.57, "+X top-left (%g %g %g)", d[0], d[1], d[2]);
    projection_dir(SKY_PROJECTION_CUBEMAP, 4, 24, 4.0, 8.0, d);
    CHECK(d[0] > 0.57 && d[1] > 0.57 && d[2] > 0.57, "+Y top-right (%g %g %g)", d[0], d[1], d[2]);
}

/* ---- renders ------------------------------------------------------------------------------------ */

typedef struct sun_case {
    double az, el;
} sun_case;
static const sun_case SUNS[] = {{0, 20}, {90, 20}, {200, 45}, {-60, 10}, {30, 90}, {150, -1}};
enum { SUN_COUNT = sizeof SUNS / sizeof SUNS[0] };
static const double SUN_RADIUS_DEG = 1.5;

static sky_view env_view(int projection, double az, double el)
{
    sky_view v = sky_view_default();
    v.projection = projection;
    v.bloom = false;
    v.altitude_km = 10.0;       /* the horizon dips 3.2 degrees: a sun 1 degree below the horizontal is in view */
    v.sun_azimuth_deg = az, v.sun_elevation_deg = el;
    v.steps = 16;
    return v;
}

/* Renders one projection at w x h for every sun, with and without the disc: the difference is the disc alone. */
static void render_suns(gpu_context *ctx, int projection, int w, int h, test_frame with[SUN_COUNT],
                        test_frame without[SUN_COUNT])
{
    test_renderer t;
    model_atmosphere a;
    model_atmosphere_earth(&a);
    test_renderer_create(&t, ctx, w, h, false, NULL, NULL);
    sky_renderer_set_atmosphere(&t.r, &a, SUN_RADIUS_DEG * PI / 180);
    sky_features f = sky_features_default();
    f.ground_albedo[0] = f.ground_albedo[1] = f.ground_albedo[2] = 0.3;
    for (int disc = 1; disc >= 0; --disc) {
        f.sun_disc = disc;
        sky_renderer_set_features(&t.r, &f);
        for (int i = 0; i < SUN_COUNT; ++i) {
            sky_view v = env_view(projection, SUNS[i].az, SUNS[i].el);
            (disc ? with : without)[i] = test_renderer_frame(&t, &v);
        }
    }
    test_renderer_destroy(&t);
}

/* The disc's centroid (weights: the disc's luminance); wrap_x: x is periodic (equirect). Returns the pixel count. */
static int disc_centroid(const test_frame *with, const test_frame *without, bool wrap_x, double *cx, double *cy)
{
    double sx = 0, sy = 0, sc = 0, ss = 0, sw = 0;
    int count = 0;
    for (int y = 0; y < with->height; ++y)
        for (int x = 0; x < with->width; ++x) {
            double wgt = luminance(test_pixel(with, x, y)) - luminance(test_pixel(without, x, y));
            if (wgt <= 1.0) continue;    /* the disc is ~100x the sky; fp16 noise is far below 1 */
            double ang = 2 * PI * (x + 0.5) / with->width;
            sx += wgt * (x + 0.5), sy += wgt * (y + 0.5), sc += wgt * cos(ang), ss += wgt * sin(ang), sw += wgt;
            ++count;
        }
    if (count == 0) return 0;
    *cy = sy / sw;
    if (wrap_x) {
        double ang = atan2(ss, sc);
        if (ang < 0) ang += 2 * PI;
        *cx = ang / (2 * PI) * with->width;
    } else {
        *cx = sx / sw;
    }
    return count;
}

static void check_suns(gpu_context *ctx)
{
    test_frame with[SUN_COUNT], without[SUN_COUNT];
    double cx, cy, ex, ey;

    /* Equirect 720 x 360: 0.5 degree per pixel; the disc is 6 pixels across. */
    render_suns(ctx, SKY_PROJECTION_EQUIRECT, 720, 360, with, without);
    double x_at[SUN_COUNT] = {0};
    for (int i = 0; i < SUN_COUNT; ++i) {
        int n = disc_centroid(&with[i], &without[i], true, &cx, &cy);
        doc_equirect(720, 360, SUNS[i].az, SUNS[i].el, &ex, &ey);
        x_at[i] = cx;
        CHECK(n > 0, "equirect: no sun disc for az %g el %g", SUNS[i].az, SUNS[i].el);
        if (SUNS[i].el == 90) {
            /* The zenith is the whole top row: the disc fills the top 1.5 degrees (3 rows), every column. */
            CHECK(n > 0 && cy < 3.0, "equirect zenith sun: centroid row %g, expected in the top 3 rows", cy);
            continue;
        }
        double dx = fabs(cx - ex);
        CHECK(n > 0 && fmin(dx, 720 - dx) < 1.0 && fabs(cy - ey) < 1.0,
              "equirect sun az %g el %g at (%.2f, %.2f), documented (%.2f, %.2f)", SUNS[i].az, SUNS[i].el, cx, cy, ex, ey);
        printf("equirect az %6.1f el %5.1f: sun at (%.2f, %.2f), documented (%.2f, %.2f)\n", SUNS[i].az, SUNS[i].el, cx,
               cy, ex, ey);
    }
    CHECK(fabs(x_at[1] - x_at[0] - 720 / 4.0) < 1.0, "azimuth +90: the sun moved %.2f pixels, expected a quarter width (180)",
          x_at[1] - x_at[0]);
    CHECK(cy > 180.0, "a sun below the horizontal (el -1) lies below the middle row: %g", cy);
    for (int i = 0; i < SUN_COUNT; ++i) test_frame_free(&with[i]), test_frame_free(&without[i]);

    /* Cube map, faces of 180 (0.5 degree per pixel at the face centre). */
    render_suns(ctx, SKY_PROJECTION_CUBEMAP, 180, 1080, with, without);
    for (int i = 0; i < SUN_COUNT; ++i) {
        double d[3];
        int face;
        doc_dir(SUNS[i].az, SUNS[i].el, d);
        doc_cube(180, d, &ex, &ey, &face);
        int n = disc_centroid(&with[i], &without[i], false, &cx, &cy);
        CHECK(n > 0 && fabs(cx - ex) < 1.0 && fabs(cy - ey) < 1.0,
              "cube sun az %g el %g at (%.2f, %.2f), documented (%.2f, %.2f) on face %d", SUNS[i].az, SUNS[i].el, cx, cy,
              ex, ey, face);
        printf("cube     az %6.1f el %5.1f: sun at (%.2f, %.2f), documented (%.2f, %.2f), face %d\n", SUNS[i].az,
               SUNS[i].el, cx, cy, ex, ey, face);
    }
    for (int i = 0; i < SUN_COUNT; ++i) test_frame_free(&with[i]), test_frame_free(&without[i]);

    /* Fisheye 360 x 360: 0.5 degree per pixel along a radius. */
    render_suns(ctx, SKY_PROJECTION_FISHEYE, 360, 360, with, without);
    for (int i = 0; i < SUN_COUNT; ++i) {
        int n = disc_centroid(&with[i], &without[i], false, &cx, &cy);
        if (SUNS[i].el - SUN_RADIUS_DEG < 0) {
            /* Below the horizon: only the part of the disc above it may show, on the rim. */
            double r = n ? hypot(cx - 180, cy - 180) / 180 : 1;
            CHECK(n == 0 || r > (90 - SUNS[i].el - SUN_RADIUS_DEG - 1) / 90, "fisheye: sun at el %g inside the rim (r %g)",
                  SUNS[i].el, r);
            continue;
        }
        doc_fisheye(360, SUNS[i].az, SUNS[i].el, &ex, &ey);
        CHECK(n > 0 && fabs(cx - ex) < 1.0 && fabs(cy - ey) < 1.0,
              "fisheye sun az %g el %g at (%.2f, %.2f), documented (%.2f, %.2f)", SUNS[i].az, SUNS[i].el, cx, cy, ex, ey);
        printf("fisheye  az %6.1f el %5.1f: sun at (%.2f, %.2f), documented (%.2f, %.2f)\n", SUNS[i].az, SUNS[i].el, cx,
               cy, ex, ey);
    }
    /* Outside the circle: black. */
    CHECK(luminance(test_pixel(&with[0], 1, 1)) == 0.0, "fisheye corner not black");
    for (int i = 0; i < SUN_COUNT; ++i) test_frame_free(&with[i]), test_frame_free(&without[i]);
}

/* Bilinear lookup in an equirect frame along a direction (the documented mapping; x wraps, y clamps). */
static double equirect_lum(const test_frame *f, const double d[3])
{
    double az = atan2(d[2], d[0]) * 180 / PI, el = asin(fmax(-1, fmin(1, d[1]))) * 180 / PI, x, y;
    doc_equirect(f->width, f->height, az, el, &x, &y);
    x -= 0.5, y -= 0.5;
    int x0 = (int)floor(x), y0 = (int)floor(y);
    double fx = x - x0, fy = y - y0, sum = 0;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            int xi = ((x0 + i) % f->width + f->width) % f->width;
            int yj = y0 + j < 0 ? 0 : y0 + j >= f->height ? f->height - 1 : y0 + j;
            sum += (i ? fx : 1 - fx) * (j ? fy : 1 - fy) * luminance(test_pixel(f, xi, yj));
        }
    return sum;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void check_cube_vs_equirect(gpu_context *ctx)
{
    enum { N = 128 };
    sky_view v = env_view(SKY_PROJECTION_EQUIRECT, 40, 30);
    test_frame eq = test_render(ctx, &v, 1024, 512);
    v.projection = SKY_PROJECTION_CUBEMAP;
    test_frame cube = test_render(ctx, &v, N, 6 * N);
    CHECK(count_bad_pixels(&eq) == 0 && count_bad_pixels(&cube) == 0, "non-finite or negative pixels");
    double sun[3];
    doc_dir(40, 30, sun);
    double *err = malloc(sizeof(double) * N * 6 * N);
    int m = 0;
    for (int y = 0; y < 6 * N; ++y)
        for (int x = 0; x < N; ++x) {
            double d[3];
            doc_cube_dir(N, x + 0.5, y + 0.5, d);
            if (dot3(d, sun) > cos(3 * PI / 180)) continue;   /* the disc's rim is a step: no bilinear there */
            double c = luminance(test_pixel(&cube, x, y)), e = equirect_lum(&eq, d);
            err[m++] = fabs(c - e) / fmax(e, 1e-3);
        }
    qsort(err, (size_t)m, sizeof *err, cmp_double);
    double median = err[m / 2], p98 = err[(int)(0.98 * m)];
    printf("cube vs equirect along %d directions: median relative error %.4f, 98th percentile %.4f\n", m, median, p98);
    CHECK(median < 0.01 && p98 < 0.05, "cube vs equirect: median %g (< 0.01), 98th percentile %g (< 0.05)", median, p98);
    free(err);

    /* Seams: the luminance step from a border pixel to its neighbour across the face edge (found through the
     * documented mapping) against the step to its neighbour inside the face. A face turned or mirrored the wrong
     * way makes the first far larger. */
    double across = 0, inside = 0;
    for (int face = 0; face < 6; ++face)
        for (int k = 0; k < N; ++k)
            for (int side = 0; side < 4; ++side) {
                int px = side == 0 ? 0 : side == 1 ? N - 1 : k, py = side == 2 ? 0 : side == 3 ? N - 1 : k;
                int ix = px + (side == 0) - (side == 1), iy = py + (side == 2) - (side == 3);
                double ox = px + 0.5 - (ix - px), oy = py + 0.5 - (iy - py);   /* one pixel outward, off the face */
                double dir[3];
                int f2;
                /* The outward point on the face's plane, then the pixel holding that direction. */
                double a = 2.0 * ox / N, b = 2.0 * oy / N, len = 0;
                for (int i = 0; i < 3; ++i)
                    dir[i] = face_corner[face][i] + a * face_right[face][i] + b * face_down[face][i], len += dir[i] * dir[i];
                double qx, qy;
                doc_cube(N, dir, &qx, &qy, &f2);
                int qxi = (int)floor(qx), qyi = (int)floor(qy);
                if (qxi < 0) qxi = 0;
                if (qxi >= N) qxi = N - 1;
                CHECK(f2 != face, "the pixel beyond face %d's edge is on another face", face);
                double lp = luminance(test_pixel(&cube, px, py + face * N));
                across += fabs(lp - luminance(test_pixel(&cube, qxi, qyi)));
                inside += fabs(lp - luminance(test_pixel(&cube, ix, iy + face * N)));
            }
    printf("cube edges: mean step across an edge %.5f, inside a face %.5f\n", across / (6 * N * 4), inside / (6 * N * 4));
    CHECK(across < 2.0 * inside + 1e-3 * 6 * N * 4, "seams: step across edges %g vs inside faces %g", across, inside);
    test_frame_free(&eq);
    test_frame_free(&cube);
}

int main(void)
{
    check_twin();
    gpu_context ctx;
    test_context(&ctx);
    check_suns(&ctx);
    check_cube_vs_equirect(&ctx);
    gpu_context_destroy(&ctx);
    return test_finish("envmap");
}
