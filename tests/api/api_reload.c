/* vksky_scene_reload (issue 25 item 2, F5 through the API): a scene of a command line naming --scene and a flag that
 * overrides one of the file's fields; the file edited on disk; the reload applies the file's new fields and keeps the
 * flag's value. Rendered through a readback renderer (validation + synchronization validation on), the reloaded
 * scene's frame equals, byte for byte, the frame of a scene the same command line makes from the edited file, and
 * differs from the edited file without the flag (the file's value would have won) and from the scene before the
 * reload. A reload that cannot read its file keeps the scene; a scene of no command line is refused. */
#include "api_host.h"
#include <stdint.h>

#define W 48u
#define H 27u

/* The scene file: Earth (Hillaire 2020 Table 1 in the fields that matter here) with a Mie g and a Rayleigh scale
 * height of our choosing. */
static void write_scene(const char *path, double mie_g, double rayleigh_km)
{
    FILE *f = fopen(path, "w");
    if (!f) { perror(path); exit(1); }
    fprintf(f, "{\"species\": {\"rayleigh\": {\"scattering\": [5.802e-3, 13.558e-3, 33.1e-3], \"density\": "
               "{\"profile\": \"exponential\", \"scale_height_km\": %g}}, \"mie\": {\"scattering\": [3.996e-3, 3.996e-3, "
               "3.996e-3], \"absorption\": [0.444e-3, 0.444e-3, 0.444e-3], \"density\": {\"profile\": \"exponential\", "
               "\"scale_height_km\": 1.2}, \"phase\": {\"model\": \"henyey-greenstein\", \"g\": %g}}}}\n",
            rayleigh_km, mie_g);
    fclose(f);
}

/* One frame of `scene` (its command line's view and quality) read back: the display bytes, malloc'd. */
static uint8_t *render(vksky_context *c, host *h, const vksky_scene *scene)
{
    vksky_readback_config rb = {.type = VKSKY_STRUCTURE_TYPE_READBACK_CONFIG};
    vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION, .next = &rb, .output = VKSKY_OUTPUT_DISPLAY,
                             .width = W, .height = H, .target_format = VK_FORMAT_R8G8B8A8_SRGB, .quality = "scene",
                             .bloom = true, .units = VKSKY_UNITS_PHOTOMETRIC, .scene = scene};
    vksky_renderer *r = NULL;
    vksky_result res = vksky_renderer_create(c, &d, &r);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_renderer_create: %s", vksky_result_name(res));
    if (!r) exit(1);
    vksky_frame_view view = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .yaw_deg = 0, .pitch_deg = 5, .fov_deg = 75};
    vksky_frame f = {.next = &view, .exposure = 12};
    host_begin(h);
    res = vksky_record(r, h->cmd, &f);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_record: %s", vksky_result_name(res));
    host_end_submit_wait(h);
    vksky_readback px;
    res = vksky_renderer_get_readback(r, &px);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_renderer_get_readback: %s", vksky_result_name(res));
    if (res != VKSKY_SUCCESS) exit(1);
    uint8_t *out = malloc(4 * (size_t)W * H);
    memcpy(out, px.display_rgba8, 4 * (size_t)W * H);
    vksky_renderer_destroy(r);
    return out;
}

static size_t differing(const uint8_t *a, const uint8_t *b)
{
    size_t n = 0;
    for (size_t i = 0; i < (size_t)W * H; ++i) n += memcmp(a + 4 * i, b + 4 * i, 4) != 0;
    return n;
}

static vksky_scene *from_args(int argc, char **argv)
{
    vksky_scene *s = NULL;
    vksky_result res = vksky_scene_from_args(argc, argv, api_message, NULL, &s);
    HOST_CHECK(res == VKSKY_SUCCESS && s, "vksky_scene_from_args: %s", vksky_result_name(res));
    if (!s) exit(1);
    return s;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: api_reload WORK_DIR\n");
        return 2;
    }
    char path[4096];
    snprintf(path, sizeof path, "%s/api_reload_scene.json", argv[1]);
    write_scene(path, 0.8, 8.0);
    vksky_own_device_desc od = {.abi_version = VKSKY_ABI_VERSION, .device_index = -1, .validation = true,
                                .message = api_message};
    vksky_context *c = NULL;
    vksky_result res = vksky_context_create_own(&od, &c);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_context_create_own: %s", vksky_result_name(res));
    if (!c) return 1;
    host h;
    host_from_context(&h, c);
    host_create_target(&h, W, H, VK_FORMAT_R8G8B8A8_SRGB);

    /* The command line: --mie-g 0.6 over the file's g (0.8 now, 0.3 after the edit); the file's Rayleigh scale height
     * (8 km, then 9) has no flag here. */
    char *with_flag[] = {"vksky", "--width", "48", "--height", "27", "--sun-elevation", "5", "--exposure", "12",
                         "--quality", "low", "--mie-g", "0.6", "--scene", path};
    char *without_flag[] = {"vksky", "--width", "48", "--height", "27", "--sun-elevation", "5", "--exposure", "12",
                            "--quality", "low", "--scene", path};
    int n_with = (int)(sizeof with_flag / sizeof *with_flag), n_without = (int)(sizeof without_flag / sizeof *without_flag);
    vksky_scene *live = from_args(n_with, with_flag);
    uint8_t *before = render(c, &h, live);

    write_scene(path, 0.3, 9.0);   /* the file changed on disk */
    res = vksky_scene_reload(live, api_message, NULL);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_scene_reload: %s", vksky_result_name(res));
    uint8_t *reloaded = render(c, &h, live);
    vksky_scene *expected_scene = from_args(n_with, with_flag), *file_scene = from_args(n_without, without_flag);
    uint8_t *expected = render(c, &h, expected_scene), *file_wins = render(c, &h, file_scene);
    size_t e = differing(reloaded, expected), f = differing(reloaded, file_wins), b = differing(reloaded, before);
    printf("pixels differing from the reloaded scene's frame: the edited file with the flag %zu, without the flag %zu, "
           "the scene before the reload %zu (of %u)\n", e, f, b, W * H);
    HOST_CHECK(e == 0, "the reloaded scene renders differently from the edited file with --mie-g 0.6 (%zu pixels)", e);
    HOST_CHECK(f > W * H / 10 && b > W * H / 10, "the candidates are too alike to tell the flag and the reload apart "
               "(%zu, %zu pixels)", f, b);

    /* A file that no longer parses: an error, the scene as it was (its frame unchanged). */
    FILE *broken = fopen(path, "w");
    if (broken) fputs("{\"species\": ", broken), fclose(broken);
    unsigned errors = api_messages[VKSKY_SEVERITY_ERROR];
    res = vksky_scene_reload(live, api_message, NULL);
    HOST_CHECK(res == VKSKY_ERROR_PARSE, "reload of a broken file: %s, expected VKSKY_ERROR_PARSE", vksky_result_name(res));
    HOST_CHECK(api_messages[VKSKY_SEVERITY_ERROR] == errors + 1, "reload of a broken file: no error message");
    uint8_t *kept = render(c, &h, live);
    HOST_CHECK(differing(kept, reloaded) == 0, "a failed reload changed the scene");
    /* Scenes of no command line, or none naming --scene: refused. */
    vksky_scene *earth = NULL;
    HOST_CHECK(vksky_scene_create_earth(&earth) == VKSKY_SUCCESS, "vksky_scene_create_earth");
    HOST_CHECK(vksky_scene_reload(earth, api_message, NULL) == VKSKY_ERROR_INVALID_ARGUMENT, "reload of Earth accepted");
    char *no_scene[] = {"vksky", "--mie-g", "0.6"};
    vksky_scene *plain = from_args(3, no_scene);
    HOST_CHECK(vksky_scene_reload(plain, api_message, NULL) == VKSKY_ERROR_INVALID_ARGUMENT,
               "reload of a command line without --scene accepted");
    HOST_CHECK(vksky_scene_reload(NULL, api_message, NULL) == VKSKY_ERROR_INVALID_ARGUMENT, "reload of NULL accepted");

    vksky_scene_destroy(plain), vksky_scene_destroy(earth), vksky_scene_destroy(live);
    vksky_scene_destroy(expected_scene), vksky_scene_destroy(file_scene);
    free(before), free(reloaded), free(expected), free(file_wins), free(kept);
    host_destroy_target(&h);
    unsigned validation = vksky_context_validation_message_count(c);
    vksky_context_destroy(c);
    remove(path);
    HOST_CHECK(validation == 0, "%u validation messages", validation);
    if (host_failures) return 1;
    printf("api_reload: ok\n");
    return 0;
}
