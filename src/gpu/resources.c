#include "gpu/resources.h"
#include <stdlib.h>

static uint32_t find_memory_type(const gpu_context *ctx, uint32_t bits, VkMemoryPropertyFlags want,
                                 VkMemoryPropertyFlags prefer)
{
    for (int pass = 0; pass < 2; ++pass) {
        VkMemoryPropertyFlags need = pass == 0 ? want | prefer : want;
        for (uint32_t i = 0; i < ctx->memory.memoryTypeCount; ++i)
            if ((bits & (1u << i)) && (ctx->memory.memoryTypes[i].propertyFlags & need) == need) return i;
    }
    char text[96];
    snprintf(text, sizeof text, "no suitable memory type (bits 0x%x, flags 0x%x)", bits, want);
    gpu_fail(VK_ERROR_OUT_OF_DEVICE_MEMORY, text);
}

VkImageSubresourceRange gpu_color_range(uint32_t base_mip, uint32_t count)
{
    return (VkImageSubresourceRange){
        .aspectMask = VK_IMAGE_ASPECT_COLOR_BIT, .baseMipLevel = base_mip, .levelCount = count, .layerCount = 1};
}

VkExtent2D gpu_mip_extent(VkExtent2D base, uint32_t mip)
{
    uint32_t w = base.width >> mip, h = base.height >> mip;
    return (VkExtent2D){w ? w : 1, h ? h : 1};
}

static VkImageView make_view(const gpu_context *ctx, VkImage image, VkImageViewType type, VkFormat format,
                             VkImageSubresourceRange range)
{
    VkImageViewCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
        .image = image,
        .viewType = type,
        .format = format,
        .subresourceRange = range,
    };
    VkImageView view;
    VK_CHECK(vkCreateImageView(ctx->device, &info, gpu_allocator(ctx->device), &view));
    return view;
}

/* A 2D image with `mips` levels, or a 3D image (depth > 1 or type 3D) of one level. */
static void image_create(const gpu_context *ctx, gpu_image *img, const char *name, VkImageType type, VkFormat format,
                         uint32_t width, uint32_t height, uint32_t depth, uint32_t mips, VkImageUsageFlags usage)
{
    *img = (gpu_image){.format = format, .extent = {width, height}, .depth = depth, .mip_levels = mips, .name = name};
    VkImageCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
        .imageType = type,
        .format = format,
        .extent = {width, height, depth},
        .mipLevels = mips,
        .arrayLayers = 1,
        .samples = VK_SAMPLE_COUNT_1_BIT,
        .tiling = VK_IMAGE_TILING_OPTIMAL,
        .usage = usage,
        .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
    };
    VK_CHECK(vkCreateImage(ctx->device, &info, gpu_allocator(ctx->device), &img->image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx->device, img->image, &req);
    VkMemoryAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = req.size,
        .memoryTypeIndex = find_memory_type(ctx, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0),
    };
    VK_CHECK(vkAllocateMemory(ctx->device, &alloc, gpu_allocator(ctx->device), &img->memory));
    VK_CHECK(vkBindImageMemory(ctx->device, img->image, img->memory, 0));
    VkImageViewType view_type = type == VK_IMAGE_TYPE_3D ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
    img->view = make_view(ctx, img->image, view_type, format, gpu_color_range(0, mips));
    /* Every mip has a view, a one-mip image too (its whole-image view): a chain that shrank to one level on a
     * tiny image must never hand a null view to a descriptor or an attachment. */
    for (uint32_t m = 0; m < mips && mips > 1; ++m) {
        img->mip_views[m] = make_view(ctx, img->image, view_type, format, gpu_color_range(m, 1));
        gpu_set_name(ctx, VK_OBJECT_TYPE_IMAGE_VIEW, (uint64_t)img->mip_views[m], name);
    }
    if (mips == 1) img->mip_views[0] = img->view;
    gpu_set_name(ctx, VK_OBJECT_TYPE_IMAGE, (uint64_t)img->image, name);
    gpu_set_name(ctx, VK_OBJECT_TYPE_IMAGE_VIEW, (uint64_t)img->view, name);
    gpu_set_name(ctx, VK_OBJECT_TYPE_DEVICE_MEMORY, (uint64_t)img->memory, name);
}

void gpu_image_create(const gpu_context *ctx, gpu_image *img, const char *name, VkFormat format, uint32_t width,
                      uint32_t height, uint32_t mips, VkImageUsageFlags usage)
{
    image_create(ctx, img, name, VK_IMAGE_TYPE_2D, format, width, height, 1, mips, usage);
}

void gpu_image_create_3d(const gpu_context *ctx, gpu_image *img, const char *name, VkFormat format, uint32_t width,
                         uint32_t height, uint32_t depth, VkImageUsageFlags usage)
{
    image_create(ctx, img, name, VK_IMAGE_TYPE_3D, format, width, height, depth, 1, usage);
}

void gpu_image_destroy(const gpu_context *ctx, gpu_image *img)
{
    if (!img->image) return;
    for (uint32_t m = 0; m < GPU_MAX_MIPS; ++m)
        if (img->mip_views[m] && img->mip_views[m] != img->view) vkDestroyImageView(ctx->device, img->mip_views[m], gpu_allocator(ctx->device));
    vkDestroyImageView(ctx->device, img->view, gpu_allocator(ctx->device));
    vkDestroyImage(ctx->device, img->image, gpu_allocator(ctx->device));
    vkFreeMemory(ctx->device, img->memory, gpu_allocator(ctx->device));
    *img = (gpu_image){0};
}

void gpu_buffer_create(const gpu_context *ctx, gpu_buffer *buf, const char *name, VkDeviceSize size,
                       VkBufferUsageFlags usage)
{
    *buf = (gpu_buffer){.size = size};
    /* --async-luts with a compute queue of another family: the LUT passes there and the frame here read the same
     * host-written buffers (the atmosphere's uniform block); concurrent sharing instead of an ownership transfer per
     * buffer (docs/synchronization.md §10). */
    uint32_t families[2] = {ctx->queue_family, ctx->compute_family};
    bool shared = ctx->compute_queue && ctx->compute_family != ctx->queue_family;
    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = size,
        .usage = usage,
        .sharingMode = shared ? VK_SHARING_MODE_CONCURRENT : VK_SHARING_MODE_EXCLUSIVE,
        .queueFamilyIndexCount = shared ? 2 : 0,
        .pQueueFamilyIndices = shared ? families : NULL,
    };
    VK_CHECK(vkCreateBuffer(ctx->device, &info, gpu_allocator(ctx->device), &buf->buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx->device, buf->buffer, &req);
    /* Host-visible buffers are read back (renders, LUTs) far more than written: prefer HOST_CACHED memory, which
     * the CPU reads at memory speed; uncached (write-combined) memory, what a discrete GPU typically offers as
     * plain HOST_VISIBLE | HOST_COHERENT, is read many times slower (issue 27). Cached and coherent first, then
     * coherent (as before: host writers such as the composite upload rely on it), then any host-visible type. */
    VkMemoryPropertyFlags visible = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT, coherent = VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    uint32_t type = find_memory_type(ctx, req.memoryTypeBits, visible, coherent | VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
    if (!(ctx->memory.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_CACHED_BIT))
        type = find_memory_type(ctx, req.memoryTypeBits, visible, coherent);
    buf->coherent = (ctx->memory.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
    VkMemoryAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size, .memoryTypeIndex = type};
    VK_CHECK(vkAllocateMemory(ctx->device, &alloc, gpu_allocator(ctx->device), &buf->memory));
    VK_CHECK(vkBindBufferMemory(ctx->device, buf->buffer, buf->memory, 0));
    VK_CHECK(vkMapMemory(ctx->device, buf->memory, 0, VK_WHOLE_SIZE, 0, &buf->mapped));
    gpu_set_name(ctx, VK_OBJECT_TYPE_BUFFER, (uint64_t)buf->buffer, name);
    gpu_set_name(ctx, VK_OBJECT_TYPE_DEVICE_MEMORY, (uint64_t)buf->memory, name);
}

void gpu_buffer_destroy(const gpu_context *ctx, gpu_buffer *buf)
{
    if (!buf->buffer) return;
    if (buf->mapped) vkUnmapMemory(ctx->device, buf->memory);   /* not mapped: its creation failed half-way */
    vkDestroyBuffer(ctx->device, buf->buffer, gpu_allocator(ctx->device));
    vkFreeMemory(ctx->device, buf->memory, gpu_allocator(ctx->device));
    *buf = (gpu_buffer){0};
}

void gpu_buffer_invalidate(const gpu_context *ctx, const gpu_buffer *buf)
{
    if (buf->coherent) return;
    VkMappedMemoryRange range = {
        .sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, .memory = buf->memory, .offset = 0, .size = VK_WHOLE_SIZE};
    VK_CHECK(vkInvalidateMappedMemoryRanges(ctx->device, 1, &range));
}
