/* The CPU cost of vksky_record (a benchmark, not a test): a DISPLAY renderer at WIDTHxHEIGHT on vksky's own device
 * (no validation), its frame recorded into the host's command buffer 1000 times after 100 of warm-up; prints the
 * median and the 90th percentile of the thread's CPU time per call, in microseconds, with the LUTs up to date
 * (a steady frame) and with force_luts (the LUT passes recorded too). Recording only: nothing is submitted.
 *   api_bench [WIDTH HEIGHT [QUALITY]]   (default 1280 720 medium) */
#include "api_host.h"
#include <time.h>

static double thread_us(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec * 1e6 + t.tv_nsec * 1e-3;
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void measure(host *h, vksky_renderer *r, const vksky_frame *f, const char *label)
{
    enum { WARM = 100, N = 1000 };
    static double us[N];
    for (int i = 0; i < WARM + N; ++i) {
        host_begin(h);
        double t0 = thread_us();
        vksky_record(r, h->cmd, f);
        double t1 = thread_us();
        HOST_VK(vkEndCommandBuffer(h->cmd));
        if (i >= WARM) us[i - WARM] = t1 - t0;
    }
    qsort(us, N, sizeof us[0], compare_double);
    printf("vksky_record %s: median %.1f us, p90 %.1f us (CPU, %d calls after %d of warm-up)\n", label, us[N / 2],
           us[N * 9 / 10], N, WARM);
}

int main(int argc, char **argv)
{
    uint32_t w = argc > 2 ? (uint32_t)atoi(argv[1]) : 1280, hgt = argc > 2 ? (uint32_t)atoi(argv[2]) : 720;
    const char *quality = argc > 3 ? argv[3] : "medium";
    vksky_own_device_desc od = {.abi_version = VKSKY_ABI_VERSION, .device_index = -1, .message = api_message};
    vksky_context *c = NULL;
    if (vksky_context_create_own(&od, &c) != VKSKY_SUCCESS) return 1;
    host h;
    host_from_context(&h, c);
    host_create_target(&h, w, hgt, VK_FORMAT_R8G8B8A8_SRGB);
    VkPhysicalDeviceDriverProperties driver = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 p = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &driver};
    vkGetPhysicalDeviceProperties2(h.physical, &p);
    printf("device: %s (%s %s), %ux%u, quality %s\n", p.properties.deviceName, driver.driverName, driver.driverInfo, w,
           hgt, quality);
    vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION, .output = VKSKY_OUTPUT_DISPLAY, .width = w,
                             .height = hgt, .target_format = VK_FORMAT_R8G8B8A8_SRGB, .quality = quality,
                             .bloom = true};
    vksky_renderer *r = NULL;
    if (vksky_renderer_create(c, &d, &r) != VKSKY_SUCCESS) return 1;
    vksky_camera cam = {.origin_altitude_m = 1.0};
    vksky_camera_look(&cam, 0.0, 10.0, 75.0, (double)w / hgt, 0.1);
    vksky_frame f = {.camera = &cam, .exposure = 12.0, .color = host_image(&h, VK_FORMAT_R8G8B8A8_SRGB)};
    measure(&h, r, &f, "steady frame");
    f.force_luts = true;
    measure(&h, r, &f, "with the LUT passes");
    vksky_renderer_destroy(r);
    host_destroy_target(&h);
    vksky_context_destroy(c);
    return host_failures ? 1 : 0;
}
