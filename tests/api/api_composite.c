/* Compositing a render through the API (vksky_composite_*, ABI 4) as an engine would: its own command buffer, its own
 * inputs, its own bands.
 *   api_composite VKSKY_BIN GEN_COMPOSITE_SCENE: a generated 96x64 scene (tests/gen_composite_scene.c: beauty.exr,
 *   position.exr, the camera as flags) is composited by `vksky --composite` (one band) and by this host: the beauty
 *   and position read with vksky_io, a LUTS_ONLY renderer of the command line's scene in the lesson's units, the
 *   camera given as a vksky_composite_view (the march settings from vksky_quality_config_preset, not from the command
 *   line), and the image in four bands of 16 rows through two slots in turn. Every layer of the host's equals the
 *   command line's, half for half as the EXR stores them. Then the calls' refusals: one message and a code each.
 * Validation + synchronization validation on throughout; any message fails. A few seconds on lavapipe. */
#include "api_host.h"
#include "io/exr_read.h"
#include "io/half_float.h"
#include <math.h>
#include <unistd.h>

enum { W = 96, H = 64, BAND = 16 };

static const char *const LAYERS[VKSKY_COMPOSITE_LAYERS] = {"", "sky.", "sun_disk.", "transmittance.", "rayleigh.",
                                                           "mie."};

static float *read_channels(const char *path, const char *const *names, int count)
{
    float *out = malloc(sizeof(float) * W * H * (size_t)count);
    char err[300];
    if (!out || io_exr_read_channels(path, names, count, out, err, sizeof err) != 0) {
        fprintf(stderr, "FAIL: %s: %s\n", path, err);
        exit(1);
    }
    return out;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: api_composite VKSKY_BIN GEN_COMPOSITE_SCENE\n");
        return 2;
    }
    char dir[] = "/tmp/api_composite_XXXXXX", cmd[2000], path[600];
    if (!mkdtemp(dir)) return 1;
    snprintf(cmd, sizeof cmd, "%s %s %d %d >/dev/null", argv[2], dir, W, H);
    if (system(cmd) != 0) return fprintf(stderr, "FAIL: %s\n", cmd), 1;
    /* The command line's composite: the same scene, camera and sun, the lesson's quality. */
    const char *sky[] = {"vksky", "--quality", "lesson", "--sun-elevation", "20", "--sun-azimuth", "-60"};
    int n = snprintf(cmd, sizeof cmd, "%s --composite %s/beauty.exr --position %s/position.exr --camera-position "
                     "-3.5,-8.5,218.8 --yaw -90 --pitch -3 --fov 40 --validate --render %s/cli.exr", argv[1], dir,
                     dir, dir);
    for (int i = 1; i < 7; ++i) n += snprintf(cmd + n, sizeof cmd - (size_t)n, " %s", sky[i]);
    if (system(cmd) != 0) return fprintf(stderr, "FAIL: %s\n", cmd), 1;

    const char *rgba[] = {"R", "G", "B", "A"};
    snprintf(path, sizeof path, "%s/beauty.exr", dir);
    float *beauty = read_channels(path, rgba, 4);
    snprintf(path, sizeof path, "%s/position.exr", dir);
    float *position = read_channels(path, rgba, 3);

    vksky_context *c = host_own_context();
    host h;
    host_from_context(&h, c);
    host_create_target(&h, 1, 1, VK_FORMAT_R8G8B8A8_SRGB);   /* its command buffer and fence; the image unused */
    vksky_scene *scene = host_scene_of_args(7, (char **)sky);
    vksky_renderer_desc rd = {.abi_version = VKSKY_ABI_VERSION, .output = VKSKY_OUTPUT_LUTS_ONLY,
                              .quality = "scene", .units = VKSKY_UNITS_RELATIVE, .scene = scene};
    vksky_renderer *r = host_renderer(c, &rd);
    vksky_composite_desc cd = {.abi_version = VKSKY_ABI_VERSION, .width = W, .rows = BAND, .slots = 2};
    vksky_composite *comp = NULL;
    vksky_result res = vksky_composite_create(r, &cd, &comp);
    HOST_CHECK(res == VKSKY_SUCCESS && comp, "vksky_composite_create: %s", vksky_result_name(res));
    if (!comp) return 1;

    /* The camera: metres, Z up, at (-3.5, -8.5, 218.8), yaw -90, pitch -3, 40 degrees; the lesson's march. */
    vksky_quality_config q;
    vksky_quality_config_preset("lesson", &q);
    vksky_composite_view v = {.camera = {-3.5, -8.5, 218.8}, .km_per_unit = 0.001, .up_axis = 2, .fov_y_deg = 40.0,
                              .sun_azimuth_deg = -60.0, .sun_elevation_deg = 20.0, .steps = (int)q.view_steps,
                              .max_steps = (int)q.view_max_steps, .sample_offset = q.sample_offset,
                              .step_distribution = q.step_distribution, .steps_ramp_km = 100.0};
    vksky_composite_view_orient(&v, -90.0, -3.0);
    double altitude = -1.0;
    res = vksky_composite_set_view(comp, &v, H, VKSKY_COMPOSITE_FAST, &altitude);
    HOST_CHECK(res == VKSKY_SUCCESS && fabs(altitude - 0.2188) < 1e-3, "set_view: %s, altitude %g km",
               vksky_result_name(res), altitude);
    HOST_CHECK(fabs(vksky_composite_view_altitude(&v, scene) - altitude) < 1e-12, "view_altitude");

    /* Four bands, slots 0, 1, 0, 1; each band's layers into the whole image's. */
    float *mine = calloc((size_t)W * H * 4 * VKSKY_COMPOSITE_LAYERS, sizeof(float));
    for (int y0 = 0; y0 < H; y0 += BAND) {
        uint32_t slot = (uint32_t)(y0 / BAND) % 2;
        float *in = vksky_composite_inputs(comp, slot);
        for (size_t i = 0; i < (size_t)W * BAND; ++i) {
            size_t src = (size_t)y0 * W + i;
            memcpy(in + 4 * i, beauty + 4 * src, 4 * sizeof(float));
            memcpy(in + 4 * ((size_t)W * BAND + i), position + 3 * src, 3 * sizeof(float));
            in[4 * ((size_t)W * BAND + i) + 3] = 1.0f;
        }
        host_begin(&h);
        vksky_composite_frame f = {.slot = slot, .first_row = y0};
        res = vksky_composite_record(comp, h.cmd, &f);
        HOST_CHECK(res == VKSKY_SUCCESS, "vksky_composite_record: %s", vksky_result_name(res));
        host_end_submit_wait(&h);
        for (uint32_t k = 0; k < VKSKY_COMPOSITE_LAYERS; ++k) {
            const float *layer = vksky_composite_layer(comp, slot, k);
            HOST_CHECK(layer != NULL, "layer %u", k);
            if (layer)
                memcpy(mine + ((size_t)k * H + (size_t)y0) * W * 4, layer, sizeof(float) * 4 * W * BAND);
        }
    }
    /* Every layer against the command line's file, as halves. */
    snprintf(path, sizeof path, "%s/cli.exr", dir);
    long differ = 0;
    for (uint32_t k = 0; k < VKSKY_COMPOSITE_LAYERS; ++k) {
        int channels = k == 0 ? 4 : 3;
        char names[4][40];
        const char *list[4];
        for (int ch = 0; ch < channels; ++ch) {
            snprintf(names[ch], sizeof names[ch], "%s%s", LAYERS[k], rgba[ch]);
            list[ch] = names[ch];
        }
        float *cli = read_channels(path, list, channels);
        for (size_t i = 0; i < (size_t)W * H; ++i)
            for (int ch = 0; ch < channels; ++ch) {
                uint16_t a = io_float_to_half(mine[((size_t)k * W * H + i) * 4 + (size_t)ch]);
                uint16_t b = io_float_to_half(cli[i * (size_t)channels + (size_t)ch]);
                if (a != b && differ++ < 5)
                    fprintf(stderr, "FAIL: layer %u pixel (%zu, %zu) channel %d: host %g, vksky --composite %g\n", k,
                            i % W, i / W, ch, io_half_to_float(a), io_half_to_float(b));
            }
        free(cli);
    }
    HOST_CHECK(differ == 0, "%ld values differ from vksky --composite's layers", differ);

    /* Refusals: a code and one message each, nothing recorded. */
    unsigned before = api_messages[VKSKY_SEVERITY_ERROR];
    host_begin(&h);
    vksky_composite_frame bad = {.slot = 2};
    HOST_CHECK(vksky_composite_record(comp, h.cmd, &bad) == VKSKY_ERROR_INVALID_ARGUMENT, "slot 2 of 2");
    host_end_submit_wait(&h);
    vksky_composite_desc old = cd;
    old.abi_version = VKSKY_ABI_VERSION - 1;
    vksky_composite *none = NULL;
    HOST_CHECK(vksky_composite_create(r, &old, &none) == VKSKY_ERROR_ABI_MISMATCH && !none, "an older ABI");
    vksky_composite_view inside = v;
    inside.camera[2] = -5000.0;   /* 5 km below the ground */
    HOST_CHECK(vksky_composite_set_view(comp, &inside, H, 0, NULL) == VKSKY_ERROR_INVALID_ARGUMENT, "inside");
    HOST_CHECK(vksky_composite_inputs(comp, 2) == NULL && vksky_composite_layer(comp, 0, 6) == NULL, "ranges");
    HOST_CHECK(api_messages[VKSKY_SEVERITY_ERROR] - before == 3, "%u messages for 3 refusals",
               api_messages[VKSKY_SEVERITY_ERROR] - before);

    vksky_composite_destroy(comp);
    vksky_renderer_destroy(r);
    vksky_scene_destroy(scene);
    host_destroy_target(&h);
    unsigned messages = vksky_context_validation_message_count(c);
    HOST_CHECK(messages == 0, "%u validation messages", messages);
    vksky_context_destroy(c);
    free(beauty), free(position), free(mine);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0) fprintf(stderr, "note: %s left\n", dir);
    if (host_failures == 0) printf("api_composite: 4 bands through 2 slots equal vksky --composite's 6 layers\n");
    return host_failures ? 1 : 0;
}
