/* Images and buffers with their memory. Knows nothing of skies. */
#ifndef VKSKY_GPU_RESOURCES_H
#define VKSKY_GPU_RESOURCES_H
#include "gpu/context.h"

#define GPU_MAX_MIPS 12

typedef struct gpu_image {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;                 /* all mips */
    VkImageView mip_views[GPU_MAX_MIPS];  /* one view per mip (never null for m < mip_levels): never sample and render the same subresource */
    VkFormat format;
    VkExtent2D extent;
    uint32_t depth;                   /* 1, or the depth of a 3D image */
    uint32_t mip_levels;
    const char *name;
} gpu_image;

typedef struct gpu_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped;                     /* host-visible buffers stay mapped */
    VkDeviceSize size;
    bool coherent;
} gpu_buffer;

void gpu_image_create(const gpu_context *ctx, gpu_image *img, const char *name, VkFormat format, uint32_t width,
                      uint32_t height, uint32_t mips, VkImageUsageFlags usage);
/* A 3D image, one level (a froxel volume). */
void gpu_image_create_3d(const gpu_context *ctx, gpu_image *img, const char *name, VkFormat format, uint32_t width,
                         uint32_t height, uint32_t depth, VkImageUsageFlags usage);
void gpu_image_destroy(const gpu_context *ctx, gpu_image *img);
/* A host-visible buffer (uniforms, readback). */
void gpu_buffer_create(const gpu_context *ctx, gpu_buffer *buf, const char *name, VkDeviceSize size,
                       VkBufferUsageFlags usage);
void gpu_buffer_destroy(const gpu_context *ctx, gpu_buffer *buf);
/* After the fence and the HOST_READ barrier: make device writes visible to the host if memory is not coherent. */
void gpu_buffer_invalidate(const gpu_context *ctx, const gpu_buffer *buf);
/* Extent of mip level `mip` of a width x height image. */
VkExtent2D gpu_mip_extent(VkExtent2D base, uint32_t mip);
VkImageSubresourceRange gpu_color_range(uint32_t base_mip, uint32_t count);
#endif
