#include "gpu/barrier.h"
#include <stdlib.h>
#include <string.h>

/* The usage table (cf. the sync2 examples in KhronosGroup/Vulkan-Docs "Synchronization Examples"). */
static const gpu_usage_info usages[GPU_USAGE_COUNT] = {
    [GPU_USAGE_NONE] = {"none", VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_UNDEFINED},
    [GPU_USAGE_COMPUTE_STORAGE_WRITE] = {"compute_storage_write", VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                         VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL},
    [GPU_USAGE_COMPUTE_SAMPLED] = {"compute_sampled", VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
    [GPU_USAGE_FRAGMENT_SAMPLED] = {"fragment_sampled", VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
    [GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED] = {"compute_fragment_sampled",
                                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                            VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                            VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
    [GPU_USAGE_COLOR_ATTACHMENT_WRITE] = {"color_attachment_write", VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                          VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                                          VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
    /* Load op LOAD and blending read the attachment: COLOR_ATTACHMENT_READ as well as WRITE. */
    [GPU_USAGE_COLOR_ATTACHMENT_BLEND] = {"color_attachment_blend", VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                          VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                                          VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
    [GPU_USAGE_TRANSFER_SRC] = {"transfer_src", VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL},
    [GPU_USAGE_TRANSFER_DST] = {"transfer_dst", VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL},
    [GPU_USAGE_HOST_READ] = {"host_read", VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT,
                             VK_IMAGE_LAYOUT_GENERAL},
    /* The acquire semaphore is waited on at COLOR_ATTACHMENT_OUTPUT; the first barrier on the image starts
     * from that same stage so the layout transition happens after the wait (the classic acquire mistake). */
    [GPU_USAGE_ACQUIRED] = {"acquired", VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_NONE,
                            VK_IMAGE_LAYOUT_UNDEFINED},
    /* Presentation: no stage or access in the barrier; the semaphore signalled by the submit orders it, and since
     * it is signalled at ALL_COMMANDS, this barrier's layout transition too (docs/synchronization.md §4). */
    [GPU_USAGE_PRESENT] = {"present", VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR},
    /* A compute chain that reads and writes an image in place and samples it (the compute post chain's mips and
     * tile counters): everything a compute shader can do to it, one layout. */
    [GPU_USAGE_COMPUTE_STORAGE_RW] = {"compute_storage_rw", VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                          VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                      VK_IMAGE_LAYOUT_GENERAL},
    [GPU_USAGE_CLEAR_DST] = {"clear_dst", VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                             VK_IMAGE_LAYOUT_GENERAL},
};

static FILE *trace_out;
static const char *drop_name;
static unsigned drop_count;

const gpu_usage_info *gpu_usage_get(gpu_usage usage) { return &usages[usage]; }

VkAccessFlags2 gpu_write_accesses(VkAccessFlags2 access)
{
    const VkAccessFlags2 writes = VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                  VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT |
                                  VK_ACCESS_2_HOST_WRITE_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT |
                                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    return access & writes;
}

VkImageMemoryBarrier2 gpu_image_barrier(VkImage image, VkImageSubresourceRange range, gpu_usage from, gpu_usage to,
                                        bool discard)
{
    const gpu_usage_info *f = &usages[from], *t = &usages[to];
    return (VkImageMemoryBarrier2){
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2,
        .srcStageMask = f->stage,
        .srcAccessMask = gpu_write_accesses(f->access),
        .dstStageMask = t->stage,
        .dstAccessMask = t->access,
        .oldLayout = discard ? VK_IMAGE_LAYOUT_UNDEFINED : f->layout,
        .newLayout = t->layout,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = image,
        .subresourceRange = range,
    };
}

gpu_barrier_batch gpu_barrier_batch_begin(const char *point) { return (gpu_barrier_batch){.point = point}; }

void gpu_barrier_trace(FILE *out) { trace_out = out; }
void gpu_barrier_trace_pass(const char *pass)
{
    if (trace_out) fprintf(trace_out, "pass %s\n", pass);
}
void gpu_barrier_set_drop(const char *name) { drop_name = (name && *name) ? name : NULL; }
unsigned gpu_barrier_dropped_count(void) { return drop_count; }

static bool dropped(const char *name)
{
    if (!drop_name || strcmp(drop_name, name) != 0) return false;
    ++drop_count;
    return true;
}

const char *gpu_hazard_name(gpu_usage from, gpu_usage to, bool discard, char *buf, size_t size)
{
    const gpu_usage_info *f = &usages[from], *t = &usages[to];
    bool src_writes = gpu_write_accesses(f->access) != 0;
    bool dst_writes = gpu_write_accesses(t->access) != 0;
    bool dst_reads = (t->access & ~gpu_write_accesses(t->access)) != 0;
    /* From GPU_USAGE_NONE there is no earlier access at all: at most a layout transition. */
    bool src_used = f->stage != VK_PIPELINE_STAGE_2_NONE;
    const char *kind = src_writes ? (dst_reads || !dst_writes ? "RAW" : "WAW") : (dst_writes && src_used ? "WAR" : "none");
    if (src_writes && dst_reads && dst_writes) kind = "RAW+WAW";
    VkImageLayout old_layout = discard ? VK_IMAGE_LAYOUT_UNDEFINED : f->layout;
    bool transition = old_layout != t->layout && to != GPU_USAGE_HOST_READ;
    snprintf(buf, size, "%s%s", strcmp(kind, "none") == 0 && transition ? "layout" : kind,
             transition && strcmp(kind, "none") != 0 ? "+layout" : "");
    return buf;
}

static void append(char *buf, size_t size, const char *s)
{
    size_t n = strlen(buf);
    if (n && n + 1 < size) buf[n++] = '|', buf[n] = 0;
    snprintf(buf + n, size - n, "%s", s);
}

void gpu_stage_string(VkPipelineStageFlags2 stage, char *buf, size_t size)
{
    buf[0] = 0;
    if (!stage) { snprintf(buf, size, "NONE"); return; }
    if (stage & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT) append(buf, size, "COMPUTE_SHADER");
    if (stage & VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT) append(buf, size, "FRAGMENT_SHADER");
    if (stage & VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT) append(buf, size, "COLOR_ATTACHMENT_OUTPUT");
    if (stage & VK_PIPELINE_STAGE_2_COPY_BIT) append(buf, size, "COPY");
    if (stage & VK_PIPELINE_STAGE_2_CLEAR_BIT) append(buf, size, "CLEAR");
    if (stage & VK_PIPELINE_STAGE_2_HOST_BIT) append(buf, size, "HOST");
    if (stage & VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT) append(buf, size, "ALL_COMMANDS");
}

void gpu_access_string(VkAccessFlags2 access, char *buf, size_t size)
{
    buf[0] = 0;
    if (!access) { snprintf(buf, size, "NONE"); return; }
    if (access & VK_ACCESS_2_SHADER_STORAGE_READ_BIT) append(buf, size, "SHADER_STORAGE_READ");
    if (access & VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT) append(buf, size, "SHADER_STORAGE_WRITE");
    if (access & VK_ACCESS_2_SHADER_SAMPLED_READ_BIT) append(buf, size, "SHADER_SAMPLED_READ");
    if (access & VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT) append(buf, size, "COLOR_ATTACHMENT_READ");
    if (access & VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT) append(buf, size, "COLOR_ATTACHMENT_WRITE");
    if (access & VK_ACCESS_2_TRANSFER_READ_BIT) append(buf, size, "TRANSFER_READ");
    if (access & VK_ACCESS_2_TRANSFER_WRITE_BIT) append(buf, size, "TRANSFER_WRITE");
    if (access & VK_ACCESS_2_HOST_READ_BIT) append(buf, size, "HOST_READ");
}

const char *gpu_layout_name(VkImageLayout layout)
{
    switch (layout) {
    case VK_IMAGE_LAYOUT_UNDEFINED: return "UNDEFINED";
    case VK_IMAGE_LAYOUT_GENERAL: return "GENERAL";
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: return "SHADER_READ_ONLY_OPTIMAL";
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL: return "COLOR_ATTACHMENT_OPTIMAL";
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return "TRANSFER_SRC_OPTIMAL";
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return "TRANSFER_DST_OPTIMAL";
    case VK_IMAGE_LAYOUT_PRESENT_SRC_KHR: return "PRESENT_SRC_KHR";
    default: return "OTHER";
    }
}

static void trace_line(const char *name, const char *point, const char *resource, const char *mips,
                       VkImageLayout old_layout, VkImageLayout new_layout, VkPipelineStageFlags2 src_stage,
                       VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access,
                       const char *hazard, bool was_dropped)
{
    if (!trace_out) return;
    char ss[128], sa[128], ds[128], da[128];
    gpu_stage_string(src_stage, ss, sizeof ss);
    gpu_access_string(src_access, sa, sizeof sa);
    gpu_stage_string(dst_stage, ds, sizeof ds);
    gpu_access_string(dst_access, da, sizeof da);
    fprintf(trace_out, "barrier %s point=%s resource=%s mips=%s layout=%s->%s src=%s/%s dst=%s/%s hazard=%s%s\n",
            name, point, resource, mips, gpu_layout_name(old_layout), gpu_layout_name(new_layout), ss, sa, ds, da,
            hazard, was_dropped ? " DROPPED" : "");
}

void gpu_barrier_add_image(gpu_barrier_batch *b, const char *name, const char *resource, VkImage image,
                           VkImageSubresourceRange range, gpu_usage from, gpu_usage to, bool discard)
{
    VkImageMemoryBarrier2 barrier = gpu_image_barrier(image, range, from, to, discard);
    char hazard[32], mips[32];
    gpu_hazard_name(from, to, discard, hazard, sizeof hazard);
    if (range.levelCount == 1) snprintf(mips, sizeof mips, "%u", range.baseMipLevel);
    else snprintf(mips, sizeof mips, "%u-%u", range.baseMipLevel, range.baseMipLevel + range.levelCount - 1);
    bool drop = dropped(name);
    trace_line(name, b->point, resource, mips, barrier.oldLayout, barrier.newLayout, barrier.srcStageMask,
               barrier.srcAccessMask, barrier.dstStageMask, barrier.dstAccessMask, hazard, drop);
    if (drop) return;
    if (b->image_count == GPU_BATCH_MAX) {
        fprintf(stderr, "vksky: internal error: barrier batch '%s' is full\n", b->point);
        exit(1);
    }
    b->images[b->image_count++] = barrier;
}

void gpu_barrier_add_buffer(gpu_barrier_batch *b, const char *name, const char *resource, VkBuffer buffer,
                            gpu_usage from, gpu_usage to)
{
    const gpu_usage_info *f = &usages[from], *t = &usages[to];
    VkBufferMemoryBarrier2 barrier = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
        .srcStageMask = f->stage,
        .srcAccessMask = gpu_write_accesses(f->access),
        .dstStageMask = t->stage,
        .dstAccessMask = t->access,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .buffer = buffer,
        .offset = 0,
        .size = VK_WHOLE_SIZE,
    };
    char hazard[32];
    gpu_hazard_name(from, to, false, hazard, sizeof hazard);
    bool drop = dropped(name);
    trace_line(name, b->point, resource, "-", VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_UNDEFINED,
               barrier.srcStageMask, barrier.srcAccessMask, barrier.dstStageMask, barrier.dstAccessMask, "RAW", drop);
    (void)hazard;
    if (drop) return;
    b->buffers[b->buffer_count++] = barrier;
}

void gpu_barrier_flush(VkCommandBuffer cmd, gpu_barrier_batch *b)
{
    if (b->image_count == 0 && b->buffer_count == 0) return;
    VkDependencyInfo dep = {
        .sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO,
        .imageMemoryBarrierCount = b->image_count,
        .pImageMemoryBarriers = b->images,
        .bufferMemoryBarrierCount = b->buffer_count,
        .pBufferMemoryBarriers = b->buffers,
    };
    vkCmdPipelineBarrier2(cmd, &dep);
    b->image_count = b->buffer_count = 0;
}
