/* Barriers from named usages (synchronization2).
 *
 * A usage says how a pass touches a resource: the pipeline stage, the access and, for images, the layout. A
 * barrier is built from (resource, subresource range, from-usage, to-usage): the source side contributes only
 * its *write* accesses (there is nothing to make available from a read), the destination side its reads and
 * writes. Barriers meant for one point of the frame are collected in a batch and recorded by one
 * vkCmdPipelineBarrier2.
 *
 * Every barrier has a stable name (e.g. "transmittance.write_to_sample"). `--trace-barriers` prints one line per
 * barrier as it is recorded and one `batch` line per vkCmdPipelineBarrier2; env VKSKY_DROP_BARRIER=<name> leaves
 * that one barrier out, and VKSKY_WEAKEN_BARRIER=<name>:<field>[=MASK] weakens one field of it (the masks'
 * proof, docs/synchronization.md appendix B), so a test can show what synchronization validation reports. */
#ifndef VKSKY_GPU_BARRIER_H
#define VKSKY_GPU_BARRIER_H
#include <volk.h>
#include <stdbool.h>
#include <stdio.h>

typedef enum gpu_usage {
    GPU_USAGE_NONE,                     /* not used yet / contents not needed */
    GPU_USAGE_COMPUTE_STORAGE_WRITE,    /* imageStore from a compute shader (GENERAL) */
    GPU_USAGE_COMPUTE_SAMPLED,          /* texture() in a compute shader */
    GPU_USAGE_FRAGMENT_SAMPLED,         /* texture() in a fragment shader */
    GPU_USAGE_COMPUTE_FRAGMENT_SAMPLED, /* sampled by compute and fragment shaders alike */
    GPU_USAGE_COLOR_ATTACHMENT_WRITE,   /* colour attachment, load op CLEAR/DONT_CARE, no blending */
    GPU_USAGE_COLOR_ATTACHMENT_BLEND,   /* colour attachment, load op LOAD and blending: reads and writes */
    GPU_USAGE_TRANSFER_SRC,             /* copy source */
    GPU_USAGE_TRANSFER_DST,             /* copy destination */
    GPU_USAGE_HOST_READ,                /* read by the CPU after the fence (buffers) */
    GPU_USAGE_ACQUIRED,                 /* swapchain image just acquired: the acquire semaphore's wait stage */
    GPU_USAGE_PRESENT,                  /* handed to the presentation engine */
    GPU_USAGE_COMPUTE_STORAGE_RW,       /* imageLoad/imageStore/atomics and texture() in compute shaders (GENERAL) */
    GPU_USAGE_CLEAR_DST,                /* vkCmdClearColorImage destination, kept in GENERAL */
    GPU_USAGE_COMPUTE_STORAGE_READ,     /* a storage buffer read by a compute shader */
    GPU_USAGE_SHADER_STORAGE_READ,      /* a storage buffer read by compute or fragment shaders (a tone map, either) */
    GPU_USAGE_COMPUTE_STORAGE_READ_WRITE, /* a storage buffer read and written by one compute dispatch */
    GPU_USAGE_COUNT
} gpu_usage;

typedef struct gpu_usage_info {
    const char *name;
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
    VkImageLayout layout;
} gpu_usage_info;

const gpu_usage_info *gpu_usage_get(gpu_usage usage);
/* Write accesses among `access` (the only ones a barrier's source side needs). */
VkAccessFlags2 gpu_write_accesses(VkAccessFlags2 access);

/* Build one image barrier. `discard`: the old contents are not needed (old layout UNDEFINED), but the source
 * stage still waits for the previous user (a write-after-read or write-after-write hazard). */
VkImageMemoryBarrier2 gpu_image_barrier(VkImage image, VkImageSubresourceRange range, gpu_usage from, gpu_usage to,
                                        bool discard);

#define GPU_BATCH_MAX 16
typedef struct gpu_barrier_batch {
    const char *point;                  /* where in the frame, for the trace */
    VkImageMemoryBarrier2 images[GPU_BATCH_MAX];
    VkBufferMemoryBarrier2 buffers[4];
    VkMemoryBarrier2 memory[4];         /* global barriers: every resource the stages touch */
    uint32_t image_count, buffer_count, memory_count;
} gpu_barrier_batch;

gpu_barrier_batch gpu_barrier_batch_begin(const char *point);
void gpu_barrier_add_image(gpu_barrier_batch *b, const char *name, const char *resource, VkImage image,
                           VkImageSubresourceRange range, gpu_usage from, gpu_usage to, bool discard);
void gpu_barrier_add_buffer(gpu_barrier_batch *b, const char *name, const char *resource, VkBuffer buffer,
                            gpu_usage from, gpu_usage to);
/* The same with the usages given as values (the library's host images: vksky_image_use before and after). */
void gpu_barrier_add_image_info(gpu_barrier_batch *b, const char *name, const char *resource, VkImage image,
                                VkImageSubresourceRange range, gpu_usage_info from, gpu_usage_info to, bool discard);
/* A global memory barrier (VkMemoryBarrier2): no resource, no layout. The canonical compute -> compute pattern on
 * images that stay in GENERAL (and on buffers): it orders every access of the source usage before every access
 * of the destination usage, whatever the resource. `resource` only labels the trace ("what it is for"). */
void gpu_barrier_add_memory(gpu_barrier_batch *b, const char *name, const char *resource, gpu_usage from,
                            gpu_usage to);
/* Records the batch (one vkCmdPipelineBarrier2, traced as one `batch` line); nothing if it is empty (every
 * barrier in it dropped). */
void gpu_barrier_flush(VkCommandBuffer cmd, gpu_barrier_batch *b);

/* One half of a queue-family ownership transfer (the async LUTs, docs/synchronization.md §10): `release` recorded on
 * the queue of src_family (its destination stage/access should be NONE: ignored), else the acquire, recorded on the
 * queue of dst_family (its source stage/access NONE), both with the same layouts and range. Traced as the barrier's
 * line and a `qfot` line. */
void gpu_barrier_add_image_qfot(gpu_barrier_batch *b, const char *name, const char *resource, VkImage image,
                                VkImageSubresourceRange range, gpu_usage_info from, gpu_usage_info to,
                                uint32_t src_family, uint32_t dst_family, bool release);
/* True (and counted as a drop) when VKSKY_DROP_BARRIER names `name`: for the synchronization that is not a
 * barrier (a semaphore wait), so its drop test works the same way. */
bool gpu_barrier_drops(const char *name);
/* A free-form line in the barrier trace (semaphores, queue choices); nothing when the trace is off. */
void gpu_barrier_trace_note(const char *format, ...) __attribute__((format(printf, 1, 2)));

/* Trace / drop controls (process-wide; set once by the app before recording). */
void gpu_barrier_trace(FILE *out);
/* A trace owned by a context (the library's vksky_context_set_trace): lines without their newline to `line`;
 * `barriers` the barrier trace (passes, commands, barriers, batches), `passes` the pass list alone. */
typedef struct gpu_trace_sink {
    void (*line)(void *user, const char *text);
    void *user;
    bool barriers, passes;
} gpu_trace_sink;
/* Sends the calling thread's trace lines to `sink` instead of the process-wide streams (NULL: back to them) while a
 * context records; returns the sink bound before, for the caller to restore. */
const gpu_trace_sink *gpu_trace_bind(const gpu_trace_sink *sink);
/* The pass list alone (--trace-passes): a line "pass <name>" where each pass begins, to `out` (NULL: off). */
void gpu_barrier_trace_passes(FILE *out);
/* The one place a pass is traced (called by gpu_label_begin, which every pass and copy of a frame opens): a line
 * "pass <name>" into the barrier trace if it is on, so that it reads as the frame (passes and the barriers between
 * them), else into the pass list's stream; printed once even when both are on. */
void gpu_barrier_trace_pass(const char *pass);
/* With the trace on, a line "commands" where a command buffer begins (called by gpu_begin_commands): barriers of
 * two submissions can never share a call. */
void gpu_barrier_trace_commands(void);
/* Name of the barrier to drop (NULL: none). Returns how many barriers were dropped so far. */
void gpu_barrier_set_drop(const char *name);
unsigned gpu_barrier_dropped_count(void);
/* The mask mutation: "<name>:<field>[=MASK]", field srcstage | srcaccess | dststage | dstaccess, MASK stage or
 * access names as the trace prints them joined by '|' (default NONE). A stage weakened to NONE takes its access
 * mask with it (an access needs a stage that performs it). NULL or "" turns it off. Returns false (and says why
 * in `why`) for a malformed spec. */
bool gpu_barrier_set_weaken(const char *spec, char *why, size_t why_size);
unsigned gpu_barrier_weakened_count(void);

/* The hazards a from -> to barrier prevents, computed from the two usages' accesses: RAW (the source writes, the
 * destination reads), WAR (the source reads, the destination writes), WAW (both write), joined by '+' in that
 * order, then "+layout" for an image whose layout changes; "layout" alone or "none" when no access conflicts.
 * The presentation engine counts as a reader (GPU_USAGE_PRESENT, GPU_USAGE_ACQUIRED). */
const char *gpu_hazard_name(gpu_usage from, gpu_usage to, bool discard, char *buf, size_t size);
/* The same for a buffer or a global barrier: no layout. */
const char *gpu_hazard_name_nolayout(gpu_usage from, gpu_usage to, char *buf, size_t size);
/* Human-readable stage and access masks (for the trace and docs). */
void gpu_stage_string(VkPipelineStageFlags2 stage, char *buf, size_t size);
void gpu_access_string(VkAccessFlags2 access, char *buf, size_t size);
const char *gpu_layout_name(VkImageLayout layout);
#endif
