/* The SCENE_LINEAR pass (src/sky/host_frame.c) in a frame a host owns, checked against independent computations, and
 * the frame the drop tests of its barriers run (tests/barrier_drops.txt, config host_frame).
 *
 * A "host" (this program) owns an RGBA16F colour image and a D32 depth buffer. Each frame it uploads its geometry
 * (a copy: the top rows sky, depth at the far plane; the bottom rows flat colour at 2 km and at 15 km along the view
 * axis), vksky records the pass, the host copies the colour image back. Two frames in one command buffer (colours
 * A then B, the same depth) put the cross-frame hazards inside what synchronization validation sees. Checks:
 *  - sky pixels equal the sky pass's frame of the same camera (vksky's own renderer; the matrices built here from the CLI's conventions),
 *    every pixel of the sky half: within 2e-3 relative (fp16 storage twice and float rounding of two ray matrices);
 *  - per geometry pixel, T = (out_A - out_B) / (A - B) and S = out_A - A T (A = 1, B = 0: T = out_A - out_B, S = out_B) against the CPU reference's
 *    transmittance and in-scattering along the camera -> point segment (ref_radiance_to_point, converged): T within
 *    2e-3 absolute (two fp16 roundings near 1: < 1e-3, plus the 64-step march; measured 9.6e-4), S within 5 % (the
 *    default LUTs and a 64-step march, measured 3.9 %; test_aerial reaches 2 % with converged LUTs and 256 steps);
 *  - the far block is hazier than the near one: larger S, smaller T;
 *  - a standard-depth projection with a finite far plane gives the same S (within 1 %), and without a depth image
 *    every pixel is the sky pass's (within 2e-3).
 * `--validate` and `--trace-barriers` as vksky; VKSKY_DROP_BARRIER / VKSKY_WEAKEN_BARRIER apply. The checks against
 * the reference run with `--check` (ctest host_frame; the drop runs only need the frame). Exit 1 on a failed check or
 * any validation message. */
#include "gpu_test.h"
#include "sky/host_frame.h"

enum { W = 48, H = 32 };
static const double NEAR_M = 0.5, NEAR_BLOCK_M = 2000.0, FAR_BLOCK_M = 15000.0, ALT_M = 200.0;
/* B = 0: out_B is S itself (fp16 relative 2^-11); A = 1: T = out_A - out_B, two fp16 roundings near 1 (< 1e-3). */
static const float COLOR_A = 1.0f, COLOR_B = 0.0f;

static uint32_t memory_type(const gpu_context *ctx, uint32_t bits)
{
    for (uint32_t i = 0; i < ctx->memory.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (ctx->memory.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT))
            return i;
    return 0;
}

/* An image of the host's own making (its view's aspect its own). */
static void host_image_create(const gpu_context *ctx, host_image *img, VkDeviceMemory *mem, VkFormat format,
                              VkImageUsageFlags usage, VkImageAspectFlags aspect)
{
    VkImageCreateInfo info = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                              .format = format, .extent = {W, H, 1}, .mipLevels = 1, .arrayLayers = 1,
                              .samples = VK_SAMPLE_COUNT_1_BIT, .tiling = VK_IMAGE_TILING_OPTIMAL, .usage = usage};
    VK_CHECK(vkCreateImage(ctx->device, &info, NULL, &img->image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx->device, img->image, &req);
    VkMemoryAllocateInfo alloc = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                                  .memoryTypeIndex = memory_type(ctx, req.memoryTypeBits)};
    VK_CHECK(vkAllocateMemory(ctx->device, &alloc, NULL, mem));
    VK_CHECK(vkBindImageMemory(ctx->device, img->image, *mem, 0));
    VkImageViewCreateInfo vinfo = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = img->image,
                                   .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
                                   .subresourceRange = {aspect, 0, 1, 0, 1}};
    VK_CHECK(vkCreateImageView(ctx->device, &vinfo, NULL, &img->view));
    img->format = format;
    img->extent = (VkExtent2D){W, H};
}

/* The matrices of vksky's command-line camera, written here from its conventions (sky_view_basis: yaw 0 north, -Z
 * in a Y-up world; 90 east, +X): view rows right, up, -forward; Vulkan clip space, reversed depth, far at infinity. */
static void camera_look(host_camera *c, double yaw_deg, double pitch_deg, double fov_y_deg, double aspect,
                        double near_m)
{
    memset(c, 0, sizeof *c);
    /* The CLI's view axis (sky_view_basis: local north, up, east) in the world's axes: north -Z, east +X. */
    double y = yaw_deg * TEST_DEG, p = pitch_deg * TEST_DEG;
    double f[3] = {cos(p) * sin(y), sin(p), -cos(p) * cos(y)}, r[3], u[3];
    if (fabs(pitch_deg) >= 90.0 - 1e-9) {
        r[0] = cos(y), r[1] = 0.0, r[2] = sin(y);   /* local dir(yaw + 90, 0), as sky_view_basis */
    } else {
        r[0] = -f[2], r[1] = 0.0, r[2] = f[0];      /* f x +Y */
        double n = sqrt(r[0] * r[0] + r[2] * r[2]);
        r[0] /= n, r[2] /= n;
    }
    u[0] = r[1] * f[2] - r[2] * f[1], u[1] = r[2] * f[0] - r[0] * f[2], u[2] = r[0] * f[1] - r[1] * f[0];
    /* world -> eye: rows right, up, -forward (the eye looks down -Z); the camera at the world origin. */
    for (int j = 0; j < 3; ++j) {
        c->view[j * 4 + 0] = r[j];
        c->view[j * 4 + 1] = u[j];
        c->view[j * 4 + 2] = -f[j];
    }
    c->view[15] = 1.0;
    /* Vulkan clip space (y down), reversed depth with the far plane at infinity: depth = near / distance. */
    double t = tan(0.5 * fov_y_deg * TEST_DEG);
    c->projection[0] = 1.0 / (t * aspect);
    c->projection[5] = -1.0 / t;
    c->projection[11] = -1.0;
    c->projection[14] = near_m;
}

/* The host's own barrier (not vksky's: untraced, not drop-tested). */
static void host_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkPipelineStageFlags2 ss,
                         VkAccessFlags2 sa, VkImageLayout from, VkPipelineStageFlags2 ds, VkAccessFlags2 da,
                         VkImageLayout to)
{
    VkImageMemoryBarrier2 b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, .srcStageMask = ss,
                               .srcAccessMask = sa, .dstStageMask = ds, .dstAccessMask = da, .oldLayout = from,
                               .newLayout = to, .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                               .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .image = image,
                               .subresourceRange = {aspect, 0, 1, 0, 1}};
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .imageMemoryBarrierCount = 1,
                            .pImageMemoryBarriers = &b};
    vkCmdPipelineBarrier2(cmd, &dep);
}

/* Row y is sky (the top half), else a block: the left half of the columns at 2 km, the right half at 15 km. */
static double block_distance_m(int x, int y) { return y < H / 2 ? 0.0 : x < W / 2 ? NEAR_BLOCK_M : FAR_BLOCK_M; }

static double rel(double a, double b) { return fabs(a - b) / fmax(fabs(b), 1e-9); }

int main(int argc, char **argv)
{
    bool trace = false, check = false;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--trace-barriers")) trace = true;
        else if (!strcmp(argv[i], "--check")) check = true;
        else if (strcmp(argv[i], "--validate") != 0) {
            fprintf(stderr, "host_frame_probe: unknown option '%s' (accepted: --validate, --trace-barriers, --check)\n",
                    argv[i]);
            return 2;
        }
    }
    char why[200];
    if (!gpu_barrier_set_weaken(getenv("VKSKY_WEAKEN_BARRIER"), why, sizeof why)) {
        fprintf(stderr, "host_frame_probe: VKSKY_WEAKEN_BARRIER: %s\n", why);
        return 2;
    }
    gpu_barrier_set_drop(getenv("VKSKY_DROP_BARRIER"));
    gpu_context ctx;
    test_context(&ctx);
    model_atmosphere earth;
    model_atmosphere_earth(&earth);

    /* The view: 200 m up, looking north 35 degrees up (the whole image above the horizon: the blocks float in the
     * air, every segment ends at its point), the sun behind the camera's right shoulder. */
    sky_view view = sky_view_default();
    view.altitude_km = ALT_M * 1e-3, view.yaw_deg = 0.0, view.pitch_deg = 35.0, view.fov_deg = 60.0;
    view.sun_azimuth_deg = 135.0, view.sun_elevation_deg = 25.0, view.steps = 64, view.bloom = false;
    test_renderer t;
    test_renderer_create(&t, &ctx, W, H, false, NULL, NULL);
    test_frame sky = test_renderer_frame(&t, &view);   /* the sky pass's frame (and the LUTs) */
    if (trace) gpu_barrier_trace(stdout);

    host_frame hf;
    char err[256];
    if (host_frame_create(&hf, &t.r, VK_FORMAT_R16G16B16A16_SFLOAT, err, sizeof err) != 0) {
        fprintf(stderr, "host_frame_probe: %s\n", err);
        return 1;
    }
    host_camera cam;
    camera_look(&cam, view.yaw_deg, view.pitch_deg, view.fov_deg, (double)W / H, NEAR_M);
    cam.origin_altitude_m = ALT_M;
    HostFramePush push;
    if (host_frame_push(&cam, &view, earth.bottom_radius, earth.top_radius - earth.bottom_radius, W, H, true, &push,
                        err, sizeof err) != 0) {
        fprintf(stderr, "host_frame_probe: %s\n", err);
        return 1;
    }

    /* The host's images and its geometry: colours A and B, reversed depth near / (distance along the axis). */
    host_image color = {0}, depth = {0};
    VkDeviceMemory color_mem, depth_mem;
    host_image_create(&ctx, &color, &color_mem, VK_FORMAT_R16G16B16A16_SFLOAT,
                      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                      VK_IMAGE_ASPECT_COLOR_BIT);
    host_image_create(&ctx, &depth, &depth_mem, VK_FORMAT_D32_SFLOAT,
                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    gpu_buffer upload[2], depth_upload, readback[2];
    for (int k = 0; k < 2; ++k) {
        gpu_buffer_create(&ctx, &upload[k], "host colour upload", W * H * 8, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
        gpu_buffer_create(&ctx, &readback[k], "host colour readback", W * H * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        uint16_t *px = upload[k].mapped;
        for (int i = 0; i < W * H * 4; ++i) px[i] = io_float_to_half((i % 4 == 3) ? 1.0f : k == 0 ? COLOR_A : COLOR_B);
    }
    gpu_buffer_create(&ctx, &depth_upload, "host depth upload", W * H * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    float *dp = depth_upload.mapped;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) dp[y * W + x] = y < H / 2 ? 0.0f : (float)(NEAR_M / block_distance_m(x, y));

    /* The host's uses around vksky's: its upload (a copy) before, its readback copy after; the depth's next use is
     * the next frame's upload. */
    color.before = (gpu_usage_info){"host_upload", VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
    color.after = (gpu_usage_info){"host_readback", VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
    depth.before = color.before;
    depth.after = color.before;
    VkCommandBuffer cmd = gpu_begin_commands(&ctx);
    VkBufferImageCopy cc = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {W, H, 1}};
    VkBufferImageCopy dc = {.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1}, .imageExtent = {W, H, 1}};
    for (int k = 0; k < 2; ++k) {
        /* The host's first frame starts from nothing; its second from its readback (colour) and vksky's hand-back
         * (depth, already TRANSFER_DST: host.depth.to_after). */
        host_barrier(cmd, color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, 0,
                     k == 0 ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        if (k == 0)
            host_barrier(cmd, depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_PIPELINE_STAGE_2_NONE, 0,
                         VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        /* The host's passes are labelled (the trace shows them between vksky's barrier points). */
        gpu_label_begin(&ctx, cmd, "host_geometry");
        vkCmdCopyBufferToImage(cmd, upload[k].buffer, color.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &cc);
        vkCmdCopyBufferToImage(cmd, depth_upload.buffer, depth.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &dc);
        gpu_label_end(&ctx, cmd);
        /* The second frame rebuilds the LUTs: their rewrite must wait for the first frame's pass (WAR). */
        host_frame_desc f = {.color = &color, .depth = &depth, .push = &push, .force_luts = k == 1};
        host_frame_record(&t.r, &hf, cmd, &f);
        gpu_label_begin(&ctx, cmd, "host_readback");
        vkCmdCopyImageToBuffer(cmd, color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback[k].buffer, 1, &cc);
        gpu_label_end(&ctx, cmd);
    }
    VkBufferMemoryBarrier2 to_host[2];
    for (int k = 0; k < 2; ++k)
        to_host[k] = (VkBufferMemoryBarrier2){.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
                                              .srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT,
                                              .srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                              .dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT,
                                              .dstAccessMask = VK_ACCESS_2_HOST_READ_BIT,
                                              .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                              .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                              .buffer = readback[k].buffer, .size = VK_WHOLE_SIZE};
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .bufferMemoryBarrierCount = 2,
                            .pBufferMemoryBarriers = to_host};
    vkCmdPipelineBarrier2(cmd, &dep);
    gpu_submit_and_wait(&ctx, cmd);
    gpu_barrier_trace(NULL);
    for (int k = 0; k < 2; ++k) gpu_buffer_invalidate(&ctx, &readback[k]);

    /* The checks. */
    const uint16_t *oa = readback[0].mapped, *ob = readback[1].mapped;
    double sun[3];
    ref_dir(view.sun_azimuth_deg * TEST_DEG, view.sun_elevation_deg * TEST_DEG, sun);
    int sky_checked = 0, geo_checked = 0;
    double worst_sky = 0.0, worst_T = 0.0, worst_S = 0.0, S_near = 0.0, S_far = 0.0, T_near = 0.0, T_far = 0.0;
    ref_quality q = ref_quality_converged();
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            size_t i = 4 * ((size_t)y * W + x);
            if (y < H / 2) {
                const float *s = test_pixel(&sky, x, y);
                for (int c = 0; c < 3; ++c) {
                    double e = rel(io_half_to_float(oa[i + c]), s[c]);
                    worst_sky = fmax(worst_sky, e);
                    CHECK(e <= 2e-3, "sky pixel (%d, %d) channel %d: %g, the sky pass %g", x, y, c,
                          io_half_to_float(oa[i + c]), s[c]);
                    /* The sky does not depend on the host's colour. */
                    CHECK(oa[i + c] == ob[i + c], "sky pixel (%d, %d) depends on the host's colour", x, y);
                }
                ++sky_checked;
                continue;
            }
            /* The reference costs ~10 ms a point: every other row and column (192 points, the two probed ones among them). */
            if (!check || x % 2 != 0 || y % 2 == 0) continue;
            /* The point: distance along the axis / the cosine of the pixel's ray with the axis. */
            double v[3];
            ref_pixel_dir(x, y, W, H, view.yaw_deg * TEST_DEG, view.pitch_deg * TEST_DEG, view.fov_deg * TEST_DEG, v);
            double f[3];
            ref_dir(view.yaw_deg * TEST_DEG, view.pitch_deg * TEST_DEG, f);
            double d_km = block_distance_m(x, y) * 1e-3 / (v[0] * f[0] + v[1] * f[1] + v[2] * f[2]);
            ref_aerial ref;
            ref_radiance_to_point(&earth, view.altitude_km, v, sun, d_km, q, &ref);
            for (int c = 0; c < 3; ++c) {
                double a = io_half_to_float(oa[i + c]), b = io_half_to_float(ob[i + c]);
                double T = (a - b) / (COLOR_A - COLOR_B), S = b - COLOR_B * T;
                double S_ref = ref.rayleigh[c] + ref.mie[c];
                worst_T = fmax(worst_T, fabs(T - ref.transmittance[c]));
                worst_S = fmax(worst_S, rel(S, S_ref));
                CHECK(fabs(T - ref.transmittance[c]) <= 2e-3, "pixel (%d, %d) at %.2f km: T %g, the reference %g", x, y,
                      d_km, T, ref.transmittance[c]);
                CHECK(rel(S, S_ref) <= 0.05, "pixel (%d, %d) at %.2f km: S %g, the reference %g", x, y, d_km, S, S_ref);
                if (c == 1 && y == H - 1 && x == W / 4) S_near = S, T_near = T;
                if (c == 1 && y == H - 1 && x == 3 * W / 4) S_far = S, T_far = T;
            }
            ++geo_checked;
        }
    printf("host_frame: %d sky pixels within %.2e of the sky pass; %d geometry pixels: max |dT| %.2e, max S error "
           "%.2f%% against the reference; green near (2 km) T %.4f S %.4f, far (15 km) T %.4f S %.4f\n",
           sky_checked, worst_sky, geo_checked, worst_T, 100 * worst_S, T_near, S_near, T_far, S_far);
    CHECK(sky_checked == W * H / 2 && (!check || geo_checked >= W * H / 8), "checked %d sky, %d geometry pixels", sky_checked, geo_checked);
    CHECK(!check || (S_far > S_near && T_far < T_near), "the far block is not hazier than the near one");

    /* --check: the same geometry through a standard-depth projection with a finite far plane (100 km), and the
     * frame without a depth image. Their own submission, after the traced frames (the drop runs do not record it). */
    if (check) {
        const double n = NEAR_M, far = 100000.0, A = far / (n - far), B = n * far / (n - far);
        host_camera std_cam = cam;
        std_cam.projection[10] = A, std_cam.projection[11] = -1.0, std_cam.projection[14] = B;
        HostFramePush std_push, sky_push;
        CHECK(host_frame_push(&std_cam, &view, earth.bottom_radius, earth.top_radius - earth.bottom_radius, W, H, true,
                              &std_push, err, sizeof err) == 0, "standard depth: %s", err);
        CHECK(std_push.depth.z == 1.0f && std_push.depth.w == 0.0f, "standard depth not detected: far %g, mode %g",
              std_push.depth.z, std_push.depth.w);
        CHECK(host_frame_push(&cam, &view, earth.bottom_radius, earth.top_radius - earth.bottom_radius, W, H, false,
                              &sky_push, err, sizeof err) == 0, "no depth: %s", err);
        /* depth = (A z_eye + B) / -z_eye with z_eye = -distance along the axis; the sky rows at the far plane. */
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                dp[y * W + x] = y < H / 2 ? 1.0f : (float)((B - A * block_distance_m(x, y)) / block_distance_m(x, y));
        gpu_buffer extra_rb[2];
        cmd = gpu_begin_commands(&ctx);
        for (int k = 0; k < 2; ++k) {
            gpu_buffer_create(&ctx, &extra_rb[k], "host colour readback", W * H * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
            host_barrier(cmd, color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, 0,
                         VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                         VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            vkCmdCopyBufferToImage(cmd, upload[1].buffer, color.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &cc);
            if (k == 0)
                vkCmdCopyBufferToImage(cmd, depth_upload.buffer, depth.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &dc);
            host_frame_desc f = {.color = &color, .depth = k == 0 ? &depth : NULL, .push = k == 0 ? &std_push : &sky_push};
            host_frame_record(&t.r, &hf, cmd, &f);
            vkCmdCopyImageToBuffer(cmd, color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, extra_rb[k].buffer, 1, &cc);
            to_host[k].buffer = extra_rb[k].buffer;
        }
        vkCmdPipelineBarrier2(cmd, &dep);
        gpu_submit_and_wait(&ctx, cmd);
        double worst_std = 0.0, worst_none = 0.0;
        for (int k = 0; k < 2; ++k) gpu_buffer_invalidate(&ctx, &extra_rb[k]);
        const uint16_t *os = extra_rb[0].mapped, *on = extra_rb[1].mapped;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                for (int c = 0; c < 3; ++c) {
                    size_t i = 4 * ((size_t)y * W + x) + c;
                    /* Standard depth: the same S (colour B = 0) as the reversed frame's, within 1 %: float32 depth
                     * near 1 resolves 15 km to ~0.2 % (its step 6e-8 against 1 - depth ~ 3e-5), plus fp16. */
                    double e = rel(io_half_to_float(os[i]), io_half_to_float(ob[i]));
                    worst_std = fmax(worst_std, e);
                    CHECK(e <= 0.01, "standard depth, pixel (%d, %d) channel %d: %g, reversed %g", x, y, c,
                          io_half_to_float(os[i]), io_half_to_float(ob[i]));
                    /* No depth image: the sky pass's frame in every pixel. */
                    double e2 = rel(io_half_to_float(on[i]), test_pixel(&sky, x, y)[c]);
                    worst_none = fmax(worst_none, e2);
                    CHECK(e2 <= 2e-3, "no depth, pixel (%d, %d) channel %d: %g, the sky pass %g", x, y, c,
                          io_half_to_float(on[i]), test_pixel(&sky, x, y)[c]);
                }
        printf("host_frame: standard depth within %.2e of reversed; no depth image: every pixel within %.2e of the sky "
               "pass\n", worst_std, worst_none);
        for (int k = 0; k < 2; ++k) gpu_buffer_destroy(&ctx, &extra_rb[k]);
    }

    for (int k = 0; k < 2; ++k) gpu_buffer_destroy(&ctx, &upload[k]), gpu_buffer_destroy(&ctx, &readback[k]);
    gpu_buffer_destroy(&ctx, &depth_upload);
    vkDestroyImageView(ctx.device, color.view, NULL), vkDestroyImageView(ctx.device, depth.view, NULL);
    vkDestroyImage(ctx.device, color.image, NULL), vkDestroyImage(ctx.device, depth.image, NULL);
    vkFreeMemory(ctx.device, color_mem, NULL), vkFreeMemory(ctx.device, depth_mem, NULL);
    host_frame_destroy(&hf, &t.r);
    test_frame_free(&sky);
    test_renderer_destroy(&t);
    gpu_context_destroy(&ctx);
    unsigned messages = gpu_validation_message_count();
    if (messages) fprintf(stderr, "host_frame_probe: validation reported %u message(s)\n", messages);
    if (check_failures) fprintf(stderr, "host_frame_probe: %d failure(s)\n", check_failures);
    return messages || check_failures ? 1 : 0;
}
