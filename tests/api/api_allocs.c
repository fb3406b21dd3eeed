/* Zero host allocations per recorded frame, counted where they happen: this test links libvksky.a (one relocatable
 * object) with the linker's --wrap for malloc, calloc, realloc, aligned_alloc, posix_memalign and free, so every
 * allocation libvksky's own code makes goes through the counters below. The Vulkan loader, the driver and the
 * validation layer are shared libraries loaded at run time: their allocations are not counted (they are not vksky's,
 * and a host's VkAllocationCallbacks see those that go through Vulkan: api_render counts them).
 *
 * 100 vksky_record calls each of DISPLAY (bloom, tone map into the host's 8-bit image), DISPLAY with the compute
 * tone map into a UNORM storage image (vksky_display_config COMPUTE: its descriptor set per host view) and
 * LUTS_ONLY, after a first frame (which may build the LUTs), must make no allocation at all; creating a renderer must make some (the
 * counters see libvksky's calls: the test can fail). Validation + synchronization validation on; any message fails. */
#include "api_host.h"
#include <stdatomic.h>

static atomic_long vksky_allocs;   /* allocations while `counting` */
static atomic_bool counting;

void *__real_malloc(size_t size);
void *__real_calloc(size_t n, size_t size);
void *__real_realloc(void *p, size_t size);
void *__real_aligned_alloc(size_t align, size_t size);
int __real_posix_memalign(void **p, size_t align, size_t size);
void __real_free(void *p);

static void counted(void) { if (atomic_load(&counting)) atomic_fetch_add(&vksky_allocs, 1); }
void *__wrap_malloc(size_t size) { counted(); return __real_malloc(size); }
void *__wrap_calloc(size_t n, size_t size) { counted(); return __real_calloc(n, size); }
void *__wrap_realloc(void *p, size_t size) { counted(); return __real_realloc(p, size); }
void *__wrap_aligned_alloc(size_t align, size_t size) { counted(); return __real_aligned_alloc(align, size); }
int __wrap_posix_memalign(void **p, size_t align, size_t size) { counted(); return __real_posix_memalign(p, align, size); }
void __wrap_free(void *p) { __real_free(p); }

enum { W = 96, H = 64, FRAMES = 100 };

/* Allocations libvksky makes over FRAMES recordings of `output` into the host's image (after one frame first). */
static long frames_allocations(host *h, vksky_context *c, vksky_output output, long *creation,
                               const vksky_display_config *dc)
{
    VkFormat format = dc ? VK_FORMAT_R8G8B8A8_UNORM : VK_FORMAT_R8G8B8A8_SRGB;
    vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION, .next = dc, .output = output, .width = W, .height = H,
                             .target_format = format, .quality = "medium", .bloom = true,
                             .units = VKSKY_UNITS_PHOTOMETRIC};
    vksky_renderer *r = NULL;
    atomic_store(&vksky_allocs, 0);
    atomic_store(&counting, true);
    vksky_result res = vksky_renderer_create(c, &d, &r);
    atomic_store(&counting, false);
    *creation = atomic_load(&vksky_allocs);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_renderer_create: %s", vksky_result_name(res));
    if (!r) exit(1);
    vksky_camera cam = {.origin_altitude_m = 1.0};
    vksky_camera_look(&cam, 30.0, 10.0, 75.0, (double)W / H, 0.1);
    vksky_frame f = {.camera = &cam, .exposure = 12.0, .color = host_image(h, format)};
    HOST_CHECK(!dc || vksky_renderer_get_tonemap_path(r) == VKSKY_TONEMAP_PATH_COMPUTE, "not the compute tone map");
    host_begin(h);
    HOST_CHECK(vksky_record(r, h->cmd, &f) == VKSKY_SUCCESS, "the first vksky_record failed");
    host_end_and_read(h);
    atomic_store(&vksky_allocs, 0);
    for (int i = 0; i < FRAMES; ++i) {
        host_begin(h);
        atomic_store(&counting, true);
        res = vksky_record(r, h->cmd, &f);
        atomic_store(&counting, false);
        HOST_CHECK(res == VKSKY_SUCCESS, "vksky_record: %s", vksky_result_name(res));
        if (i + 1 < FRAMES) HOST_VK(vkEndCommandBuffer(h->cmd));
        else host_end_and_read(h);   /* the last one runs: the recordings were real */
    }
    long n = atomic_load(&vksky_allocs);
    vksky_renderer_destroy(r);
    return n;
}

int main(void)
{
    host h = {0};
    host_create_device(&h, NULL);
    host_create_target(&h, W, H, VK_FORMAT_R8G8B8A8_SRGB);
    vksky_context_desc cd = host_context_desc(&h, NULL);
    cd.message = api_message;
    vksky_context *c = NULL;
    vksky_result res = vksky_context_create(&cd, &c);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_context_create: %s", vksky_result_name(res));
    if (!c) return 1;
    long made_display, made_luts, made_storage;
    long display = frames_allocations(&h, c, VKSKY_OUTPUT_DISPLAY, &made_display, NULL);
    long luts = frames_allocations(&h, c, VKSKY_OUTPUT_LUTS_ONLY, &made_luts, NULL);
    host s = h;   /* the same device, a UNORM storage image of its own */
    host_create_target_usage(&s, W, H, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT);
    vksky_display_config dc = {.type = VKSKY_STRUCTURE_TYPE_DISPLAY_CONFIG, .tonemap_path = VKSKY_TONEMAP_PATH_COMPUTE,
                               .target_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                               VK_IMAGE_USAGE_STORAGE_BIT};
    long storage = frames_allocations(&s, c, VKSKY_OUTPUT_DISPLAY, &made_storage, &dc);
    host_destroy_target(&s);
    printf("libvksky's own allocations: renderer creation %ld (DISPLAY), %ld (LUTS_ONLY); %d vksky_record calls: "
           "%ld (DISPLAY), %ld (LUTS_ONLY), %ld (DISPLAY, compute tone map)\n", made_display, made_luts, FRAMES,
           display, luts, storage);
    HOST_CHECK(storage == 0, "%ld allocations in %d DISPLAY frames of the compute tone map", storage, FRAMES);
    HOST_CHECK(made_display > 0 && made_luts > 0, "no allocation counted while a renderer was made: the counters "
               "do not see libvksky's calls, so the per-frame count proves nothing");
    HOST_CHECK(display == 0, "%ld allocations in %d DISPLAY frames", display, FRAMES);
    HOST_CHECK(luts == 0, "%ld allocations in %d LUTS_ONLY frames", luts, FRAMES);
    vksky_context_destroy(c);
    host_destroy_target(&h);
    host_destroy_device(&h, NULL);
    HOST_CHECK(host_validation_messages == 0, "%u validation messages", host_validation_messages);
    HOST_CHECK(api_messages[VKSKY_SEVERITY_ERROR] + api_messages[VKSKY_SEVERITY_VALIDATION] == 0,
               "vksky reported errors");
    return host_failures ? 1 : 0;
}
