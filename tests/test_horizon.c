/* test_horizon (issue 26): the planet's edge per pixel, the way to space, the dither. Validation and synchronization
 * validation on (gpu_test.h); any message fails.
 *
 * 1. Position: an airless planet with a white ground lit head-on at the horizon (the sun along the ground's normal
 *    where the view axis meets the edge), black above. On the centre column of an odd width the horizon is level;
 *    its measured row (the rows' ground coverage summed, each pixel / the full-ground value just below) must be
 *    within 1/4 pixel of the analytic horizon: the elevation -atan(sqrt(h (2R + h)) / R) projected by the pinhole
 *    (y = H (1 - tan(e - pitch) / tan(fov / 2)) / 2), all in double here. Altitudes 1 m .. 36 000 km, render
 *    scales 0.25, 0.5, 1, the march and the sky-view LUT (auto below the top), fragment and compute passes, two
 *    pitches and two fovs. Then every preset (low, medium, high, ultra, cpu: its own LUT sizes, steps, sky mode and
 *    render scale, app/quality) at the same six altitudes.
 * 2. Leak: Earth, black ground, sunset, a camera 1 m up (the ground's own in-scattering is a few thousandths of the
 *    sky): no pixel of the rows wholly below the horizon within 2 px of it above 5 % of the sky pixel above the
 *    horizon in its column, at scales 0.25 and 0.5 (the upsample) and 1, march and LUT.
 * 3. The way to space: an altitude sweep 0 -> 1000 km (5 km a frame), --sky-mode auto against the march: no pixel's
 *    change from one frame to the next exceeds the march's own change by more than 1 % of the pixel (floored at
 *    0.1 % of the frame's brightest: space is black). The lookup blends into the march from a quarter of the
 *    atmosphere's height to its top (its rays below 3 degrees of elevation from a tenth to three tenths); the
 *    march's step exponent moves to uniform over the upper half (horizon.glsl, sky_common.glsl).
 * 4. Dither: a twilight gradient in 8 bits against the exact tone map of the frame's own linear pixels: the region's
 *    mean within 0.1 LSB, every pixel within 1 LSB of the undithered one, fewer than 60 % of horizontal neighbours
 *    identical, two renders byte-identical. */
#include "gpu_test.h"
#include "sky/renderer.h"
#include "sky/view_params.h"
#include "app/quality/quality.h"

typedef struct run_desc {
    int width, height;
    double scale;
    sky_pass_kind kind;
    post_pass_kind post;
    VkFormat format;
} run_desc;

static void renderer_open(sky_renderer *r, gpu_context *ctx, const run_desc *d, const model_atmosphere *a,
                          const sky_features *f)
{
    sky_renderer_desc desc = {.width = (uint32_t)d->width, .height = (uint32_t)d->height, .render_scale = d->scale,
                              .readback = true, .display_format = d->format ? d->format : VK_FORMAT_R8G8B8A8_SRGB,
                              .post_pass = d->post, .lut = sky_lut_quality_default()};
    sky_renderer_create(r, ctx, &desc);
    sky_renderer_set_atmosphere(r, a, SUN_RADIUS_RAD);
    sky_renderer_set_features(r, f);
}

/* The frame's linear luminance (EXR pixels) into lum, its display bytes into display (either may be NULL). */
static void render(sky_renderer *r, const sky_view *v, int w, int h, float *lum, unsigned char *display)
{
    frame_desc f = {.view = v};
    sky_renderer_render(r, &f);
    const uint16_t *half = r->readback_linear.mapped;
    for (size_t i = 0; lum && i < (size_t)w * h; ++i)
        lum[i] = (float)(0.2126 * io_half_to_float(half[4 * i]) + 0.7152 * io_half_to_float(half[4 * i + 1]) +
                         0.0722 * io_half_to_float(half[4 * i + 2]));
    if (display) memcpy(display, r->readback_display.mapped, (size_t)w * h * 4);
}

static const double R_GROUND = 6360.0;

static double horizon_elevation(double h) { return -atan(sqrt(h * (2.0 * R_GROUND + h)) / R_GROUND); }

/* The analytic horizon's row (continuous, 0 at the top edge) on the centre column. */
static double horizon_row(double h, double pitch_deg, double fov_deg, int height)
{
    double ndc = tan(horizon_elevation(h) - pitch_deg * TEST_DEG) / tan(0.5 * fov_deg * TEST_DEG);
    return 0.5 * height * (1.0 - ndc);
}

static double worst_position;
static const char *position_label = "";   /* the preset under test, for the failure's line */

static void check_position(sky_renderer *r, const run_desc *d, sky_view *v, double h, double offset_frac,
                           double fov, float *lum)
{
    /* From 36 000 km the planet is a disc 17 degrees across, its shading (the sun's cosine) falling steeply inside
     * the limb: at the fovs of the lower cameras the pixels the estimate reads below the edge (3 px) would be
     * darker than the edge's own ground. A twentieth of the fov (1 .. 5 degrees) keeps them within 1 %. */
    if (h > 10000.0) fov /= 20.0;
    v->altitude_km = h;
    v->fov_deg = fov;
    double e_h = horizon_elevation(h) / TEST_DEG;
    v->pitch_deg = e_h + offset_frac * fov;
    /* The ground's normal at the edge on the view axis: elevation 90 + e_h toward the view's azimuth. */
    v->sun_elevation_deg = 90.0 + e_h, v->sun_azimuth_deg = v->yaw_deg;
    render(r, v, d->width, d->height, lum, NULL);
    double y_true = horizon_row(h, v->pitch_deg, fov, d->height);
    int x = d->width / 2, end = (int)floor(y_true) + 3;
    if (end >= d->height || y_true < 2.0) {
        CHECK(0, "horizon row %.2f off the image", y_true);
        return;
    }
    double ground = lum[(size_t)end * d->width + x], covered = 0.0;
    for (int y = 0; y < end; ++y) covered += lum[(size_t)y * d->width + x] / ground;
    double y_measured = end - covered, err = fabs(y_measured - y_true);
    if (err > worst_position) worst_position = err;
    CHECK(ground > 0.0 && err <= 0.25,
          "%sh %g km pitch %.3f fov %g scale %g kind %d mode %d: horizon at row %.3f, analytic %.3f (%.3f px)",
          position_label, h, v->pitch_deg, fov, d->scale, d->kind, v->mode, y_measured, y_true, err);
}

static void test_position(gpu_context *ctx)
{
    model_atmosphere air;
    model_atmosphere_earth(&air);
    for (int c = 0; c < 3; ++c)
        air.rayleigh_scattering[c] = air.mie_scattering[c] = air.mie_absorption[c] = air.ozone_absorption[c] = 0.0;
    sky_features f = sky_features_default();
    f.ground_albedo[0] = f.ground_albedo[1] = f.ground_albedo[2] = 1.0;
    f.sun_disc = false;
    static const double altitudes[] = {0.001, 1.0, 10.0, 100.0, 400.0, 36000.0};
    static const double scales[] = {0.25, 0.5, 1.0};
    int frames = 0;
    for (int s = 0; s < 3; ++s) {
        run_desc d = {161, 128, scales[s], s == 1 ? SKY_PASS_COMPUTE : SKY_PASS_FRAGMENT,
                      s == 2 ? POST_PASS_COMPUTE : POST_PASS_FRAGMENT, 0};
        sky_renderer r;
        renderer_open(&r, ctx, &d, &air, &f);
        float *lum = malloc(sizeof(float) * d.width * d.height);
        for (int m = 0; m < 2; ++m)
            for (int a = 0; a < 6; ++a) {
                /* The sky-view LUT serves only inside the atmosphere (auto: the march above). */
                if (m == 1 && altitudes[a] >= 100.0) continue;
                sky_view v = sky_view_default();
                v.mode = m ? SKY_CHOICE_AUTO : SKY_CHOICE_MARCH;
                v.pass_kind = d.kind;
                v.bloom = false;
                v.tonemap = VKSKY_TONEMAP_CLAMP;
                for (int k = 0; k < 2; ++k) {
                    check_position(&r, &d, &v, altitudes[a], k ? 0.21 : -0.17, k ? 75.0 : 20.0, lum);
                    check_position(&r, &d, &v, altitudes[a], k ? -0.3 : 0.08, k ? 30.0 : 100.0, lum);
                    frames += 2;
                }
            }
        free(lum);
        sky_renderer_destroy(&r);
    }
    printf("position: %d frames, worst %.3f px from the analytic horizon (bound 0.25)\n", frames, worst_position);
}

/* Every preset with its own knobs (quality_apply: LUT sizes, steps, sky mode, render scale: low's and cpu's 0.5) on
 * the airless planet of test_position, at the six altitudes, a pitch above and one below the edge. */
static void test_presets(gpu_context *ctx)
{
    model_atmosphere air;
    model_atmosphere_earth(&air);
    for (int c = 0; c < 3; ++c)
        air.rayleigh_scattering[c] = air.mie_scattering[c] = air.mie_absorption[c] = air.ozone_absorption[c] = 0.0;
    sky_features f = sky_features_default();
    f.ground_albedo[0] = f.ground_albedo[1] = f.ground_albedo[2] = 1.0;
    f.sun_disc = false;
    static const char *presets[] = {"low", "medium", "high", "ultra", "cpu"};
    static const double altitudes[] = {0.001, 1.0, 10.0, 100.0, 400.0, 36000.0};
    char label[64];
    double before = worst_position;
    worst_position = 0.0;
    for (int p = 0; p < 5; ++p) {
        const quality_config *q = quality_preset(presets[p]);
        CHECK(q != NULL, "no preset %s", presets[p]);
        if (!q) continue;
        sky_view v = sky_view_default();
        sky_lut_quality lut = sky_lut_quality_default();
        double scale = 1.0;
        int bloom_mips = 0;
        bool bloom_quarter = false;
        quality_apply(q, &v, &lut, &scale, &bloom_mips, &bloom_quarter);
        v.bloom = false;
        v.tonemap = VKSKY_TONEMAP_CLAMP;
        run_desc d = {161, 128, scale, v.pass_kind, POST_PASS_FRAGMENT, 0};
        sky_renderer r;
        sky_renderer_desc desc = {.width = (uint32_t)d.width, .height = (uint32_t)d.height, .render_scale = scale,
                                  .readback = true, .display_format = VK_FORMAT_R8G8B8A8_SRGB,
                                  .post_pass = POST_PASS_FRAGMENT, .lut = lut};
        sky_renderer_create(&r, ctx, &desc);
        sky_renderer_set_atmosphere(&r, &air, SUN_RADIUS_RAD);
        sky_renderer_set_features(&r, &f);
        float *lum = malloc(sizeof(float) * d.width * d.height);
        snprintf(label, sizeof label, "preset %s: ", presets[p]);
        position_label = label;
        for (int a = 0; a < 6; ++a) {
            check_position(&r, &d, &v, altitudes[a], -0.17, 20.0, lum);
            check_position(&r, &d, &v, altitudes[a], 0.21, 75.0, lum);
        }
        position_label = "";
        free(lum);
        sky_renderer_destroy(&r);
    }
    printf("presets: low, medium, high, ultra, cpu at 6 altitudes, worst %.3f px from the analytic horizon (bound "
           "0.25)\n", worst_position);
    worst_position = fmax(worst_position, before);
}

static void test_leak(gpu_context *ctx)
{
    model_atmosphere earth;
    model_atmosphere_earth(&earth);
    sky_features f = sky_features_default();
    f.ground_albedo[0] = f.ground_albedo[1] = f.ground_albedo[2] = 0.0;
    f.sun_disc = false;
    static const double scales[] = {0.25, 0.5, 1.0};
    double worst = 0.0;
    for (int s = 0; s < 3; ++s) {
        run_desc d = {321, 180, scales[s], SKY_PASS_FRAGMENT, POST_PASS_FRAGMENT, 0};
        sky_renderer r;
        renderer_open(&r, ctx, &d, &earth, &f);
        float *lum = malloc(sizeof(float) * d.width * d.height);
        for (int m = 0; m < 2; ++m) {
            sky_view v = sky_view_default();
            v.mode = m ? SKY_CHOICE_SKYVIEW : SKY_CHOICE_MARCH;
            v.bloom = false;
            v.sun_elevation_deg = 3.0, v.pitch_deg = 5.0, v.fov_deg = 40.0;
            render(&r, &v, d.width, d.height, lum, NULL);
            double y_h = horizon_row(v.altitude_km, v.pitch_deg, v.fov_deg, d.height);
            int first_ground = (int)ceil(y_h), last_sky = (int)floor(y_h) - 1;
            for (int x = 0; x < d.width; x += 4) {
                double sky = lum[(size_t)last_sky * d.width + x];
                for (int y = first_ground; y < y_h + 2.0; ++y) {
                    double leak = lum[(size_t)y * d.width + x] / sky;
                    if (leak > worst) worst = leak;
                    CHECK(leak <= 0.05, "scale %g mode %d column %d row %d: ground %.3g of the sky above", d.scale,
                          v.mode, x, y, leak);
                }
            }
        }
        free(lum);
        sky_renderer_destroy(&r);
    }
    printf("leak: the brightest ground pixel within 2 px below the horizon is %.2f %% of the sky (bound 5 %%)\n",
           100.0 * worst);
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static void test_sweep(gpu_context *ctx)
{
    model_atmosphere earth;
    model_atmosphere_earth(&earth);
    sky_features f = sky_features_default();
    f.sun_disc = false;
    run_desc d = {64, 36, 1.0, SKY_PASS_FRAGMENT, POST_PASS_FRAGMENT, 0};
    sky_renderer r;
    renderer_open(&r, ctx, &d, &earth, &f);
    size_t n = (size_t)d.width * d.height;
    float *frames[2][2];
    for (int i = 0; i < 4; ++i) frames[i / 2][i % 2] = malloc(sizeof(float) * n);
    const int count = 201;   /* 5 km a frame: the blend moves 10 % a frame */
    double worst = 0.0, worst_h = 0.0, worst_p99 = 0.0;
    float *excess = malloc(sizeof(float) * n);
    for (int k = 0; k < count; ++k) {
        double h = 1000.0 * k / (count - 1);
        for (int m = 0; m < 2; ++m) {
            sky_view v = sky_view_default();
            v.mode = m ? SKY_CHOICE_AUTO : SKY_CHOICE_MARCH;
            v.bloom = false;
            v.altitude_km = h, v.pitch_deg = -10.0;
            render(&r, &v, d.width, d.height, frames[m][k & 1], NULL);
        }
        if (k == 0) continue;
        const float *a0 = frames[1][(k - 1) & 1], *a1 = frames[1][k & 1];
        const float *m0 = frames[0][(k - 1) & 1], *m1 = frames[0][k & 1];
        double peak = 0.0;
        for (size_t i = 0; i < n; ++i) peak = fmax(peak, a1[i]);
        for (size_t i = 0; i < n; ++i) {
            /* 1 % of the pixel; floored at 0.1 % of the frame's brightest (space is black). */
            double scale = fmax(fmax(a0[i], a1[i]), 1e-3 * peak);
            excess[i] = (float)((fabs(a1[i] - a0[i]) - fabs(m1[i] - m0[i])) / scale);
            if (excess[i] > worst) worst = excess[i], worst_h = h;
        }
        qsort(excess, n, sizeof *excess, cmp_float);
        worst_p99 = fmax(worst_p99, excess[(size_t)(0.99 * (double)(n - 1))]);
    }
    CHECK(worst <= 0.01, "auto's frame-to-frame change exceeds the march's by %.2f %% of the pixel at %g km",
          100 * worst, worst_h);
    printf("sweep: %d frames 0 -> 1000 km; auto's change exceeds the march's by at most %.3f %% of the pixel (at %g "
           "km; bound 1 %%; 99th percentile of a frame pair at most %.3f %%)\n", count, 100.0 * worst, worst_h,
           100.0 * worst_p99);
    free(excess);
    for (int i = 0; i < 4; ++i) free(frames[i / 2][i % 2]);
    sky_renderer_destroy(&r);
}

/* Narkowicz's ACES fit and the sRGB encoding, written here from their definitions. */
static double aces(double x)
{
    double y = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
    return y < 0.0 ? 0.0 : y > 1.0 ? 1.0 : y;
}
static double srgb(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055; }

static void test_dither(gpu_context *ctx)
{
    model_atmosphere earth;
    model_atmosphere_earth(&earth);
    sky_features f = sky_features_default();
    for (int post = 0; post < 2; ++post) {
        run_desc d = {160, 100, 1.0, SKY_PASS_FRAGMENT, post ? POST_PASS_COMPUTE : POST_PASS_FRAGMENT, 0};
        sky_renderer r;
        renderer_open(&r, ctx, &d, &earth, &f);
        size_t n = (size_t)d.width * d.height;
        unsigned char *on = malloc(4 * n), *again = malloc(4 * n), *off = malloc(4 * n);
        sky_view v = sky_view_default();
        v.bloom = false;
        v.sun_elevation_deg = -4.0, v.pitch_deg = 20.0;
        render(&r, &v, d.width, d.height, NULL, on);
        /* The exact display value of each pixel from the frame's own scene-linear pixels. */
        const uint16_t *half = r.readback_linear.mapped;
        double exposure = sky_view_tonemap_push(&v, true).params.x;
        double *exact = malloc(sizeof(double) * 3 * n);
        for (size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c)
                exact[3 * i + c] = 255.0 * srgb(aces(exposure * io_half_to_float(half[4 * i + c])));
        render(&r, &v, d.width, d.height, NULL, again);
        v.no_dither = true;
        render(&r, &v, d.width, d.height, NULL, off);
        /* The region: the sky's smooth gradient above the horizon (rows 5 .. 55 of 100 here; the horizon is
         * near row 74), away from 0 and 255. */
        double sum_on = 0.0, sum_off = 0.0, sum_exact = 0.0;
        size_t same_on = 0, same_off = 0, pairs = 0, count = 0;
        int worst_step = 0;
        for (int y = 5; y < 55; ++y)
            for (int x = 0; x < d.width; ++x) {
                size_t i = (size_t)y * d.width + x;
                for (int c = 0; c < 3; ++c) {
                    sum_on += on[4 * i + c], sum_off += off[4 * i + c], sum_exact += exact[3 * i + c], ++count;
                    int step = abs((int)on[4 * i + c] - (int)off[4 * i + c]);
                    if (step > worst_step) worst_step = step;
                }
                if (x + 1 < d.width) {
                    same_on += !memcmp(on + 4 * i, on + 4 * i + 4, 3);
                    same_off += !memcmp(off + 4 * i, off + 4 * i + 4, 3);
                    ++pairs;
                }
            }
        double mean_err = (sum_on - sum_exact) / (double)count, mean_err_off = (sum_off - sum_exact) / (double)count;
        double share_on = (double)same_on / pairs, share_off = (double)same_off / pairs;
        CHECK(fabs(mean_err) <= 0.1, "post %d: the dithered mean is %.3f LSB from the exact", post, mean_err);
        CHECK(worst_step <= 1, "post %d: a dithered pixel %d LSB from the undithered", post, worst_step);
        CHECK(share_on < 0.6, "post %d: %.1f %% identical neighbours with the dither", post, 100 * share_on);
        CHECK(!memcmp(on, again, 4 * n), "post %d: two renders of one view differ", post);
        printf("dither (%s tone map): mean %+.3f LSB from the exact (undithered %+.3f), at most %d LSB from the "
               "undithered, identical neighbours %.1f %% (undithered %.1f %%), two renders identical: %s\n",
               post ? "compute" : "fragment", mean_err, mean_err_off, worst_step, 100 * share_on, 100 * share_off,
               memcmp(on, again, 4 * n) ? "no" : "yes");
        free(on), free(again), free(off), free(exact);
        sky_renderer_destroy(&r);
    }
}

int main(int argc, char **argv)
{
    gpu_context ctx;
    test_context(&ctx);
    const char *only = argc > 1 ? argv[1] : "";
    if (!*only || !strcmp(only, "position")) test_position(&ctx);
    if (!*only || !strcmp(only, "presets")) test_presets(&ctx);
    if (!*only || !strcmp(only, "leak")) test_leak(&ctx);
    if (!*only || !strcmp(only, "sweep")) test_sweep(&ctx);
    if (!*only || !strcmp(only, "dither")) test_dither(&ctx);
    gpu_context_destroy(&ctx);
    if (check_failures) fprintf(stderr, "test_horizon: %d failure(s)\n", check_failures);
    else printf("test_horizon: all checks pass\n");
    return check_failures ? 1 : 0;
}
