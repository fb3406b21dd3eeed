/* The spectral groups summed on the GPU (ABI 4, issue 32: vksky_spectral_sum, vksky_frame_spectral_sum) against the
 * same groups read back and summed here, in double: every group renderer's frame read back (its linear RGBA16F, the
 * half floats decoded by this file's own decoder), times vksky_scene_spectral_group's weights, summed, turned into
 * Rec.709 by vksky_spectral_xyz_to_rec709. The GPU's float32 sum must equal that within float rounding: per pixel,
 * the largest channel difference relative to the pixel's largest channel below 1e-5 (float32's epsilon is 6e-8; up to
 * 16 groups of four products and a matrix with coefficients up to 3.2); alpha the last group's composite alpha (three
 * wavelengths a pass) or 1 (four). The groups in one command buffer (a renderer each) and one submission per group
 * (one renderer, each group's scene in turn); a second frame with the sun moved (the sum starts again from 0); the
 * refusals. Validation and synchronization validation on: any message fails. */
#include <vksky.h>
#include "api_host.h"
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

enum { W = 40, H = 23, MAX_GROUPS = 17 };

static double half_to_double(uint16_t h)
{
    int e = (h >> 10) & 31, m = h & 1023;
    double v = e == 0 ? ldexp(m, -24) : e == 31 ? INFINITY : ldexp(m + 1024, e - 25);
    return h & 0x8000 ? -v : v;
}

static void submit(host *h)
{
    host_end_submit_wait(h);
}

static void frame_of(vksky_renderer *r, VkCommandBuffer cmd, const vksky_frame_view *view,
                     const vksky_frame_spectral_sum *sum)
{
    vksky_frame f = {.next = sum ? (const void *)sum : (const void *)view, .exposure = 0.0};
    vksky_result res = vksky_record(r, cmd, &f);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_record: %s", vksky_result_name(res));
}

/* One case: `wavelengths`, `per_pass` a pass, the sun at `elevation` (a second frame at elevation + 3). */
static void check_case(vksky_context *c, host *h, uint32_t wavelengths, uint32_t per_pass, double pitch,
                       double elevation, bool one_renderer)
{
    char sun[32];
    snprintf(sun, sizeof sun, "%g", elevation);
    char *argv[] = {"vksky", "--sun-elevation", sun, "--ground-albedo", "0.3,0.25,0.2", "--quality", "low",
                    "--no-bloom"};
    vksky_scene *scene = host_scene_of_args(8, argv);
    uint32_t groups = vksky_spectral_group_count(wavelengths, per_pass);
    vksky_scene *gs[MAX_GROUPS] = {0};
    vksky_renderer *r[MAX_GROUPS] = {0};
    double w[MAX_GROUPS][4][3];
    vksky_readback_config rb = {.type = VKSKY_STRUCTURE_TYPE_READBACK_CONFIG};
    vksky_spectral_sum *sum = NULL;
    HOST_CHECK(vksky_spectral_sum_create(c, W, H, &sum) == VKSKY_SUCCESS && sum, "vksky_spectral_sum_create");
    if (!sum) return;
    vksky_frame_view view = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .yaw_deg = 0.0, .pitch_deg = pitch,
                             .fov_deg = 70.0};
    double worst = 0.0;
    for (int frame = 0; frame < 2; ++frame) {
        if (frame == 1) vksky_scene_set_sun(scene, 0.0, elevation + 3.0);
        for (uint32_t g = 0; g < groups; ++g) {
            vksky_scene_destroy(gs[g]);
            gs[g] = NULL;
            HOST_CHECK(vksky_scene_spectral_group(scene, wavelengths, per_pass, g, &gs[g], w[g], NULL) == VKSKY_SUCCESS,
                       "group %u", g);
            if (one_renderer && g > 0) continue;
            if (!r[g]) {
                vksky_renderer_desc d = host_readback_desc(&rb, gs[g], W, H, false);
                r[g] = host_renderer(c, &d);
            } else {
                HOST_CHECK(vksky_renderer_set_scene(r[g], gs[g]) == VKSKY_SUCCESS, "set_scene");
            }
        }
        /* The host's sum: each group's readback, in double. */
        static double xyz[W * H][3];
        static double alpha[W * H];
        memset(xyz, 0, sizeof xyz);
        for (uint32_t g = 0; g < groups; ++g) {
            vksky_renderer *rg = one_renderer ? r[0] : r[g];
            if (one_renderer) HOST_CHECK(vksky_renderer_set_scene(rg, gs[g]) == VKSKY_SUCCESS, "set_scene");
            host_begin(h);
            frame_of(rg, h->cmd, &view, NULL);
            submit(h);
            vksky_readback px;
            HOST_CHECK(vksky_renderer_get_readback(rg, &px) == VKSKY_SUCCESS, "readback");
            for (size_t i = 0; i < (size_t)W * H; ++i) {
                for (uint32_t ch = 0; ch < 4; ++ch)
                    for (int q = 0; q < 3; ++q) xyz[i][q] += w[g][ch][q] * half_to_double(px.linear_rgba16f[4 * i + ch]);
                alpha[i] = per_pass == 3 ? half_to_double(px.linear_rgba16f[4 * i + 3]) : 1.0;
            }
        }
        /* The GPU's sum: all groups in one command buffer (a renderer each), or a submission per group. */
        if (!one_renderer) host_begin(h);
        for (uint32_t g = 0; g < groups; ++g) {
            vksky_frame_spectral_sum step = {.type = VKSKY_STRUCTURE_TYPE_FRAME_SPECTRAL_SUM, .next = &view, .sum = sum,
                                             .group = g, .first = g == 0, .last = g + 1 == groups};
            memcpy(step.xyz_weights, w[g], sizeof step.xyz_weights);
            if (one_renderer) {
                HOST_CHECK(vksky_renderer_set_scene(r[0], gs[g]) == VKSKY_SUCCESS, "set_scene");
                host_begin(h);
            }
            frame_of(one_renderer ? r[0] : r[g], h->cmd, &view, &step);
            if (one_renderer) submit(h);
        }
        if (!one_renderer) submit(h);
        const float *gpu = NULL;
        HOST_CHECK(vksky_spectral_sum_get(sum, &gpu) == VKSKY_SUCCESS && gpu, "vksky_spectral_sum_get");
        if (!gpu) break;
        double brightest = 0.0;
        int alpha_bad = 0;
        for (size_t i = 0; i < (size_t)W * H; ++i) {
            double rgb[3], big = 0.0, diff = 0.0;
            vksky_spectral_xyz_to_rec709(xyz[i], rgb);
            for (int q = 0; q < 3; ++q) big = fmax(big, fabs(rgb[q])), diff = fmax(diff, fabs(gpu[4 * i + q] - rgb[q]));
            brightest = fmax(brightest, big);
            if (big > 0.0) worst = fmax(worst, diff / big);
            alpha_bad += gpu[4 * i + 3] != (float)alpha[i];
        }
        HOST_CHECK(brightest > 0.01, "no sky: the brightest channel %g", brightest);
        HOST_CHECK(alpha_bad == 0, "%d pixels' alpha differ from the last group's composite", alpha_bad);
    }
    HOST_CHECK(worst < 1e-5, "%u wavelengths %u a pass: the GPU's sum differs from the host's by %.3g relative", wavelengths,
               per_pass, worst);
    printf("api_spectral_sum: %u wavelengths, %u a pass, %s: max relative difference per pixel %.3g (float32 sum "
           "against double)\n", wavelengths, per_pass, one_renderer ? "a submission per group" : "one command buffer",
           worst);
    for (uint32_t g = 0; g < groups; ++g) vksky_renderer_destroy(r[g]), vksky_scene_destroy(gs[g]);
    vksky_spectral_sum_destroy(sum);
    vksky_scene_destroy(scene);
}

static void check_refusals(vksky_context *c, host *h)
{
    vksky_spectral_sum *sum = NULL, *other = NULL;
    HOST_CHECK(vksky_spectral_sum_create(c, 0, H, &sum) == VKSKY_ERROR_INVALID_ARGUMENT && !sum, "0 wide accepted");
    HOST_CHECK(vksky_spectral_sum_create(c, W, H, &sum) == VKSKY_SUCCESS, "create");
    HOST_CHECK(vksky_spectral_sum_create(c, W + 1, H, &other) == VKSKY_SUCCESS, "create");
    vksky_scene *earth = NULL, *g0 = NULL;
    vksky_scene_create_earth(&earth);
    double w[4][3];
    vksky_scene_spectral_group(earth, 8, 3, 0, &g0, w, NULL);
    vksky_readback_config rb = {.type = VKSKY_STRUCTURE_TYPE_READBACK_CONFIG};
    vksky_renderer_desc d = host_readback_desc(&rb, earth, W, H, false);
    d.quality = "low";   /* not a command line's scene */
    vksky_renderer *rgb = host_renderer(c, &d);
    d.scene = g0;
    vksky_renderer *grp = host_renderer(c, &d);
    vksky_frame_view view = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .pitch_deg = 10.0, .fov_deg = 60.0};
    vksky_frame_spectral_sum step = {.type = VKSKY_STRUCTURE_TYPE_FRAME_SPECTRAL_SUM, .next = &view, .sum = sum,
                                     .first = true, .last = true};
    unsigned before = api_messages[VKSKY_SEVERITY_ERROR];
    host_begin(h);
    vksky_frame f = {.next = &step};
    HOST_CHECK(vksky_record(rgb, h->cmd, &f) == VKSKY_ERROR_INVALID_ARGUMENT, "an RGB renderer's frame summed");
    step.sum = other;
    HOST_CHECK(vksky_record(grp, h->cmd, &f) == VKSKY_ERROR_INVALID_ARGUMENT, "a sum of another size accepted");
    step.sum = sum, step.group = VKSKY_SPECTRAL_SUM_GROUPS_MAX;
    HOST_CHECK(vksky_record(grp, h->cmd, &f) == VKSKY_ERROR_INVALID_ARGUMENT, "group 17 accepted");
    step.group = 0, step.xyz_weights[1][2] = NAN;
    HOST_CHECK(vksky_record(grp, h->cmd, &f) == VKSKY_ERROR_INVALID_ARGUMENT, "a NaN weight accepted");
    HOST_CHECK(api_messages[VKSKY_SEVERITY_ERROR] == before + 4, "%u error messages for 4 refusals",
               api_messages[VKSKY_SEVERITY_ERROR] - before);
    HOST_VK(vkEndCommandBuffer(h->cmd));   /* nothing recorded: not submitted */
    vksky_renderer_destroy(rgb), vksky_renderer_destroy(grp);
    vksky_spectral_sum_destroy(sum), vksky_spectral_sum_destroy(other);
    vksky_scene_destroy(g0), vksky_scene_destroy(earth);
}

int main(void)
{
    HOST_CHECK(vksky_abi_version() == VKSKY_ABI_VERSION && VKSKY_ABI_VERSION >= 4u, "ABI %u", vksky_abi_version());
    vksky_context *c = host_own_context();
    host h;
    host_from_context(&h, c);
    host_create_target(&h, W, H, VK_FORMAT_R8G8B8A8_SRGB);   /* its command buffer and fence */
    check_case(c, &h, 8, 3, 0.0, 2.0, false);    /* a sunset, the horizon across the frame: alpha the coverage */
    check_case(c, &h, 24, 4, 25.0, -3.0, false); /* twilight, four a pass */
    check_case(c, &h, 12, 3, 10.0, 30.0, true);  /* one renderer, a submission per group */
    check_refusals(c, &h);
    host_destroy_target(&h);
    HOST_CHECK(vksky_context_validation_message_count(c) == 0, "%u validation messages",
               vksky_context_validation_message_count(c));
    vksky_context_destroy(c);
    if (host_failures) fprintf(stderr, "api_spectral_sum: %d failures\n", host_failures);
    else printf("api_spectral_sum: ok\n");
    return host_failures ? 1 : 0;
}
