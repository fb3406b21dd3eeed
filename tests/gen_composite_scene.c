/* Seed 004's test scene (../shared/seeds/004_*, "Test Scene Reference"), written the way a renderer hands it to a
 * compositor: camera 218.8 m above the ground at (-3.5, -8.5, 218.8) m (world Z up, metres), 960x540, a ground
 * plane (z = 0) and spheres standing on it 1, 5, 10 and 20 km from the camera, sky above.
 *
 *   gen_composite_scene DIR [WIDTH HEIGHT [sky]]
 *     DIR/render.exr    one Blender-style multilayer file: ViewLayer.Combined.R,G,B,A (half) and
 *                       ViewLayer.Position.X,Y,Z (float), worldToCamera and worldToNDC attributes; sky pixels have
 *                       alpha 0 and position (0, 0, 0), as Blender writes them
 *     DIR/beauty.exr    the beauty alone: R, G, B, A (half)
 *     DIR/position.exr  the position alone as R, G, B (float; sky: NaN), no camera attributes
 *     DIR/camera.txt    the flags that describe the camera without the attributes (the surfaces are lit by a
 *                       sun at azimuth -70, elevation 12 degrees: composite with --sun-azimuth -70 --sun-elevation 12):
 *                       --camera-position -3.5,-8.5,218.8 --yaw -90 --pitch -3 --fov 40
 *   "sky": the camera looks 60 degrees up: no pixel has geometry (a bad input for the composite).
 *   "edges" (issue 28): the scene rendered at 4x the size with no anti-aliasing (alpha 0 or 1) into DIR/hi.exr, and
 *     from it, as Cycles writes it, the WIDTH x HEIGHT render with 4x4 coverage (alpha in [0, 1], premultiplied
 *     beauty) whose Position and Depth come from one of the pixel's 16 samples ((0, 0, 0) and 1e10 where it missed):
 *     DIR/edges.exr   ViewLayer.Combined, ViewLayer.Position, and Composite.Combined (the beauty x 2: a grade)
 *     DIR/edges2.exr  the same and a second view layer Other (beauty x 0.5, positions 1 km higher)
 *     DIR/depth.exr   ViewLayer.Combined and ViewLayer.Depth.Z (camera-space Z) only
 *     DIR/opaque.exr  an opaque film: alpha 1 everywhere, the background grey at position (0, 0, 0)
 *     DIR/halfpos.exr ViewLayer.Position stored as HALF: the ground beyond 65504 m overflows to inf
 *     Box-filtering a composite of hi.exr 4x4 gives the coverage-correct composite of edges.exr.
 *   "flat": DIR/render.exr of up to 16384 x 16384 pixels made fast (every row the same: it compresses to nothing),
 *     no camera attributes: the left 1/64 of the width a grey surface on the ground 1 km north of the camera
 *     (-3.5, -8.5, 218.8), the rest background (alpha 0, position NaN); for the composite's memory bound.
 *
 * The pixel rays follow vksky's image convention (docs/model.md: yaw/pitch like the sun's azimuth/elevation, in the
 * world turned so that Z is up, north +Y and east +X: (north, up, east) -> (east, north, up)) but are computed here
 * on their own; the files are
 * written through OpenEXRCore directly, not through vksky's writers. */
#include <math.h>
#include <stdbool.h>
#include <openexr.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;
static const double CAMERA[3] = {-3.5, -8.5, 218.8};
static const double YAW = -90.0, FOV = 40.0;
static double PITCH = -3.0;   /* "sky": 60 (nothing but sky in view) */

typedef struct sphere { double centre[3], radius, albedo[3]; } sphere;

/* vksky's direction of (azimuth, elevation) in its local frame (north, up, east), turned into the Z-up world
 * (Blender's: north +Y, east +X). */
static void world_dir(double az_deg, double el_deg, double out[3])
{
    double az = az_deg * PI / 180.0, el = el_deg * PI / 180.0;
    double l[3] = {cos(el) * cos(az), sin(el), cos(el) * sin(az)};
    out[0] = l[2], out[1] = l[0], out[2] = l[1];
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static uint16_t to_half(float f)
{
    uint32_t x;
    memcpy(&x, &f, 4);
    uint32_t sign = (x >> 16) & 0x8000u;
    int e = (int)((x >> 23) & 0xff) - 127 + 15;
    uint32_t m = x & 0x7fffffu;
    if (((x >> 23) & 0xff) == 0xff) return (uint16_t)(sign | 0x7c00u | (m ? 0x200u : 0u));
    if (e >= 31) return (uint16_t)(sign | 0x7c00u);
    if (e <= 0) {
        if (e < -10) return (uint16_t)sign;
        m |= 0x800000u;
        uint32_t shift = (uint32_t)(14 - e);
        uint32_t h = m >> shift, rest = m & ((1u << shift) - 1), half = 1u << (shift - 1);
        if (rest > half || (rest == half && (h & 1))) ++h;
        return (uint16_t)(sign | h);
    }
    uint32_t h = ((uint32_t)e << 10) | (m >> 13), rest = m & 0x1fffu;
    if (rest > 0x1000u || (rest == 0x1000u && (h & 1))) ++h;   /* may carry into the exponent: still right */
    return (uint16_t)(sign | h);
}

typedef struct channel { const char *name; int half; const float *plane; } channel;

/* One scanline part: planar float channels (stored as HALF or FLOAT), optional camera attributes. */
static int write_exr(const char *path, int w, int h, const channel *ch, int count, const float *w2c, const float *w2n,
                     int one_row)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t f = NULL;
    int part = 0;
    exr_result_t rc = exr_start_write(&f, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (!rc) rc = exr_add_part(f, "rgba", EXR_STORAGE_SCANLINE, &part);
    if (!rc) rc = exr_initialize_required_attr_simple(f, part, w, h, EXR_COMPRESSION_ZIP);
    for (int c = 0; c < count && !rc; ++c)
        rc = exr_add_channel(f, part, ch[c].name, ch[c].half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT,
                             EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    exr_attr_m44f_t m;
    if (!rc && w2c) memcpy(m.m, w2c, sizeof m.m), rc = exr_attr_set_m44f(f, part, "worldToCamera", &m);
    if (!rc && w2n) memcpy(m.m, w2n, sizeof m.m), rc = exr_attr_set_m44f(f, part, "worldToNDC", &m);
    if (!rc) rc = exr_write_header(f);
    int32_t lines = 1;
    if (!rc) rc = exr_get_scanlines_per_chunk(f, part, &lines);
    for (int y0 = 0; y0 < h && !rc; y0 += lines) {
        exr_chunk_info_t ci;
        exr_encode_pipeline_t enc;
        memset(&enc, 0, sizeof enc);
        rc = exr_write_scanline_chunk_info(f, part, y0, &ci);
        if (!rc) rc = exr_encoding_initialize(f, part, &ci, &enc);
        void *bufs[8] = {0};
        for (int k = 0; k < enc.channel_count && !rc; ++k) {
            exr_coding_channel_info_t *e = &enc.channels[k];
            const channel *c = NULL;
            for (int j = 0; j < count; ++j)
                if (!strcmp(ch[j].name, e->channel_name)) c = &ch[j];
            int bpe = c->half ? 2 : 4;
            bufs[k] = malloc((size_t)w * ci.height * bpe);
            for (int y = 0; y < ci.height; ++y)
                for (int x = 0; x < w; ++x) {
                    float v = c->plane[one_row ? (size_t)x : (size_t)(y0 + y) * w + x];   /* one_row: every row the same */
                    size_t at = (size_t)y * w + x;
                    if (c->half) ((uint16_t *)bufs[k])[at] = to_half(v);
                    else ((float *)bufs[k])[at] = v;
                }
            e->encode_from_ptr = bufs[k];
            e->user_pixel_stride = bpe;
            e->user_line_stride = w * bpe;
            e->user_data_type = c->half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
            e->user_bytes_per_element = (int16_t)bpe;
        }
        if (!rc) rc = exr_encoding_choose_default_routines(f, part, &enc);
        if (!rc) rc = exr_encoding_run(f, part, &enc);
        exr_encoding_destroy(f, &enc);
        for (int k = 0; k < 8; ++k) free(bufs[k]);
    }
    exr_result_t frc = exr_finish(&f);
    if (rc || frc) {
        fprintf(stderr, "gen_composite_scene: %s: %s\n", path, exr_get_default_error_message(rc ? rc : frc));
        return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    bool edges = argc == 5 && !strcmp(argv[4], "edges"), flat = argc == 5 && !strcmp(argv[4], "flat");
    if (argc != 2 && argc != 4 && !(argc == 5 && (!strcmp(argv[4], "sky") || edges || flat))) {
        fprintf(stderr, "usage: gen_composite_scene DIR [WIDTH HEIGHT [sky|edges|flat]]\n");
        return 2;
    }
    if (argc == 5 && !strcmp(argv[4], "sky")) PITCH = 60.0;
    int W = argc >= 4 ? atoi(argv[2]) : 960, H = argc >= 4 ? atoi(argv[3]) : 540;
    const int SS = 4;   /* "edges": samples per pixel side */
    if (edges) W *= SS, H *= SS;
    int most = flat ? 16384 : 8192;
    if (W < 8 || H < 8 || W > most || H > most) {
        fprintf(stderr, "gen_composite_scene: WIDTH and HEIGHT in [8, %d]\n", most);
        return 2;
    }
    if (flat) {   /* one row of each constant plane, repeated: write_exr reads plane[y * w + x] */
        float *row = malloc((size_t)W * 7 * sizeof(float));
        float *px = row, value[7] = {0.2f, 0.2f, 0.2f, 1.0f, (float)CAMERA[0], (float)(CAMERA[1] + 1000.0), 0.0f};
        for (int k = 0; k < 7; ++k)
            for (int x = 0; x < W; ++x) px[(size_t)k * W + x] = x < W / 64 ? value[k] : k < 4 ? 0.0f : NAN;
        const char *names[7] = {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B",
                                "ViewLayer.Combined.A", "ViewLayer.Position.X", "ViewLayer.Position.Y",
                                "ViewLayer.Position.Z"};
        channel ch[7];
        for (int k = 0; k < 7; ++k) ch[k] = (channel){names[k], k < 4, px + (size_t)k * W};
        char path[4096];
        snprintf(path, sizeof path, "%s/render.exr", argv[1]);
        int rc = write_exr(path, W, H, ch, 7, NULL, NULL, 1);
        free(row);
        return rc ? 1 : 0;
    }
    /* The camera basis (vksky's: right = forward x up-axis, up = right x forward) in world axes. */
    double f[3], right[3], up[3], sun[3];
    world_dir(YAW, PITCH, f);
    world_dir(YAW + 90.0, 0.0, right);
    up[0] = right[1] * f[2] - right[2] * f[1], up[1] = right[2] * f[0] - right[0] * f[2],
    up[2] = right[0] * f[1] - right[1] * f[0];
    world_dir(-70.0, 12.0, sun);   /* the sun of the composite's --sun-azimuth -70 --sun-elevation 12 */
    double ty = tan(0.5 * FOV * PI / 180.0), tx = ty * W / H;
    /* Spheres standing on the ground, 1, 5, 10, 20 km away, spread across the view, ~3 degrees across. */
    sphere spheres[4];
    const double dist[4] = {1000.0, 5000.0, 10000.0, 20000.0}, az[4] = {-14.0, -5.0, 4.0, 13.0};
    const double albedo[4][3] = {{0.8, 0.2, 0.2}, {0.2, 0.7, 0.2}, {0.2, 0.3, 0.8}, {0.8, 0.8, 0.8}};
    for (int i = 0; i < 4; ++i) {
        double d[3];
        world_dir(YAW + az[i], 0.0, d);
        spheres[i].radius = 0.03 * dist[i];
        for (int k = 0; k < 3; ++k) spheres[i].centre[k] = CAMERA[k] + d[k] * dist[i], spheres[i].albedo[k] = albedo[i][k];
        spheres[i].centre[2] = spheres[i].radius;
    }
    size_t n = (size_t)W * H;
    float *pl = calloc(n * 8, sizeof(float));
    float *R = pl, *G = pl + n, *B = pl + 2 * n, *A = pl + 3 * n, *X = pl + 4 * n, *Y = pl + 5 * n, *Z = pl + 6 * n,
          *nanpos = pl + 7 * n;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double nx = 2.0 * (x + 0.5) / W - 1.0, ny = 1.0 - 2.0 * (y + 0.5) / H, v[3];
            for (int k = 0; k < 3; ++k) v[k] = f[k] + nx * tx * right[k] + ny * ty * up[k];
            double len = sqrt(dot(v, v));
            for (int k = 0; k < 3; ++k) v[k] /= len;
            double t_hit = INFINITY, normal[3] = {0, 0, 1}, alb[3] = {0.25, 0.22, 0.18};
            if (v[2] < 0.0) t_hit = -CAMERA[2] / v[2];   /* the ground plane */
            for (int i = 0; i < 4; ++i) {
                double oc[3] = {CAMERA[0] - spheres[i].centre[0], CAMERA[1] - spheres[i].centre[1],
                                CAMERA[2] - spheres[i].centre[2]};
                double b = dot(oc, v), c = dot(oc, oc) - spheres[i].radius * spheres[i].radius, disc = b * b - c;
                if (disc < 0.0) continue;
                double t = -b - sqrt(disc);
                if (t > 0.0 && t < t_hit) {
                    t_hit = t;
                    for (int k = 0; k < 3; ++k)
                        normal[k] = (CAMERA[k] + t * v[k] - spheres[i].centre[k]) / spheres[i].radius,
                        alb[k] = spheres[i].albedo[k];
                }
            }
            size_t at = (size_t)y * W + x;
            if (!isfinite(t_hit)) {   /* sky: what Blender writes (alpha 0, position 0); NaN in the plain file */
                nanpos[at] = NAN;
                continue;
            }
            /* A plain Lambertian surface under a white sun and sky, in scene-linear units near 1. */
            double lit = 0.3 + 2.0 * fmax(0.0, dot(normal, sun));
            R[at] = (float)(alb[0] * lit), G[at] = (float)(alb[1] * lit), B[at] = (float)(alb[2] * lit), A[at] = 1.0f;
            X[at] = (float)(CAMERA[0] + t_hit * v[0]), Y[at] = (float)(CAMERA[1] + t_hit * v[1]);
            Z[at] = (float)(CAMERA[2] + t_hit * v[2]);
            nanpos[at] = 0.0f;
        }
    /* The plain position file: R, G, B = X, Y, Z, NaN where there is no geometry. */
    float *PX = malloc(n * 3 * sizeof(float)), *PY = PX + n, *PZ = PX + 2 * n;
    for (size_t i = 0; i < n; ++i) {
        bool sky = isnan(nanpos[i]);
        PX[i] = sky ? NAN : X[i], PY[i] = sky ? NAN : Y[i], PZ[i] = sky ? NAN : Z[i];
    }
    /* worldToCamera (row vectors: p_cam = p_world M; the camera looks along -Z): column j of the rotation is camera
     * axis j (right, up, -forward), the last row -c . axis_j. worldToNDC = worldToCamera x P, NDC in [-1, 1]. */
    const double *axes[3] = {right, up, f};
    float w2c[16] = {0}, w2n[16] = {0};
    for (int j = 0; j < 3; ++j) {
        double s = j == 2 ? -1.0 : 1.0;
        for (int i = 0; i < 3; ++i) w2c[4 * i + j] = (float)(s * axes[j][i]);
        w2c[12 + j] = (float)(-s * dot(CAMERA, axes[j]));
    }
    w2c[15] = 1.0f;
    double P[4][4] = {{1.0 / tx, 0, 0, 0}, {0, 1.0 / ty, 0, 0}, {0, 0, -1.0, -1.0}, {0, 0, -0.2, 0}};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0.0;
            for (int k = 0; k < 4; ++k) s += w2c[4 * i + k] * P[k][j];
            w2n[4 * i + j] = (float)s;
        }
    char path[4096];
    int rc = 0;
    if (edges) {
        float *depth_hi = nanpos;   /* camera-space Z of each sample (the plain file's NaN plane is not written) */
        for (size_t i = 0; i < n; ++i) {
            double d[3] = {X[i] - CAMERA[0], Y[i] - CAMERA[1], Z[i] - CAMERA[2]};
            depth_hi[i] = A[i] > 0.0f ? (float)dot(d, f) : 1e10f;
        }
        channel hi[7] = {{"ViewLayer.Combined.R", 1, R}, {"ViewLayer.Combined.G", 1, G}, {"ViewLayer.Combined.B", 1, B},
                         {"ViewLayer.Combined.A", 1, A}, {"ViewLayer.Position.X", 0, X}, {"ViewLayer.Position.Y", 0, Y},
                         {"ViewLayer.Position.Z", 0, Z}};
        snprintf(path, sizeof path, "%s/hi.exr", argv[1]);
        rc |= write_exr(path, W, H, hi, 7, w2c, w2n, 0);
        int w = W / SS, h = H / SS;
        size_t m = (size_t)w * h;
        float *lo = calloc(m * 19, sizeof(float));
        float *L[19];
        for (int k = 0; k < 19; ++k) L[k] = lo + (size_t)k * m;
        /* 0-3 beauty, 4-6 position, 7 depth, 8-11 Composite, 12-15 Other beauty, 16-18 Other position */
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                size_t o = (size_t)y * w + x;
                for (int sy = 0; sy < SS; ++sy)
                    for (int sx = 0; sx < SS; ++sx) {
                        size_t i = (size_t)(y * SS + sy) * W + (size_t)(x * SS + sx);
                        L[0][o] += R[i] / (SS * SS), L[1][o] += G[i] / (SS * SS), L[2][o] += B[i] / (SS * SS);
                        L[3][o] += A[i] / (SS * SS);
                    }
                /* Position and depth from one sample, as Cycles does: a fixed pseudo-random one per pixel. */
                unsigned hash = (unsigned)(x * 73856093u) ^ (unsigned)(y * 19349663u);
                int sx = (int)(hash % SS), sy = (int)((hash / SS) % SS);
                size_t i = (size_t)(y * SS + sy) * W + (size_t)(x * SS + sx);
                L[4][o] = X[i], L[5][o] = Y[i], L[6][o] = Z[i], L[7][o] = depth_hi[i];
                for (int c = 0; c < 4; ++c) L[8 + c][o] = L[c][o] * (c < 3 ? 2.0f : 1.0f), L[12 + c][o] = L[c][o] * (c < 3 ? 0.5f : 1.0f);
                L[16][o] = L[4][o], L[17][o] = L[5][o], L[18][o] = L[6][o] + (L[3][o] > 0.0f ? 1000.0f : 0.0f);
            }
        const char *names[19] = {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B",
                                 "ViewLayer.Combined.A", "ViewLayer.Position.X", "ViewLayer.Position.Y",
                                 "ViewLayer.Position.Z", "ViewLayer.Depth.Z", "Composite.Combined.R",
                                 "Composite.Combined.G", "Composite.Combined.B", "Composite.Combined.A",
                                 "Other.Combined.R", "Other.Combined.G", "Other.Combined.B", "Other.Combined.A",
                                 "Other.Position.X", "Other.Position.Y", "Other.Position.Z"};
        channel all[19];
        for (int k = 0; k < 19; ++k) all[k] = (channel){names[k], k < 4 || (k >= 8 && k < 16), L[k]};
        channel one[11];   /* edges.exr: beauty, position, Composite */
        for (int k = 0; k < 7; ++k) one[k] = all[k];
        for (int k = 0; k < 4; ++k) one[7 + k] = all[8 + k];
        snprintf(path, sizeof path, "%s/edges.exr", argv[1]);
        rc |= write_exr(path, w, h, one, 11, w2c, w2n, 0);
        channel two[18];
        for (int k = 0, j = 0; k < 19; ++k)
            if (k != 7) two[j++] = all[k];
        snprintf(path, sizeof path, "%s/edges2.exr", argv[1]);
        rc |= write_exr(path, w, h, two, 18, w2c, w2n, 0);
        channel dep[5] = {all[0], all[1], all[2], all[3], all[7]};
        snprintf(path, sizeof path, "%s/depth.exr", argv[1]);
        rc |= write_exr(path, w, h, dep, 5, w2c, w2n, 0);
        channel half_pos[7];
        for (int k = 0; k < 7; ++k) half_pos[k] = all[k], half_pos[k].half = 1;
        snprintf(path, sizeof path, "%s/halfpos.exr", argv[1]);
        rc |= write_exr(path, w, h, half_pos, 7, w2c, w2n, 0);
        for (size_t i = 0; i < m; ++i)
            if (L[3][i] < 1.0f) {   /* an opaque film: the background fills the rest; no sample hit, no position */
                for (int c = 0; c < 3; ++c) L[c][i] += (1.0f - L[3][i]) * 0.5f;
                L[3][i] = 1.0f;
            }
        snprintf(path, sizeof path, "%s/opaque.exr", argv[1]);
        rc |= write_exr(path, w, h, one, 7, w2c, w2n, 0);
        free(lo);
        free(pl);
        return rc ? 1 : 0;
    }
    channel multi[7] = {{"ViewLayer.Combined.R", 1, R}, {"ViewLayer.Combined.G", 1, G}, {"ViewLayer.Combined.B", 1, B},
                        {"ViewLayer.Combined.A", 1, A}, {"ViewLayer.Position.X", 0, X}, {"ViewLayer.Position.Y", 0, Y},
                        {"ViewLayer.Position.Z", 0, Z}};
    snprintf(path, sizeof path, "%s/render.exr", argv[1]);
    rc |= write_exr(path, W, H, multi, 7, w2c, w2n, 0);
    channel beauty[4] = {{"R", 1, R}, {"G", 1, G}, {"B", 1, B}, {"A", 1, A}};
    snprintf(path, sizeof path, "%s/beauty.exr", argv[1]);
    rc |= write_exr(path, W, H, beauty, 4, NULL, NULL, 0);
    channel position[3] = {{"R", 0, PX}, {"G", 0, PY}, {"B", 0, PZ}};
    snprintf(path, sizeof path, "%s/position.exr", argv[1]);
    rc |= write_exr(path, W, H, position, 3, NULL, NULL, 0);
    snprintf(path, sizeof path, "%s/camera.txt", argv[1]);
    FILE *cf = fopen(path, "w");
    if (cf) {
        fprintf(cf, "--camera-position %g,%g,%g --yaw %g --pitch %g --fov %g\n", CAMERA[0], CAMERA[1], CAMERA[2], YAW,
                PITCH, FOV);
        rc |= fclose(cf) != 0;
    } else {
        rc = 1;
    }
    free(pl);
    free(PX);
    return rc ? 1 : 0;
}
