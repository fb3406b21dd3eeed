/* Every error path of the API returns its documented code and the process lives on: NULL handles and descs, a
 * wrong abi_version, a size of 0, an unknown quality name, a missing and a malformed scene file, an unsupported
 * target format or output, a frame that does not fit its renderer, and Vulkan failures provoked by allocation
 * callbacks that fail after N allocations (every N from 0 to past the renderer's last one, sampled): each create
 * returns VKSKY_ERROR_OUT_OF_MEMORY or VKSKY_ERROR_VULKAN, and what it made before failing is freed (the live
 * count returns to where it was). Validation + synchronization validation on the host's device: no message. */
#include "api_host.h"

typedef struct failing { long live, calls, budget; } failing;   /* budget < 0: never fail */
static void *fail_alloc(void *user, size_t size, size_t align, VkSystemAllocationScope scope)
{
    (void)scope;
    failing *f = user;
    if (f->budget >= 0 && f->calls >= f->budget) return NULL;
    if (align < 16) align = 16;
    unsigned char *base = aligned_alloc(align, ((size + 2 * align - 1) / align) * align);
    if (!base) return NULL;
    f->live++, f->calls++;
    size_t *header = (size_t *)(base + align);
    header[-1] = align, header[-2] = size;
    return base + align;
}
static void fail_free(void *user, void *mem)
{
    if (!mem) return;
    ((failing *)user)->live--;
    free((unsigned char *)mem - ((size_t *)mem)[-1]);
}
static void *fail_realloc(void *user, void *old, size_t size, size_t align, VkSystemAllocationScope scope)
{
    if (!old) return fail_alloc(user, size, align, scope);
    if (!size) { fail_free(user, old); return NULL; }
    void *p = fail_alloc(user, size, align, scope);
    if (!p) return NULL;
    size_t old_size = ((size_t *)old)[-2];
    memcpy(p, old, old_size < size ? old_size : size);
    fail_free(user, old);
    return p;
}

#define EXPECT(call, code)                                                                                  \
    do {                                                                                                    \
        vksky_result got_ = (call);                                                                         \
        HOST_CHECK(got_ == (code), "%s returned %s, expected %s", #call, vksky_result_name(got_), #code);   \
    } while (0)

static vksky_renderer_desc display_desc(uint32_t w, uint32_t h)
{
    return (vksky_renderer_desc){.abi_version = VKSKY_ABI_VERSION, .output = VKSKY_OUTPUT_DISPLAY, .width = w,
                                 .height = h, .target_format = VK_FORMAT_R8G8B8A8_SRGB, .quality = "low"};
}

int main(int argc, char **argv)
{
    const char *bad_dir = argc > 1 ? argv[1] : "tests/scenes_bad";
    vksky_context *c = NULL;
    vksky_renderer *r = NULL;
    vksky_scene *s = NULL;

    /* Contexts. */
    EXPECT(vksky_context_create(NULL, &c), VKSKY_ERROR_INVALID_ARGUMENT);
    vksky_context_desc empty = {.abi_version = VKSKY_ABI_VERSION};
    EXPECT(vksky_context_create(&empty, NULL), VKSKY_ERROR_INVALID_ARGUMENT);
    EXPECT(vksky_context_create(&empty, &c), VKSKY_ERROR_INVALID_ARGUMENT);
    vksky_context_desc old = {.abi_version = VKSKY_ABI_VERSION + 1};
    EXPECT(vksky_context_create(&old, &c), VKSKY_ERROR_ABI_MISMATCH);
    vksky_own_device_desc od = {.abi_version = 0};
    EXPECT(vksky_context_create_own(&od, &c), VKSKY_ERROR_ABI_MISMATCH);
    EXPECT(vksky_context_create_own(NULL, &c), VKSKY_ERROR_INVALID_ARGUMENT);
    od = (vksky_own_device_desc){.abi_version = VKSKY_ABI_VERSION, .device_index = 99};
    EXPECT(vksky_context_create_own(&od, &c), VKSKY_ERROR_INVALID_ARGUMENT);
    HOST_CHECK(c == NULL, "a failed create left a handle");
    vksky_context_destroy(NULL);

    /* Scenes. */
    EXPECT(vksky_scene_load(NULL, api_message, NULL, &s), VKSKY_ERROR_INVALID_ARGUMENT);
    EXPECT(vksky_scene_load("/nonexistent/scene.json", api_message, NULL, &s), VKSKY_ERROR_IO);
    char path[512];
    snprintf(path, sizeof path, "%s/empty.json", bad_dir);
    EXPECT(vksky_scene_load(path, api_message, NULL, &s), VKSKY_ERROR_PARSE);
    snprintf(path, sizeof path, "%s/bad-preset.json", bad_dir);
    EXPECT(vksky_scene_load(path, api_message, NULL, &s), VKSKY_ERROR_PARSE);
    HOST_CHECK(s == NULL, "a failed load left a scene");
    EXPECT(vksky_scene_create_earth(NULL), VKSKY_ERROR_INVALID_ARGUMENT);
    EXPECT(vksky_scene_copy(NULL, &s), VKSKY_ERROR_INVALID_ARGUMENT);
    EXPECT(vksky_scene_load("mars", api_message, NULL, &s), VKSKY_SUCCESS);
    EXPECT(vksky_scene_set_sun(s, 0.0, 91.0), VKSKY_ERROR_INVALID_ARGUMENT);
    EXPECT(vksky_scene_set_sun(NULL, 0.0, 10.0), VKSKY_ERROR_INVALID_ARGUMENT);
    HOST_CHECK(vksky_scene_ground_radius_m(s) < 4.0e6, "mars's ground radius %g m", vksky_scene_ground_radius_m(s));
    vksky_scene_destroy(s);
    vksky_scene_destroy(NULL);

    /* Renderers, on the host's device with failing allocation callbacks (not failing yet). */
    failing count = {.budget = -1};
    VkAllocationCallbacks cb = {.pUserData = &count, .pfnAllocation = fail_alloc, .pfnReallocation = fail_realloc,
                                .pfnFree = fail_free};
    host h;
    host_create_device(&h, NULL);
    vksky_context_desc cd = host_context_desc(&h, &cb);
    count.budget = 0;   /* the context's command pool cannot be made */
    vksky_result res = vksky_context_create(&cd, &c);
    HOST_CHECK(res == VKSKY_ERROR_OUT_OF_MEMORY || res == VKSKY_ERROR_VULKAN, "context with no memory: %s",
               vksky_result_name(res));
    HOST_CHECK(count.live == 0, "%ld blocks left", count.live);
    count.budget = -1;
    EXPECT(vksky_context_create(&cd, &c), VKSKY_SUCCESS);
    if (!c) return 1;
    vksky_renderer_desc d = display_desc(32, 18);
    EXPECT(vksky_renderer_create(NULL, &d, &r), VKSKY_ERROR_INVALID_ARGUMENT);
    EXPECT(vksky_renderer_create(c, NULL, &r), VKSKY_ERROR_INVALID_ARGUMENT);
    EXPECT(vksky_renderer_create(c, &d, NULL), VKSKY_ERROR_INVALID_ARGUMENT);
    d.abi_version = 7;
    EXPECT(vksky_renderer_create(c, &d, &r), VKSKY_ERROR_ABI_MISMATCH);
    d = display_desc(0, 18);
    EXPECT(vksky_renderer_create(c, &d, &r), VKSKY_ERROR_INVALID_ARGUMENT);
    d = display_desc(32, 18);
    d.quality = "fastest";
    EXPECT(vksky_renderer_create(c, &d, &r), VKSKY_ERROR_INVALID_ARGUMENT);
    d = display_desc(32, 18);
    d.target_format = VK_FORMAT_R16G16B16A16_SFLOAT;
    EXPECT(vksky_renderer_create(c, &d, &r), VKSKY_ERROR_UNSUPPORTED);
    d = display_desc(32, 18);
    d.output = VKSKY_OUTPUT_SCENE_LINEAR;
    EXPECT(vksky_renderer_create(c, &d, &r), VKSKY_ERROR_UNSUPPORTED);
    d = display_desc(32, 18);
    d.max_error = 1e-9;   /* no measured configuration is that good */
    d.quality = NULL;
    EXPECT(vksky_renderer_create(c, &d, &r), VKSKY_ERROR_INVALID_ARGUMENT);
    HOST_CHECK(r == NULL, "a failed create left a renderer");

    /* Vulkan failures: every N from 0 up to the renderer's allocation count, sampled (each try builds pipelines). */
    d = display_desc(32, 18);
    long live0 = count.live, calls0 = count.calls;
    EXPECT(vksky_renderer_create(c, &d, &r), VKSKY_SUCCESS);
    long needed = count.calls - calls0;
    vksky_renderer_destroy(r);
    r = NULL;
    HOST_CHECK(count.live == live0, "a destroyed renderer left %ld blocks", count.live - live0);
    int tries = 0;
    /* The layer reports each failing call's result as a message of its own (the call's VkResult named alone): those
     * are the provoked failures, not misuse; anything else still fails the test. */
    for (long n = 0; n < needed; ++n, ++tries) {
        count.budget = count.calls + n;
        res = vksky_renderer_create(c, &d, &r);
        count.budget = -1;
        HOST_CHECK(res == VKSKY_ERROR_OUT_OF_MEMORY || res == VKSKY_ERROR_VULKAN,
                   "allocation %ld failing: %s", n, vksky_result_name(res));
        HOST_CHECK(r == NULL, "a failed create left a renderer");
        HOST_CHECK(count.live == live0, "allocation %ld failing: %ld blocks leaked", n, count.live - live0);
        if (r) vksky_renderer_destroy(r), r = NULL;
    }
    printf("renderer creation: %ld allocations; %d failing points tried, each returned an error\n", needed, tries);

    /* Frames that do not fit. */
    EXPECT(vksky_renderer_create(c, &d, &r), VKSKY_SUCCESS);
    host_create_target(&h, 32, 18, VK_FORMAT_R8G8B8A8_SRGB);
    vksky_camera cam = {.origin_altitude_m = 1.0};
    vksky_camera_look(&cam, 0, 10, 60, 1.0, 0.1);
    vksky_frame f = {.camera = &cam, .color = host_image(&h, VK_FORMAT_R8G8B8A8_SRGB)};
    host_begin(&h);
    EXPECT(vksky_record(NULL, h.cmd, &f), VKSKY_ERROR_INVALID_ARGUMENT);
    EXPECT(vksky_record(r, VK_NULL_HANDLE, &f), VKSKY_ERROR_INVALID_ARGUMENT);
    EXPECT(vksky_record(r, h.cmd, NULL), VKSKY_ERROR_INVALID_ARGUMENT);
    f.color.extent = (VkExtent2D){16, 16};
    EXPECT(vksky_record(r, h.cmd, &f), VKSKY_ERROR_INVALID_ARGUMENT);   /* 16x16 into a 32x18 renderer */
    f.color.extent = (VkExtent2D){32, 18};
    f.camera = NULL;
    EXPECT(vksky_record(r, h.cmd, &f), VKSKY_ERROR_INVALID_ARGUMENT);
    vksky_camera flat = {0};   /* all-zero matrices: no rays */
    f.camera = &flat;
    EXPECT(vksky_record(r, h.cmd, &f), VKSKY_ERROR_INVALID_ARGUMENT);
    HOST_VK(vkEndCommandBuffer(h.cmd));
    EXPECT(vksky_renderer_resize(r, 0, 5), VKSKY_ERROR_INVALID_ARGUMENT);
    EXPECT(vksky_renderer_set_scene(r, NULL), VKSKY_ERROR_INVALID_ARGUMENT);
    EXPECT(vksky_get_luts(NULL, NULL), VKSKY_ERROR_INVALID_ARGUMENT);
    vksky_renderer_destroy(r);
    vksky_renderer_destroy(NULL);
    vksky_context_destroy(c);
    HOST_CHECK(count.live == 0, "%ld blocks left after the context", count.live);
    host_destroy_target(&h);
    host_destroy_device(&h, NULL);
    HOST_CHECK(host_validation_messages == host_result_messages, "%u validation messages besides the failing calls' results",
               host_validation_messages - host_result_messages);
    HOST_CHECK(!strcmp(vksky_result_name(VKSKY_ERROR_PARSE), "VKSKY_ERROR_PARSE"), "result names");
    printf("%s\n", host_failures ? "api_errors: FAILED" : "api_errors: every error path returned its code");
    return host_failures ? 1 : 0;
}
