/* The points of the aerial-perspective tests (test_aerial: the march, test_ap_volume: the froxel volume) and the
 * frame that puts them through the composite pass exactly as `vksky --composite` runs it. Included by each test
 * (static: one test executable each). */
#ifndef VKSKY_TESTS_AERIAL_POINTS_H
#define VKSKY_TESTS_AERIAL_POINTS_H
#include "gpu_test.h"
#include "gpu/pipeline_cache.h"
#include "sky/composite.h"

typedef struct point_case {
    const char *what;
    double view_az, view_el;   /* view direction (deg, vksky's convention: local frame, up = +Y) */
    double d_km;
} point_case;

typedef struct group {
    double altitude_km, sun_az, sun_el;
    const point_case *points;
    int count;
} group;

typedef struct result { float T[3], R[3], M[3], composite[4]; } result;

static const float BEAUTY[3] = {0.3f, 0.5f, 0.7f};

/* One composite frame (width = number of points, height 1): camera straight above the world origin in a Y-up,
 * metre world, each pixel's position d km along its view direction. */
static void run_group(test_renderer *t, const group *g, composite_view base, const ap_volume_desc *volume,
                      result *out)
{
    sky_composite c;
    char err[256];
    int rc = sky_composite_create(&c, &t->r, (uint32_t)g->count, 1, volume, err, sizeof err);
    CHECK(rc == 0, "composite create: %s", err);
    if (rc) return;
    composite_view v = base;
    /* The camera straight above the origin; vksky's local (north, up, east) is (y, z, x) in a Z-up world and
     * (-z, y, x) in a Y-up one (docs/aerial_perspective.md "Conventions"). */
    double unit = 1.0 / base.km_per_unit;
    v.camera[0] = v.camera[1] = v.camera[2] = 0.0;
    v.camera[base.up_axis] = g->altitude_km * unit;
    v.sun_azimuth_deg = g->sun_az, v.sun_elevation_deg = g->sun_el;
    float *in = sky_composite_inputs(&c);
    for (int i = 0; i < g->count; ++i) {
        double dir[3];
        ref_dir(g->points[i].view_az * TEST_DEG, g->points[i].view_el * TEST_DEG, dir);
        float *beauty = in + 4 * i, *pos = in + 4 * (g->count + i);
        beauty[0] = BEAUTY[0], beauty[1] = BEAUTY[1], beauty[2] = BEAUTY[2], beauty[3] = 1.0f;
        double w[3] = {dir[2], dir[1], -dir[0]};
        if (base.up_axis == 2) w[0] = dir[2], w[1] = dir[0], w[2] = dir[1];
        for (int k = 0; k < 3; ++k) pos[k] = (float)(v.camera[k] + w[k] * g->points[i].d_km * unit);
        pos[3] = 1.0f;
    }
    CompositePush push;
    /* The volume's froxels cover the camera's frustum, whose aspect is the image's: give it seed 004's 960x540
     * frame rather than this one-row strip (the points are all geometry: the pixel grid is not used). */
    uint32_t fw = volume ? 960 : (uint32_t)g->count, fh = volume ? 540 : 1;
    double h = composite_push(&v, t->r.medium.bottom_radius, fw, fh, &push);
    CHECK(fabs(h - g->altitude_km) < 1e-9, "camera altitude %.12f km, expected %.12f", h, g->altitude_km);
    /* As vksky --composite runs it: without a --max-steps (the default settings' view), its fast defaults (issue 28
     * item 6: a segment's steps by its length; the sky tiles do not apply to this strip). */
    composite_push_fast(&v, &push);
    sky_composite_render(&t->r, &c, &push, 1);
    for (int i = 0; i < g->count; ++i) {
        memcpy(out[i].T, sky_composite_layer(&c, VKSKY_AOV_TRANSMITTANCE) + 4 * i, sizeof out[i].T);
        memcpy(out[i].R, sky_composite_layer(&c, VKSKY_AOV_RAYLEIGH) + 4 * i, sizeof out[i].R);
        memcpy(out[i].M, sky_composite_layer(&c, VKSKY_AOV_MIE) + 4 * i, sizeof out[i].M);
        memcpy(out[i].composite, sky_composite_layer(&c, VKSKY_AOV_COMPOSITE) + 4 * i, sizeof out[i].composite);
    }
    sky_composite_destroy(&c, &t->r);
}

/* The seed's camera 218.8 m up, sun 30 deg; then from 10 km; then at sunset. */
static const point_case seed_points[] = {
    {"distance 0", 90, 0, 0.0},       {"near 200 m", 90, 0, 0.2},      {"1 km", 90, 0, 1.0},
    {"5 km", 90, 0, 5.0},             {"10 km", 90, 0, 10.0},          {"20 km", 90, 0, 20.0},
    {"above, 30 deg up, 5 km", 120, 30, 5.0},   {"below, 1 deg down, 10 km", 200, -1, 10.0},
    {"grazing 0.1 deg, 20 km", 250, 0.1, 20.0}, {"toward the sun, 3 km", 0, 28, 3.0},
    {"steep down, 150 m", 45, -60, 0.15}};
static const point_case high_points[] = {
    {"10 km: down 30 deg, 15 km", 30, -30, 15.0}, {"10 km: horizontal 50 km", 100, 0, 50.0},
    {"10 km: up 20 deg, 20 km", 270, 20, 20.0},   {"10 km: nadir 9.9 km", 0, -90, 9.9}};
static const point_case sunset_points[] = {
    {"sunset: toward the sun, 10 km", 90, 0, 10.0}, {"sunset: away, 10 km", 270, 0, 10.0},
    {"sunset: 1 km", 0, 0, 1.0},                   {"sunset: up 45, 10 km", 180, 45, 10.0},
    {"sunset: ground 3 deg down", 90, -3, 4.0}};
static const group groups[] = {{0.2188, 0.0, 30.0, seed_points, 11}, {10.0, 180.0, 45.0, high_points, 4},
                        {0.2188, 90.0, 0.5, sunset_points, 5}};

static double rel(double gpu, double ref, double floor) { return fabs(gpu - ref) / fmax(fabs(ref), floor); }
/* Converged LUTs. The multi-scattering LUT is test_sky's converged one refined further (64^2 texels, 64^2
 * directions; 18 s on lavapipe): with 32^2 texels and 32^2 directions the Psi it holds is ~2 % off near the ground,
 * and Psi is most of the Mie layer away from the sun (S: 0.9 %, mie: 2.7 %; here S <= 1.6 %, mie <= 2.1 %; 128^2
 * texels and 128 steps: S <= 0.6 %, but 4 minutes). */
static sky_lut_quality aerial_converged_luts(void)
{
    sky_lut_quality converged = sky_lut_quality_default();
    converged.lut_f32 = true;
    converged.multiscatter_sqrt_dirs = 64;
    converged.multiscatter_steps = 64;
    converged.multiscatter_size = 64;
    return converged;
}

/* The Vulkan context (validation on), Hillaire's Earth, a renderer with the converged LUTs; and the composite
 * view of the tests: a Y-up world in metres, a converged march of `steps` (quadratic spacing), field of view fov.
 * VKSKY_TEST_LUT_DIR: the LUT cache directory the ctest fixture aerial_luts filled (tests/aerial_luts.c), which
 * test_aerial and ap_volume read with VKSKY_LUT_CACHE=ro: the converged LUTs (most of each test's CPU on
 * lavapipe) are computed once for both, and uploaded byte for byte (the LUT cache's contract, ctest lut_cache).
 * Without it (the binary run by hand) the test computes them itself. */
static void aerial_setup(gpu_context *ctx, model_atmosphere *earth, test_renderer *t)
{
    test_context(ctx);
    const char *lut_dir = getenv("VKSKY_TEST_LUT_DIR");
    if (lut_dir && lut_dir[0]) CHECK(gpu_cache_dir_attach(ctx, lut_dir), "LUT cache directory %s", lut_dir);
    model_atmosphere_earth(earth);
    sky_lut_quality converged = aerial_converged_luts();
    test_renderer_create(t, ctx, 9, 9, false, &converged, NULL);
}
/* With the fixture's directory: the converged LUTs came from it (the key matched), not computed a second time. */
static void aerial_check_shared_luts(const test_renderer *t)
{
    const char *lut_dir = getenv("VKSKY_TEST_LUT_DIR");
    if (lut_dir && lut_dir[0])
        CHECK(t->r.lut_cache == SKY_LUT_CACHE_HIT, "the converged LUTs were not read from %s (LUT cache state %d)",
              lut_dir, (int)t->r.lut_cache);
}
static void aerial_teardown(gpu_context *ctx, test_renderer *t)
{
    test_renderer_destroy(t);
    gpu_cache_dir_attach(ctx, NULL);
    gpu_context_destroy(ctx);
}
static composite_view aerial_view(double fov_y_deg, int steps)
{
    return (composite_view){.km_per_unit = 0.001, .up_axis = 1, .fov_y_deg = fov_y_deg, .steps = steps,
                            .max_steps = steps, .steps_ramp_km = 100.0, .sample_offset = 0.5, .step_distribution = 2.0};
}
#endif
