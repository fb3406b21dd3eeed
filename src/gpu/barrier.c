#include "gpu/barrier.h"
#include <stdarg.h>
#include "gpu/fail.h"   /* an overflowing batch is a bug, reported as every failure below the API is */
#include <stdarg.h>
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
    /* Storage buffers (the exposure meter's): no layout. */
    [GPU_USAGE_COMPUTE_STORAGE_READ] = {"compute_storage_read", VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL},
    [GPU_USAGE_SHADER_STORAGE_READ] = {"shader_storage_read",
                                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL},
    [GPU_USAGE_COMPUTE_STORAGE_READ_WRITE] = {"compute_storage_read_write", VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                              VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                              VK_IMAGE_LAYOUT_GENERAL},
};

static FILE *trace_out;
static FILE *pass_out;   /* --trace-passes */
/* The sink a context's recording thread has bound (gpu_trace_bind): the library's per-context traces. Thread-local:
 * two contexts recorded on two threads each see their own. NULL: the process-wide streams above (the CLI). */
static _Thread_local const gpu_trace_sink *bound;
static const char *drop_name;
static unsigned drop_count;
/* The mask mutation (gpu_barrier_set_weaken): which barrier, which field, the mask it gets instead. */
enum { WEAKEN_OFF = -1, WEAKEN_SRC_STAGE, WEAKEN_SRC_ACCESS, WEAKEN_DST_STAGE, WEAKEN_DST_ACCESS, WEAKEN_FIELDS };
static const char *const weaken_fields[WEAKEN_FIELDS] = {"srcstage", "srcaccess", "dststage", "dstaccess"};
static char weaken_name[128];
static int weaken_field = WEAKEN_OFF;
static VkFlags64 weaken_mask;
static unsigned weaken_count;

/* Stage and access names as the trace prints them (and as a weakening spec names them), in printing order. */
typedef struct flag_name {
    VkFlags64 bit;
    const char *name;
} flag_name;
static const flag_name stage_names[] = {
    {VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, "TOP_OF_PIPE"},
    {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, "COMPUTE_SHADER"},
    {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT, "EARLY_FRAGMENT_TESTS"},
    {VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, "LATE_FRAGMENT_TESTS"},
    {VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, "FRAGMENT_SHADER"},
    {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, "COLOR_ATTACHMENT_OUTPUT"},
    {VK_PIPELINE_STAGE_2_COPY_BIT, "COPY"},
    {VK_PIPELINE_STAGE_2_CLEAR_BIT, "CLEAR"},
    {VK_PIPELINE_STAGE_2_HOST_BIT, "HOST"},
    {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, "ALL_COMMANDS"},
    {VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, "BOTTOM_OF_PIPE"},
};
static const flag_name access_names[] = {
    {VK_ACCESS_2_SHADER_STORAGE_READ_BIT, "SHADER_STORAGE_READ"},
    {VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, "SHADER_STORAGE_WRITE"},
    {VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, "SHADER_SAMPLED_READ"},
    {VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, "COLOR_ATTACHMENT_READ"},
    {VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, "COLOR_ATTACHMENT_WRITE"},
    {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, "DEPTH_STENCIL_ATTACHMENT_READ"},
    {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, "DEPTH_STENCIL_ATTACHMENT_WRITE"},
    {VK_ACCESS_2_TRANSFER_READ_BIT, "TRANSFER_READ"},
    {VK_ACCESS_2_TRANSFER_WRITE_BIT, "TRANSFER_WRITE"},
    {VK_ACCESS_2_HOST_READ_BIT, "HOST_READ"},
    {VK_ACCESS_2_MEMORY_READ_BIT, "MEMORY_READ"},
    {VK_ACCESS_2_MEMORY_WRITE_BIT, "MEMORY_WRITE"},
};
#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

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
void gpu_barrier_trace_passes(FILE *out) { pass_out = out; }
const gpu_trace_sink *gpu_trace_bind(const gpu_trace_sink *sink)
{
    const gpu_trace_sink *was = bound;
    bound = sink;
    return was;
}

/* Is a line of this kind wanted (a pass line: with either trace on; any other: the barrier trace's)? */
static bool tracing(bool pass_line)
{
    if (bound) return bound->line && (bound->barriers || (pass_line && bound->passes));
    return trace_out || (pass_line && pass_out);
}

/* One trace line (no newline in `format`) to the bound sink, else to the process-wide stream. */
static void __attribute__((format(printf, 2, 3))) trace_emit(bool pass_line, const char *format, ...)
{
    if (!tracing(pass_line)) return;
    va_list args;
    va_start(args, format);
    if (bound) {
        char text[1024];   /* a barrier line: four masks of at most 160 characters, names, layouts */
        vsnprintf(text, sizeof text, format, args);
        bound->line(bound->user, text);
    } else {
        FILE *out = trace_out ? trace_out : pass_out;
        vfprintf(out, format, args);
        fputc('\n', out);
    }
    va_end(args);
}

void gpu_barrier_trace_pass(const char *pass) { trace_emit(true, "pass %s", pass); }
void gpu_barrier_trace_commands(void) { trace_emit(false, "commands"); }
void gpu_barrier_set_drop(const char *name) { drop_name = (name && *name) ? name : NULL; }
unsigned gpu_barrier_dropped_count(void) { return drop_count; }
unsigned gpu_barrier_weakened_count(void) { return weaken_count; }

static bool dropped(const char *name)
{
    if (!drop_name || strcmp(drop_name, name) != 0) return false;
    ++drop_count;
    return true;
}

/* "A|B|C" -> the bits, from one of the name tables; false on an unknown name. */
static bool parse_mask(const char *text, const flag_name *names, size_t count, VkFlags64 *out)
{
    *out = 0;
    if (strcmp(text, "NONE") == 0) return true;
    while (*text) {
        size_t len = strcspn(text, "|");
        bool found = false;
        for (size_t i = 0; i < count; ++i)
            if (strlen(names[i].name) == len && strncmp(names[i].name, text, len) == 0) *out |= names[i].bit, found = true;
        if (!found) return false;
        text += len + (text[len] == '|');
    }
    return true;
}

bool gpu_barrier_set_weaken(const char *spec, char *why, size_t why_size)
{
    weaken_field = WEAKEN_OFF;
    if (!spec || !*spec) return true;
    const char *colon = strchr(spec, ':');
    if (!colon || colon == spec || (size_t)(colon - spec) >= sizeof weaken_name) {
        snprintf(why, why_size, "'%s' is not <barrier name>:<field>[=MASK]", spec);
        return false;
    }
    const char *field = colon + 1, *eq = strchr(field, '=');
    size_t flen = eq ? (size_t)(eq - field) : strlen(field);
    int which = WEAKEN_OFF;
    for (int i = 0; i < WEAKEN_FIELDS; ++i)
        if (strlen(weaken_fields[i]) == flen && strncmp(weaken_fields[i], field, flen) == 0) which = i;
    if (which == WEAKEN_OFF) {
        snprintf(why, why_size, "field '%.*s' is not one of srcstage, srcaccess, dststage, dstaccess", (int)flen, field);
        return false;
    }
    bool stage = which == WEAKEN_SRC_STAGE || which == WEAKEN_DST_STAGE;
    VkFlags64 mask = 0;
    if (eq && !parse_mask(eq + 1, stage ? stage_names : access_names, stage ? COUNT(stage_names) : COUNT(access_names),
                          &mask)) {
        snprintf(why, why_size, "mask '%s' is not NONE or %s names joined by '|' (as --trace-barriers prints them)",
                 eq + 1, stage ? "stage" : "access");
        return false;
    }
    memcpy(weaken_name, spec, (size_t)(colon - spec));
    weaken_name[colon - spec] = 0;
    weaken_field = which;
    weaken_mask = mask;
    return true;
}

/* Applies the mutation to one barrier's masks if it names this barrier: the field it weakened, else NULL. A stage
 * mask with no stage that performs accesses (NONE, TOP_OF_PIPE, BOTTOM_OF_PIPE) takes that side's accesses too. */
static const char *weaken(const char *name, VkPipelineStageFlags2 *ss, VkAccessFlags2 *sa, VkPipelineStageFlags2 *ds,
                          VkAccessFlags2 *da)
{
    if (weaken_field == WEAKEN_OFF || strcmp(name, weaken_name) != 0) return NULL;
    const VkPipelineStageFlags2 no_access = VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT | VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT;
    ++weaken_count;
    switch (weaken_field) {
    case WEAKEN_SRC_STAGE: *ss = weaken_mask; if (!(*ss & ~no_access)) *sa = 0; break;
    case WEAKEN_SRC_ACCESS: *sa = weaken_mask; break;
    case WEAKEN_DST_STAGE: *ds = weaken_mask; if (!(*ds & ~no_access)) *da = 0; break;
    default: *da = weaken_mask; break;
    }
    return weaken_fields[weaken_field];
}

/* The presentation engine reads the image before it is acquired and after it is presented. */
static bool usage_reads(gpu_usage u)
{
    VkAccessFlags2 a = usages[u].access;
    return (a & ~gpu_write_accesses(a)) != 0 || u == GPU_USAGE_PRESENT || u == GPU_USAGE_ACQUIRED;
}
static bool usage_writes(gpu_usage u) { return gpu_write_accesses(usages[u].access) != 0; }

static const char *hazards(gpu_usage from, gpu_usage to, bool transition, char *buf, size_t size)
{
    bool raw = usage_writes(from) && usage_reads(to);
    bool war = usage_reads(from) && usage_writes(to);
    bool waw = usage_writes(from) && usage_writes(to);
    snprintf(buf, size, "%s%s%s%s%s%s%s", raw ? "RAW" : "", raw && war ? "+" : "", war ? "WAR" : "",
             (raw || war) && waw ? "+" : "", waw ? "WAW" : "", (raw || war || waw) && transition ? "+" : "",
             transition ? "layout" : "");
    if (!buf[0]) snprintf(buf, size, "none");
    return buf;
}

const char *gpu_hazard_name(gpu_usage from, gpu_usage to, bool discard, char *buf, size_t size)
{
    VkImageLayout old_layout = discard ? VK_IMAGE_LAYOUT_UNDEFINED : usages[from].layout;
    return hazards(from, to, old_layout != usages[to].layout, buf, size);
}

const char *gpu_hazard_name_nolayout(gpu_usage from, gpu_usage to, char *buf, size_t size)
{
    return hazards(from, to, false, buf, size);
}

static void append(char *buf, size_t size, const char *s)
{
    size_t n = strlen(buf);
    if (n && n + 1 < size) buf[n++] = '|', buf[n] = 0;
    snprintf(buf + n, size - n, "%s", s);
}

static void flags_string(VkFlags64 flags, const flag_name *names, size_t count, char *buf, size_t size)
{
    buf[0] = 0;
    if (!flags) { snprintf(buf, size, "NONE"); return; }
    for (size_t i = 0; i < count; ++i)
        if (flags & names[i].bit) append(buf, size, names[i].name);
}

void gpu_stage_string(VkPipelineStageFlags2 stage, char *buf, size_t size)
{
    flags_string(stage, stage_names, COUNT(stage_names), buf, size);
}

void gpu_access_string(VkAccessFlags2 access, char *buf, size_t size)
{
    flags_string(access, access_names, COUNT(access_names), buf, size);
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
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL: return "DEPTH_STENCIL_ATTACHMENT_OPTIMAL";
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL: return "DEPTH_STENCIL_READ_ONLY_OPTIMAL";
    case VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL: return "DEPTH_ATTACHMENT_OPTIMAL";
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL: return "DEPTH_READ_ONLY_OPTIMAL";
    case VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL: return "ATTACHMENT_OPTIMAL";
    case VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL: return "READ_ONLY_OPTIMAL";
    default: return "OTHER";
    }
}

/* One trace line per barrier, as it is added to its batch: what it orders, and whether the drop or the mutation
 * switch changed it. mips "-": a buffer; "*": a global memory barrier (no resource; `resource` says what for). */
static void trace_line(const char *name, const char *point, const char *resource, const char *mips,
                       VkImageLayout old_layout, VkImageLayout new_layout, VkPipelineStageFlags2 src_stage,
                       VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access,
                       const char *hazard, bool was_dropped, const char *weakened)
{
    if (!tracing(false)) return;
    char ss[160], sa[160], ds[160], da[160];
    gpu_stage_string(src_stage, ss, sizeof ss);
    gpu_access_string(src_access, sa, sizeof sa);
    gpu_stage_string(dst_stage, ds, sizeof ds);
    gpu_access_string(dst_access, da, sizeof da);
    trace_emit(false, "barrier %s point=%s resource=%s mips=%s layout=%s->%s src=%s/%s dst=%s/%s hazard=%s%s%s%s",
            name, point, resource, mips, gpu_layout_name(old_layout), gpu_layout_name(new_layout), ss, sa, ds, da,
            hazard, was_dropped ? " DROPPED" : "", weakened ? " WEAKENED=" : "", weakened ? weakened : "");
}

void gpu_barrier_add_image(gpu_barrier_batch *b, const char *name, const char *resource, VkImage image,
                           VkImageSubresourceRange range, gpu_usage from, gpu_usage to, bool discard)
{
    VkImageMemoryBarrier2 barrier = gpu_image_barrier(image, range, from, to, discard);
    const char *weakened = weaken(name, &barrier.srcStageMask, &barrier.srcAccessMask, &barrier.dstStageMask,
                                  &barrier.dstAccessMask);
    char hazard[40], mips[32];
    gpu_hazard_name(from, to, discard, hazard, sizeof hazard);
    if (range.levelCount == 1) snprintf(mips, sizeof mips, "%u", range.baseMipLevel);
    else snprintf(mips, sizeof mips, "%u-%u", range.baseMipLevel, range.baseMipLevel + range.levelCount - 1);
    bool drop = dropped(name);
    trace_line(name, b->point, resource, mips, barrier.oldLayout, barrier.newLayout, barrier.srcStageMask,
               barrier.srcAccessMask, barrier.dstStageMask, barrier.dstAccessMask, hazard, drop, weakened);
    if (drop) return;
    if (b->image_count == GPU_BATCH_MAX) {
        char text[160];   /* a bug of ours: the CLI prints it and exits 1; the library returns an error */
        snprintf(text, sizeof text, "internal error: barrier batch '%s' is full", b->point);
        gpu_fail(VK_ERROR_UNKNOWN, text);
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
    const char *weakened = weaken(name, &barrier.srcStageMask, &barrier.srcAccessMask, &barrier.dstStageMask,
                                  &barrier.dstAccessMask);
    char hazard[40];
    gpu_hazard_name_nolayout(from, to, hazard, sizeof hazard);
    bool drop = dropped(name);
    trace_line(name, b->point, resource, "-", VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_UNDEFINED,
               barrier.srcStageMask, barrier.srcAccessMask, barrier.dstStageMask, barrier.dstAccessMask, hazard, drop,
               weakened);
    if (drop) return;
    if (b->buffer_count == COUNT(b->buffers)) {
        char text[160];   /* a bug of ours: the CLI prints it and exits 1; the library returns an error */
        snprintf(text, sizeof text, "internal error: barrier batch '%s' has too many buffers", b->point);
        gpu_fail(VK_ERROR_UNKNOWN, text);
    }
    b->buffers[b->buffer_count++] = barrier;
}

void gpu_barrier_add_memory(gpu_barrier_batch *b, const char *name, const char *resource, gpu_usage from,
                            gpu_usage to)
{
    const gpu_usage_info *f = &usages[from], *t = &usages[to];
    VkMemoryBarrier2 barrier = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
        .srcStageMask = f->stage,
        .srcAccessMask = gpu_write_accesses(f->access),
        .dstStageMask = t->stage,
        .dstAccessMask = t->access,
    };
    const char *weakened = weaken(name, &barrier.srcStageMask, &barrier.srcAccessMask, &barrier.dstStageMask,
                                  &barrier.dstAccessMask);
    char hazard[40];
    gpu_hazard_name_nolayout(from, to, hazard, sizeof hazard);
    bool drop = dropped(name);
    trace_line(name, b->point, resource, "*", VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_UNDEFINED,
               barrier.srcStageMask, barrier.srcAccessMask, barrier.dstStageMask, barrier.dstAccessMask, hazard, drop,
               weakened);
    if (drop) return;
    if (b->memory_count == COUNT(b->memory)) {
        char text[160];   /* a bug of ours: the CLI prints it and exits 1; the library returns an error */
        snprintf(text, sizeof text, "internal error: barrier batch '%s' has too many global barriers", b->point);
        gpu_fail(VK_ERROR_UNKNOWN, text);
    }
    b->memory[b->memory_count++] = barrier;
}

void gpu_barrier_flush(VkCommandBuffer cmd, gpu_barrier_batch *b)
{
    if (b->image_count == 0 && b->buffer_count == 0 && b->memory_count == 0) return;
    VkDependencyInfo dep = {
        .sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO,
        .memoryBarrierCount = b->memory_count,
        .pMemoryBarriers = b->memory,
        .bufferMemoryBarrierCount = b->buffer_count,
        .pBufferMemoryBarriers = b->buffers,
        .imageMemoryBarrierCount = b->image_count,
        .pImageMemoryBarriers = b->images,
    };
    /* One trace line per call: how many barrier calls a frame makes is read from the trace (docs, §2). */
    trace_emit(false, "batch point=%s images=%u buffers=%u memory=%u", b->point, b->image_count, b->buffer_count,
               b->memory_count);
    vkCmdPipelineBarrier2(cmd, &dep);
    b->image_count = b->buffer_count = b->memory_count = 0;
}

/* The library's host images: one side of the barrier is the host's own use (vksky_image_use), given as a value, not
 * a row of the usage table. Named, traced, droppable and weakenable like every other barrier; an access-free host
 * use (the presentation engine, a use the host does not name) counts as a reader, as GPU_USAGE_PRESENT does. */
void gpu_barrier_add_image_info(gpu_barrier_batch *b, const char *name, const char *resource, VkImage image,
                                VkImageSubresourceRange range, gpu_usage_info from, gpu_usage_info to, bool discard)
{
    VkImageMemoryBarrier2 barrier = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2,
        .srcStageMask = from.stage,
        .srcAccessMask = gpu_write_accesses(from.access),
        .dstStageMask = to.stage,
        .dstAccessMask = to.access,
        .oldLayout = discard ? VK_IMAGE_LAYOUT_UNDEFINED : from.layout,
        .newLayout = to.layout,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = image,
        .subresourceRange = range,
    };
    const char *weakened = weaken(name, &barrier.srcStageMask, &barrier.srcAccessMask, &barrier.dstStageMask,
                                  &barrier.dstAccessMask);
    bool from_writes = gpu_write_accesses(from.access) != 0, to_writes = gpu_write_accesses(to.access) != 0;
    bool from_reads = (from.access & ~gpu_write_accesses(from.access)) != 0 || from.access == 0;
    bool to_reads = (to.access & ~gpu_write_accesses(to.access)) != 0 || to.access == 0;
    bool raw = from_writes && to_reads, war = from_reads && to_writes, waw = from_writes && to_writes;
    bool transition = barrier.oldLayout != barrier.newLayout;
    char hazard[40];
    snprintf(hazard, sizeof hazard, "%s%s%s%s%s%s%s", raw ? "RAW" : "", raw && war ? "+" : "", war ? "WAR" : "",
             (raw || war) && waw ? "+" : "", waw ? "WAW" : "", (raw || war || waw) && transition ? "+" : "",
             transition ? "layout" : "");
    if (!hazard[0]) snprintf(hazard, sizeof hazard, "none");
    bool drop = dropped(name);
    trace_line(name, b->point, resource, "0", barrier.oldLayout, barrier.newLayout, barrier.srcStageMask,
               barrier.srcAccessMask, barrier.dstStageMask, barrier.dstAccessMask, hazard, drop, weakened);
    if (drop || b->image_count == GPU_BATCH_MAX) return;   /* a full batch: 16 images, the frame uses at most 6 */
    b->images[b->image_count++] = barrier;
}

/* A queue-family ownership transfer's half (docs/synchronization.md §10): the barrier as add_image_info builds it,
 * with the two families set, and a `qfot` trace line after it saying which half this is. */
void gpu_barrier_add_image_qfot(gpu_barrier_batch *b, const char *name, const char *resource, VkImage image,
                                VkImageSubresourceRange range, gpu_usage_info from, gpu_usage_info to,
                                uint32_t src_family, uint32_t dst_family, bool release)
{
    uint32_t before = b->image_count;
    gpu_barrier_add_image_info(b, name, resource, image, range, from, to, false);
    if (b->image_count > before) {
        b->images[before].srcQueueFamilyIndex = src_family;
        b->images[before].dstQueueFamilyIndex = dst_family;
    }
    if (trace_out)
        fprintf(trace_out, "qfot %s %s family=%u->%u (%s)\n", name, release ? "release" : "acquire", src_family,
                dst_family, release ? "recorded on the source queue; its destination stage and access are ignored"
                                    : "recorded on the destination queue; its source stage and access are NONE");
}

bool gpu_barrier_drops(const char *name) { return dropped(name); }

void gpu_barrier_trace_note(const char *format, ...)
{
    if (!trace_out) return;
    va_list ap;
    va_start(ap, format);
    vfprintf(trace_out, format, ap);
    va_end(ap);
    fputc('\n', trace_out);
}
