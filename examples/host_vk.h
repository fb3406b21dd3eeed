/* The example host's Vulkan boilerplate (instance, device, images, buffers, a graphics pipeline, an EXR writer):
 * what any engine already has. Nothing here knows vksky; sky_host.c is the part that shows the integration. */
#ifndef VKSKY_EXAMPLE_HOST_VK_H
#define VKSKY_EXAMPLE_HOST_VK_H
#include <vulkan/vulkan.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define HV_CHECK(call)                                                                                             \
    do {                                                                                                           \
        VkResult r_ = (call);                                                                                      \
        if (r_ != VK_SUCCESS) hv_fail(__FILE__, __LINE__, #call, r_);                                              \
    } while (0)
void hv_fail(const char *file, int line, const char *call, VkResult r);

typedef struct hv_device {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice gpu;
    VkDevice device;
    VkQueue queue;
    uint32_t family;
    VkCommandPool pool;
} hv_device;
/* Vulkan 1.3 with `features13` enabled (what vksky_get_device_requirements asks); `validate`: the Khronos layer
 * with synchronization validation, every warning or error printed and counted (hv_validation_messages). */
void hv_device_create(hv_device *d, bool validate, const char *const *instance_exts, uint32_t ext_count,
                      bool swapchain, const VkPhysicalDeviceVulkan13Features *features13);
void hv_device_destroy(hv_device *d);
unsigned hv_validation_messages(void);

typedef struct hv_image {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;
    VkFormat format;
    VkExtent2D extent;
} hv_image;
void hv_image_create(const hv_device *d, hv_image *img, VkFormat format, VkExtent2D extent, VkImageUsageFlags usage,
                     VkImageAspectFlags aspect);
void hv_image_destroy(const hv_device *d, hv_image *img);

typedef struct hv_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped;
} hv_buffer;
void hv_buffer_create(const hv_device *d, hv_buffer *b, VkDeviceSize size, VkBufferUsageFlags usage);
void hv_buffer_destroy(const hv_device *d, hv_buffer *b);

/* A dynamic-rendering pipeline: `mesh` true: vertex input (position, normal, albedo), depth test GREATER (reversed
 * depth) and write; false: a full-screen triangle without vertex input or depth. */
VkPipeline hv_pipeline(const hv_device *d, VkPipelineLayout layout, const uint32_t *vs, size_t vs_size,
                       const uint32_t *fs, size_t fs_size, VkFormat color, VkFormat depth, bool mesh);
/* One image barrier (sync2). */
void hv_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkPipelineStageFlags2 src_stage,
                VkAccessFlags2 src_access, VkImageLayout from, VkPipelineStageFlags2 dst_stage,
                VkAccessFlags2 dst_access, VkImageLayout to);
VkCommandBuffer hv_begin(const hv_device *d);
void hv_submit_wait(const hv_device *d, VkCommandBuffer cmd);

float hv_half_to_float(uint16_t h);
/* An uncompressed scanline EXR of float RGBA. 0 on success. */
int hv_write_exr(const char *path, const float *rgba, int width, int height);
/* The window's tone map (tonemap.frag: exposure, Reinhard, then the sRGB encoding its swapchain format applies) on
 * the host's half-float RGBA pixels, written as an 8-bit RGBA PNG (libpng), opaque. 0 on success. */
int hv_write_png_tonemapped(const char *path, const uint16_t *rgba, int width, int height, float exposure);
/* The same from half-float RGBA (an RGBA16F image read back). */
int hv_write_exr_half(const char *path, const uint16_t *rgba, int width, int height);
/* Records the copy of a colour image (in TRANSFER_SRC_OPTIMAL) into `buffer` and the barrier that makes the copy
 * visible to the host, submits `cmd`, waits and frees it. */
void hv_copy_to_host(const hv_device *d, VkCommandBuffer cmd, VkImage image, VkExtent2D extent, const hv_buffer *buffer);
#endif

/* The window: a GLFW window, its surface and an sRGB FIFO swapchain, the semaphores of one frame in flight, and the
 * host's tone map pass (a full-screen triangle sampling the HDR image into the swapchain image). */
typedef struct GLFWwindow GLFWwindow;
typedef struct hv_window {
    GLFWwindow *window;
    VkSurfaceKHR surface;
    VkSwapchainKHR swapchain;
    VkFormat format;
    VkExtent2D extent;
    uint32_t count;
    VkImage images[8];
    VkImageView views[8];
    VkSemaphore acquired, done[8];
    VkSampler sampler;
    VkDescriptorSetLayout set_layout;
    VkDescriptorPool pool;
    VkDescriptorSet set;
    VkPipelineLayout layout;
    VkPipeline tonemap;
} hv_window;
/* Creates the GLFW window too (glfwInit first); the swapchain's size is the window's framebuffer's. */
void hv_window_create(const hv_device *d, hv_window *w, GLFWwindow *window, VkImageView hdr_view,
                      const uint32_t *vs, size_t vs_size, const uint32_t *fs, size_t fs_size);
void hv_window_destroy(const hv_device *d, hv_window *w);
/* Records the tone map of the HDR image into swapchain image `index` at the end of `cmd`, submits it (waiting for the
 * acquire, signalling the image's semaphore), presents, waits for the queue (one frame in flight: simple, not fast;
 * an engine keeps two, with a fence each) and frees `cmd`. */
void hv_window_present(const hv_device *d, hv_window *w, VkCommandBuffer cmd, uint32_t index);

/* The mesh of sky_host_scene.h (the ground, every box's four sides and top) as triangles of (position, normal,
 * albedo) into `out`; returns the vertex count ((1 + 5 boxes) x 6). */
uint32_t hv_mesh_build(float *out);
