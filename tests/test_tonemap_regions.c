/* The tone map's regions (sky/tonemap_regions.h, issue 26 item 1), on the CPU:
 *  - they tile the output: every pixel in exactly one region;
 *  - they are conservative: every pixel of a far region has, at each of its four bilinear taps, the sky pass's
 *    horizon distance beyond 2 texels with one sign, computed here independently of the planner: the directions
 *    from the C twin of the projections (sky/projection.c; perspective from the ray matrix), the distance as
 *    horizon.glsl computes it (central differences a quarter texel apart), so the far-only pipeline gives each of
 *    them the pixel the full shader gives (ctest tonemap_regions compares the images);
 *  - they pay off: with the horizon across a 1 m frame most of it is far (320x180: >= 80, 70, 45 % of the pixels
 *    at render scales 1, 0.5, 0.25; 1920x1080: >= 95 %; a 256 cube map >= 50 %), and a frame looking down from 1 m (no horizon in it) is far everywhere;
 *  - VKSKY_TONEMAP_SPLIT=0: one region, the full path.
 * Views: perspective at render scales 1, 0.5, 0.25 with pitches, fovs and yaws, from 1 m to 36 000 km; equirect
 * (whole and as a band with an offset), cube map (a band across a face edge), fisheye. */
#include "sky/projection.h"
#include "sky/tonemap_regions.h"
#include "sky/view_params.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static const double R_GROUND = 6360.0, ATMO = 100.0;
static int failures = 0;

#define CHECK(cond, ...)                                                                                               \
    do {                                                                                                               \
        if (!(cond)) {                                                                                                 \
            fprintf(stderr, "FAIL: " __VA_ARGS__);                                                                     \
            fputc('\n', stderr);                                                                                       \
            failures++;                                                                                                \
        }                                                                                                              \
    } while (0)

typedef struct frame {
    SkyPush push;
    int projection, whole_w, whole_h;   /* the whole image's size (the sky pass's texels) */
    VkExtent2D hdr, display;
} frame;

/* The direction's y at a tile-local texel position, independently of the planner. */
static double elevation_y(const frame *f, double x, double y)
{
    const SkyPush *p = &f->push;
    double gx = x + p->projection.y, gy = y + p->projection.z, d[3];
    if (f->projection == SKY_PROJECTION_PERSPECTIVE) {
        double nx = 2.0 * gx * p->right.w - 1.0, ny = 1.0 - 2.0 * gy * p->up.w;
        d[0] = p->forward.x + nx * p->right.x + ny * p->up.x;
        d[1] = p->forward.y + nx * p->right.y + ny * p->up.y;
        d[2] = p->forward.z + nx * p->right.z + ny * p->up.z;
        return d[1] / sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    if (!projection_dir((sky_projection)f->projection, f->whole_w, f->whole_h, gx, gy, d)) {
        /* Outside the fisheye: the sky pass writes +1e4; the level function's value there is never needed. */
        return NAN;
    }
    return d[1] / sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* horizon.glsl's horizon_distance at texel (i, j), in texels. */
static double texel_distance(const frame *f, int i, int j)
{
    double cx = i + 0.5, cy = j + 0.5, s = f->push.horizon.x, e = 0.25;
    double v = elevation_y(f, cx, cy);
    if (isnan(v)) return 1.0e4;
    double fx = elevation_y(f, cx + e, cy) - elevation_y(f, cx - e, cy);
    double fy = elevation_y(f, cx, cy + e) - elevation_y(f, cx, cy - e);
    if (isnan(fx) || isnan(fy)) return v - s >= 0.0 ? 1.0e4 : -1.0e4;   /* (the rim: sky side) */
    double len = hypot(fx, fy) / (2.0 * e);
    return len > 1e-12 ? (v - s) / len : (v - s >= 0.0 ? 1.0e4 : -1.0e4);
}

static void check_frame(const char *name, const frame *f, double min_far_share)
{
    tonemap_regions r;
    tonemap_regions_plan(&r, &f->push, f->hdr, f->display);
    uint32_t w = f->display.width, h = f->display.height;
    unsigned char *seen = calloc((size_t)w * h, 1), *far = calloc((size_t)w * h, 1);
    for (uint32_t k = 0; k < r.count; ++k) {
        VkRect2D q = r.region[k].rect;
        for (uint32_t y = (uint32_t)q.offset.y; y < q.offset.y + q.extent.height && y < h; ++y)
            for (uint32_t x = (uint32_t)q.offset.x; x < q.offset.x + q.extent.width && x < w; ++x)
                seen[y * w + x]++, far[y * w + x] = !r.region[k].horizon;
    }
    long bad_cover = 0, far_pixels = 0, unsafe = 0;
    double sx = (double)f->hdr.width / w, sy = (double)f->hdr.height / h;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            bad_cover += seen[y * w + x] != 1;
            if (!far[y * w + x]) continue;
            far_pixels++;
            int i0 = (int)floor((x + 0.5) * sx - 0.5), j0 = (int)floor((y + 0.5) * sy - 0.5);
            int sign = 0;
            for (int k = 0; k < 4; ++k) {
                int i = i0 + (k & 1), j = j0 + (k >> 1);
                i = i < 0 ? 0 : i >= (int)f->hdr.width ? (int)f->hdr.width - 1 : i;
                j = j < 0 ? 0 : j >= (int)f->hdr.height ? (int)f->hdr.height - 1 : j;
                double d = texel_distance(f, i, j);
                int s = d > 2.0 ? 1 : d < -2.0 ? -1 : 0;
                if (s == 0 || (sign && s != sign)) {
                    if (unsafe < 3) fprintf(stderr, "  unsafe: pixel %u,%u tap %d,%d d=%g\n", x, y, i, j, d);
                    unsafe++;
                }
                sign = s;
            }
        }
    CHECK(bad_cover == 0, "%s: %ld pixels not in exactly one region", name, bad_cover);
    CHECK(unsafe == 0, "%s: %ld taps of far pixels within 2 texels of the horizon (or of both sides)", name, unsafe);
    double share = (double)far_pixels / ((double)w * h);
    CHECK(share >= min_far_share, "%s: far share %.1f %% < %.1f %%", name, 100.0 * share, 100.0 * min_far_share);
    printf("%-44s %3u regions, %5.1f %% far\n", name, r.count, 100.0 * share);
    free(seen);
    free(far);
}

static frame perspective(double altitude, double pitch, double fov, double yaw, uint32_t w, uint32_t h, double scale)
{
    sky_view v = sky_view_default();
    v.altitude_km = altitude, v.pitch_deg = pitch, v.fov_deg = fov, v.yaw_deg = yaw;
    frame f = {.projection = SKY_PROJECTION_PERSPECTIVE, .display = {w, h}};
    f.hdr = (VkExtent2D){(uint32_t)fmax(1.0, floor(w * scale)), (uint32_t)fmax(1.0, floor(h * scale))};
    f.push = sky_view_push(&v, f.hdr.width, f.hdr.height, (double)w / h);
    sky_view_set_horizon(&f.push, &v, R_GROUND, ATMO, scale == 1.0);
    return f;
}

/* A map (whole, or the band of `rows` rows at `top`, one padding row each side as tiles.c draws it). */
static frame map(int projection, int width, double altitude, int top, int rows)
{
    sky_view v = sky_view_default();
    v.altitude_km = altitude, v.projection = projection;
    int ww, wh;
    projection_image_size((sky_projection)projection, width, 0, &ww, &wh);
    frame f = {.projection = projection, .whole_w = ww, .whole_h = wh};
    if (rows > 0) {
        int y0 = top - 1 < 0 ? 0 : top - 1, y1 = top + rows + 1 > wh ? wh : top + rows + 1;
        v.tile_y = y0, v.whole_width = ww, v.whole_height = wh;
        f.hdr = f.display = (VkExtent2D){(uint32_t)ww, (uint32_t)(y1 - y0)};
    } else {
        f.hdr = f.display = (VkExtent2D){(uint32_t)ww, (uint32_t)wh};
    }
    f.push = sky_view_push(&v, (uint32_t)ww, (uint32_t)wh, (double)ww / wh);
    sky_view_set_horizon(&f.push, &v, R_GROUND, ATMO, true);
    return f;
}

int main(void)
{
    static const double scales[] = {1.0, 0.5, 0.25};
    static const double shares[] = {0.8, 0.7, 0.45};   /* the horizon path's band: +-2 texels and a tile's rows */
    for (int s = 0; s < 3; ++s) {
        char name[96];
        snprintf(name, sizeof name, "1 m, pitch 10, 320x180, scale %g", scales[s]);
        frame f = perspective(0.001, 10.0, 75.0, 0.0, 320, 180, scales[s]);
        check_frame(name, &f, shares[s]);
    }
    frame big = perspective(0.001, 10.0, 75.0, 0.0, 1920, 1080, 1.0);
    check_frame("1 m, pitch 10, 1920x1080, scale 1", &big, 0.95);
    frame down = perspective(0.001, -90.0, 40.0, 0.0, 160, 90, 0.5);
    check_frame("1 m, looking down, fov 40 (no horizon)", &down, 1.0);
    struct { double alt, pitch, fov, yaw, scale; } views[] = {
        {0.001, 1.0, 75.0, 0.0, 0.5},    {0.001, -40.0, 120.0, 30.0, 0.5}, {0.001, 60.0, 20.0, 0.0, 0.5},
        {1.0, 0.0, 90.0, 45.0, 1.0},     {10.0, -5.0, 75.0, 0.0, 0.5},     {100.0, -10.0, 75.0, 0.0, 0.25},
        {400.0, -20.0, 75.0, 0.0, 0.5},  {36000.0, -90.0, 30.0, 0.0, 1.0}, {0.001, 89.0, 170.0, 0.0, 0.5}};
    for (size_t k = 0; k < sizeof views / sizeof views[0]; ++k) {
        char name[96];
        snprintf(name, sizeof name, "%g km, pitch %g, fov %g, scale %g", views[k].alt, views[k].pitch, views[k].fov,
                 views[k].scale);
        frame f = perspective(views[k].alt, views[k].pitch, views[k].fov, views[k].yaw, 200, 120, views[k].scale);
        check_frame(name, &f, 0.0);
    }
    frame eq = map(SKY_PROJECTION_EQUIRECT, 256, 0.001, 0, 0);
    check_frame("equirect 256x128, 1 m", &eq, 0.8);
    frame eq_band = map(SKY_PROJECTION_EQUIRECT, 256, 100.0, 60, 7);
    check_frame("equirect band of 7 rows at 60, 100 km", &eq_band, 0.0);
    frame cube = map(SKY_PROJECTION_CUBEMAP, 32, 0.001, 0, 0);   /* faces as wide as a tile: all horizon */
    check_frame("cube map 32, 1 m", &cube, 0.0);
    frame cube_big = map(SKY_PROJECTION_CUBEMAP, 256, 0.001, 0, 0);
    check_frame("cube map 256, 1 m", &cube_big, 0.5);
    frame cube_band = map(SKY_PROJECTION_CUBEMAP, 32, 5.0, 50, 30);
    check_frame("cube map band across a face edge, 5 km", &cube_band, 0.0);
    frame fish = map(SKY_PROJECTION_FISHEYE, 128, 0.001, 0, 0);
    check_frame("fisheye 128, 1 m", &fish, 0.2);
    frame fish_high = map(SKY_PROJECTION_FISHEYE, 128, 20.0, 0, 0);
    check_frame("fisheye 128, 20 km", &fish_high, 0.0);

    setenv("VKSKY_TONEMAP_SPLIT", "0", 1);
    tonemap_regions r;
    tonemap_regions_plan(&r, &big.push, big.hdr, big.display);
    CHECK(r.count == 1 && r.region[0].horizon && r.region[0].rect.extent.width == 1920 &&
              r.region[0].rect.extent.height == 1080,
          "VKSKY_TONEMAP_SPLIT=0: not one full region");
    if (failures) {
        printf("test_tonemap_regions: %d failure(s)\n", failures);
        return 1;
    }
    printf("test_tonemap_regions: all passed\n");
    return 0;
}
