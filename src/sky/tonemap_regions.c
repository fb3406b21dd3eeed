/* The tone map's regions: which output tiles may need the horizon path (see sky/tonemap_regions.h).
 *
 * The sky pass stores in each texel's alpha d = f / |grad f| (horizon.glsl): f = v.y - sin(horizon), the level
 * function of the texel centre's direction v, its gradient by central differences a quarter texel apart. The tone
 * map takes the horizon path where its bilinear sample of d is within 2 texels. With lx, ly bounds on |df/dx| and
 * |df/dy| (per texel) over the texels a tile reads, the sky pass's finite-difference gradient is at most
 * hypot(lx, ly) (each component a mean of the derivative); if every such texel has |f| > 4 hypot(lx, ly), all their
 * d are beyond 4, of one sign, and so is the bilinear sample (a convex mix, whatever the filter's rounding): the far
 * path. Over a rectangle of texel centres with centre c and half extents hx, hy, |f| >= |f(c)| - lx hx - ly hy; the
 * test adds 1e-5 for the GPU's float directions. The bounds per projection, from the shader's maths
 * (projection.glsl):
 *  - perspective, v = normalize(w), w = F + ndc.x R + ndc.y U affine in the texel: affine_bounds (the derivative of
 *    v.y itself, small where the view looks up or down, not only of v);
 *  - equirect: v.y = sin(lat), lat linear in y at pi / H a texel: lx = 0, ly = pi / H;
 *  - cube map: inside a face w is affine too (one coordinate +-1, the other two moving 2 / S a texel); a tile that
 *    spans faces is tested face by face (the direction jumps at a face's edge);
 *  - fisheye: v.y = cos(min(r, 1) pi / 2), r = |q|, q moving 2 / W and 2 / H a texel: pi / W and pi / H times the
 *    sine at the tile's largest r; outside the circle the sky pass writes d = +1e4 and the clamped direction has v.y = 0 >= sin(horizon), so a
 *    tile found far on the sky side stays on it there, and one found on the ground side has no texel outside. */
#include "sky/tonemap_regions.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* The direction's y of a (tile-local) texel centre, as projection.glsl computes the whole direction. */
static double dir_y(const SkyPush *p, double x, double y)
{
    double gx = x + p->projection.y, gy = y + p->projection.z;
    int kind = (int)p->projection.x;
    if (kind == VKSKY_PROJECTION_EQUIRECT) return sin(PI * (0.5 - gy * p->up.w));
    if (kind == VKSKY_PROJECTION_CUBEMAP) {
        double face = floor(gy * p->right.w), a = 2.0 * gx * p->right.w - 1.0;
        double b = 2.0 * (gy * p->right.w - face) - 1.0;
        double w[3] = {a, -b, 1.0};   /* +Z, -Z: y = -b; +X, -X: y = -b */
        if (face == 2.0) w[0] = a, w[1] = 1.0, w[2] = -b;
        if (face == 3.0) w[0] = a, w[1] = -1.0, w[2] = b;
        return w[1] / sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    }
    if (kind == VKSKY_PROJECTION_FISHEYE) {
        double qx = 2.0 * gx * p->right.w - 1.0, qy = 1.0 - 2.0 * gy * p->up.w;
        double r = fmin(sqrt(qx * qx + qy * qy), 1.0);
        return cos(r * 0.5 * PI);
    }
    double nx = 2.0 * gx * p->right.w - 1.0, ny = 1.0 - 2.0 * gy * p->up.w, w[3];
    w[0] = p->forward.x + nx * p->right.x + ny * p->up.x;
    w[1] = p->forward.y + nx * p->right.y + ny * p->up.y;
    w[2] = p->forward.z + nx * p->right.z + ny * p->up.z;
    return w[1] / sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Bounds on |d(v.y)/dx| and |d(v.y)/dy| over a rectangle where v = normalize(w), w affine: w0 at its centre, wx and
 * wy per texel, half extents hx, hy. d(v.y) = (dw.y - v.y (v . dw)) / |w|, with |w| >= w0 - |wx| hx - |wy| hy and
 * w . dw affine (its extremes at the corners). False where |w| may come near 0. */
static bool affine_bounds(const double w0[3], const double wx[3], const double wy[3], double hx, double hy,
                          double w_floor, double *lx, double *ly)
{
    double w_min = fmax(w_floor, sqrt(dot3(w0, w0)) - sqrt(dot3(wx, wx)) * hx - sqrt(dot3(wy, wy)) * hy);
    if (!(w_min > 1e-3)) return false;
    double px = fabs(dot3(w0, wx)) + hx * dot3(wx, wx) + hy * fabs(dot3(wx, wy));   /* max |w . wx| */
    double py = fabs(dot3(w0, wy)) + hx * fabs(dot3(wx, wy)) + hy * dot3(wy, wy);
    double vy = fmin(1.0, (fabs(w0[1]) + fabs(wx[1]) * hx + fabs(wy[1]) * hy) / w_min);   /* max |v.y| */
    /* The tighter of that and |dv| <= |dw| / |w|. */
    *lx = fmin(sqrt(dot3(wx, wx)), fabs(wx[1]) + vy * px / w_min) / w_min;
    *ly = fmin(sqrt(dot3(wy, wy)), fabs(wy[1]) + vy * py / w_min) / w_min;
    return true;
}

/* Whether every texel centre of columns i0..i1, rows j0..j1 (one cube face at most) is beyond the horizon path's
 * reach, all on one side: that side (1 sky, -1 ground), or 0. lx, ly: bounds on |df/dx|, |df/dy| per texel over the rectangle; |f| >= |f(c)| - lx hx -
 * ly hy (hx, hy its half extents), and the sky pass's gradient is at most hypot(lx, ly): |f| > 4 hypot(lx, ly) makes
 * |d| > 4 (2 would do; the rest is for the GPU's float gradient). */
static int rect_far(const SkyPush *p, int i0, int i1, int j0, int j1)
{
    double cx = 0.5 * (i0 + i1) + 0.5, cy = 0.5 * (j0 + j1) + 0.5, hx = 0.5 * (i1 - i0), hy = 0.5 * (j1 - j0);
    double f = dir_y(p, cx, cy) - p->horizon.x, lx, ly;
    double gx = cx + p->projection.y, gy = cy + p->projection.z;
    int kind = (int)p->projection.x;
    if (kind == VKSKY_PROJECTION_EQUIRECT) {
        lx = 0.0, ly = PI * p->up.w;
    } else if (kind == VKSKY_PROJECTION_FISHEYE) {
        /* |d(v.y)| = sin(r pi / 2) (pi / 2) |dr|: the sine at the rectangle's largest r. */
        double qx = 2.0 * gx * p->right.w - 1.0, qy = 1.0 - 2.0 * gy * p->up.w;
        double reach = hypot(2.0 * p->right.w * hx, 2.0 * p->up.w * hy);
        if (hypot(qx, qy) - reach > 1.0 + 1e-6) return 1;   /* wholly outside the circle: d = +1e4 there */
        double r_max = fmin(1.0, hypot(qx, qy) + reach);
        double s = sin(0.5 * PI * r_max);
        lx = PI * p->right.w * s, ly = PI * p->up.w * s;
    } else if (kind == VKSKY_PROJECTION_CUBEMAP) {
        /* Inside a face w = (a, -b, 1) up to signs and order (projection.glsl), a, b moving 2 / S a texel. */
        double face = floor(gy * p->right.w), a = 2.0 * gx * p->right.w - 1.0;
        double b = 2.0 * (gy * p->right.w - face) - 1.0, k = 2.0 * p->right.w;
        double w0[3] = {a, -b, 1.0}, wx[3] = {k, 0.0, 0.0}, wy[3] = {0.0, -k, 0.0};
        if (face == 2.0) w0[1] = 1.0, w0[2] = -b, wy[1] = 0.0, wy[2] = -k;
        if (face == 3.0) w0[1] = -1.0, w0[2] = b, wy[1] = 0.0, wy[2] = k;
        if (!affine_bounds(w0, wx, wy, hx, hy, 1.0, &lx, &ly)) return 0;   /* |w| >= 1 on a face */
    } else {
        double nx = 2.0 * gx * p->right.w - 1.0, ny = 1.0 - 2.0 * gy * p->up.w;
        double w0[3] = {p->forward.x + nx * p->right.x + ny * p->up.x, p->forward.y + nx * p->right.y + ny * p->up.y,
                        p->forward.z + nx * p->right.z + ny * p->up.z};
        double wx[3] = {2.0 * p->right.w * p->right.x, 2.0 * p->right.w * p->right.y, 2.0 * p->right.w * p->right.z};
        double wy[3] = {-2.0 * p->up.w * p->up.x, -2.0 * p->up.w * p->up.y, -2.0 * p->up.w * p->up.z};
        if (!affine_bounds(w0, wx, wy, hx, hy, 0.0, &lx, &ly)) return 0;
    }
    return fabs(f) > lx * hx + ly * hy + 4.0 * hypot(lx, ly) + 1e-5 ? (f > 0.0 ? 1 : -1) : 0;
}

/* Whether output tile [x0, x1) x [y0, y1) reads only far texels: its bilinear taps (and at scale 1 its own texels),
 * one texel more each way, clamped to the image. */
static bool tile_far(const SkyPush *p, VkExtent2D hdr, VkExtent2D display, uint32_t x0, uint32_t x1, uint32_t y0,
                     uint32_t y1)
{
    double sx = (double)hdr.width / display.width, sy = (double)hdr.height / display.height;
    int i0 = (int)floor((x0 + 0.5) * sx - 0.5) - 1, i1 = (int)floor((x1 - 0.5) * sx - 0.5) + 2;
    int j0 = (int)floor((y0 + 0.5) * sy - 0.5) - 1, j1 = (int)floor((y1 - 0.5) * sy - 0.5) + 2;
    i0 = i0 < 0 ? 0 : i0, j0 = j0 < 0 ? 0 : j0;
    i1 = i1 > (int)hdr.width - 1 ? (int)hdr.width - 1 : i1, j1 = j1 > (int)hdr.height - 1 ? (int)hdr.height - 1 : j1;
    if ((int)p->projection.x != VKSKY_PROJECTION_CUBEMAP) return rect_far(p, i0, i1, j0, j1) != 0;
    /* Face by face: a face is 1 / right.w rows of the whole image; the tile's rows start projection.z rows in. Every
     * part on the same side: a tap pair across a face's edge may join the ground of one face and the sky of the next
     * (their bilinear d then near 0). */
    double face_rows = 1.0 / p->right.w;
    int side = 0;
    for (int j = j0; j <= j1;) {
        double face = floor((j + 0.5 + p->projection.z) / face_rows);
        int end = (int)ceil((face + 1.0) * face_rows - p->projection.z - 0.5) - 1;   /* the face's last row */
        if (end < j) end = j;
        if (end > j1) end = j1;
        int part = rect_far(p, i0, i1, j, end);
        if (part == 0 || (side && part != side)) return false;
        side = part;
        j = end + 1;
    }
    return true;
}

static void one_region(tonemap_regions *out, VkExtent2D display)
{
    out->count = 1;
    out->region[0] = (tonemap_region){{{0, 0}, display}, true};
}

void tonemap_regions_plan(tonemap_regions *out, const SkyPush *sky, VkExtent2D hdr, VkExtent2D display)
{
    const char *env = getenv("VKSKY_TONEMAP_SPLIT");
    if ((env && !strcmp(env, "0")) || !display.width || !display.height || !hdr.width || !hdr.height) {
        one_region(out, display);
        return;
    }
    out->count = 0;
    uint32_t row_first = 0, prev_first = 0, prev_count = 0;   /* this and the previous tile row's regions */
    for (uint32_t y0 = 0; y0 < display.height; y0 += TONEMAP_REGION_ROWS) {
        uint32_t y1 = y0 + TONEMAP_REGION_ROWS < display.height ? y0 + TONEMAP_REGION_ROWS : display.height;
        row_first = out->count;
        for (uint32_t x0 = 0; x0 < display.width; x0 += TONEMAP_REGION_TILE) {
            uint32_t x1 = x0 + TONEMAP_REGION_TILE < display.width ? x0 + TONEMAP_REGION_TILE : display.width;
            bool horizon = !tile_far(sky, hdr, display, x0, x1, y0, y1);
            tonemap_region *last = out->count > row_first ? &out->region[out->count - 1] : NULL;
            if (last && last->horizon == horizon) {
                last->rect.extent.width = x1 - last->rect.offset.x;
                continue;
            }
            if (out->count == TONEMAP_REGIONS_MAX) {
                one_region(out, display);
                return;
            }
            out->region[out->count++] = (tonemap_region){{{(int32_t)x0, (int32_t)y0}, {x1 - x0, y1 - y0}}, horizon};
        }
        /* The same runs as the row above: grow those instead. */
        uint32_t n = out->count - row_first;
        bool same = prev_count == n && row_first > 0;
        for (uint32_t k = 0; same && k < n; ++k) {
            const tonemap_region *a = &out->region[prev_first + k], *b = &out->region[row_first + k];
            same = a->horizon == b->horizon && a->rect.offset.x == b->rect.offset.x &&
                   a->rect.extent.width == b->rect.extent.width;
        }
        if (same) {
            for (uint32_t k = 0; k < n; ++k) out->region[prev_first + k].rect.extent.height += y1 - y0;
            out->count = row_first;
        } else {
            prev_first = row_first, prev_count = n;
        }
    }
}
