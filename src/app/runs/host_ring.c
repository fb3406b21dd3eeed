/* The host's readback ring (host_ring.h). The producer is the caller's thread: it records (vksky_record) and submits.
 * The consumers are threads of ours (one, or several encoding frames at once: issue 27): each waits
 * for its frame's fence, reads the slot (vksky_renderer_get_readback_slot, which touches only that slot: it may run
 * beside the recording of other slots and beside other consumers) and hands the pixels on. Frames retire in order. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "app/runs/host_ring.h"
#include "app/runs/ring_order.h"
#include "app/runs/stage_times.h"
#include "app/runs/startup.h"
#include <stdlib.h>
#include <string.h>
#include <time.h>

int host_ring_slots_wanted(void)
{
    const char *env = getenv("VKSKY_READBACK_SLOTS");
    int n = env && *env ? atoi(env) : 2;
    if (n < 2) return 0;
    return n > HOST_RING_MAX_SLOTS ? HOST_RING_MAX_SLOTS : n;
}

int host_ring_consumers_wanted(long pixels) { return ring_consumers_wanted(pixels, HOST_RING_MAX_CONSUMERS); }

int host_record(vksky_renderer *r, VkCommandBuffer cmd, const host_view *v, uint32_t slot)
{
    /* The view as the command line gave it: the sky pass's own rays from yaw, pitch and fov. */
    vksky_frame_view given = {.type = VKSKY_STRUCTURE_TYPE_FRAME_VIEW, .yaw_deg = v->yaw_deg,
                              .pitch_deg = v->pitch_deg, .fov_deg = v->fov_deg};
    /* An environment map (one band: the whole image, or a band of it): the projection gives each pixel its direction,
     * not the view. A perspective band keeps the view (chained after the band). */
    bool is_map = v->projection != VKSKY_PROJECTION_TYPE_PERSPECTIVE;
    vksky_frame_band map = {.type = VKSKY_STRUCTURE_TYPE_FRAME_BAND, .next = is_map ? NULL : &given,
                            .projection = v->projection, .whole_width = v->whole_width,
                            .whole_height = v->whole_height, .first_row = v->first_row,
                            .meter_first_row = v->meter_first_row, .meter_rows = v->meter_rows};
    const void *placed = is_map || v->band ? (const void *)&map : (const void *)&given;
    /* The slot's pair of readback buffers; auto exposure's result beside it (one per frame in flight). The host's own
     * image instead (v->target): no readback. */
    vksky_readback_target target = {.type = VKSKY_STRUCTURE_TYPE_READBACK_TARGET, .next = placed, .slot = slot,
                                    .follows_frame = v->follows_frame};
    const void *head = v->target ? placed : (const void *)&target;
    vksky_auto_exposure metered = {.type = VKSKY_STRUCTURE_TYPE_AUTO_EXPOSURE, .next = head, .slot = slot};
    vksky_frame frame = {.next = v->auto_exposure ? (const void *)&metered : head, .exposure = v->exposure,
                         .force_luts = v->force_luts};
    vksky_frame_display display;
    if (v->display) {
        display = *v->display;
        display.next = frame.next;
        frame.next = &display;
    }
    vksky_frame_spectral_sum sum;
    if (v->spectral_sum) {   /* chained first */
        sum = *v->spectral_sum;
        sum.next = frame.next;
        frame.next = &sum;
    }
    if (v->target) frame.color = *v->target;
    return vksky_record(r, cmd, &frame) == VKSKY_SUCCESS ? 0 : 1;
}

int host_commands_create(host_commands *h, vksky_context *ctx)
{
    vksky_context_handles k;
    vksky_context_get_handles(ctx, &k);
    *h = (host_commands){.device = k.device, .queue = k.queue};
    VkCommandPoolCreateInfo pinfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                     .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                     .queueFamilyIndex = k.queue_family};
    VkFenceCreateInfo finfo = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    bool ok = vkCreateCommandPool(h->device, &pinfo, NULL, &h->pool) == VK_SUCCESS;
    VkCommandBufferAllocateInfo ainfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                         .commandPool = h->pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                         .commandBufferCount = 1};
    ok = ok && vkAllocateCommandBuffers(h->device, &ainfo, &h->cmd) == VK_SUCCESS &&
         vkCreateFence(h->device, &finfo, NULL, &h->fence) == VK_SUCCESS;
    if (!ok) fprintf(stderr, "vksky: cannot make the frame's command buffer and fence\n");
    return ok ? 0 : 1;
}

void host_commands_destroy(host_commands *h)
{
    if (h->fence) vkDestroyFence(h->device, h->fence, NULL);
    if (h->pool) vkDestroyCommandPool(h->device, h->pool, NULL);   /* frees its command buffer */
    h->fence = VK_NULL_HANDLE, h->pool = VK_NULL_HANDLE;
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

int host_frames_wanted(void)
{
    const char *env = getenv("VKSKY_FRAMES");
    int n = env ? atoi(env) : 1;
    return n < 1 ? 1 : n > 16 ? 16 : n;
}

int host_commands_submit(host_commands *h, const host_submission *s, int first, int count)
{
    VkSemaphoreSubmitInfo wait, signal;
    uint32_t waits = 0;
    bool luts_waited = false;
    if (h->async && host_async_luts_list(h->async, s->luts, s->luts_count, s->force_luts || first > 0, &luts_waited))
        return 1;
    if (s->trace) fputs("commands\n", s->trace);   /* the host's command buffer, as the CLI's trace names one */
    VkCommandBufferBeginInfo binfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                      .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    if (vkResetCommandBuffer(h->cmd, 0) != VK_SUCCESS || vkBeginCommandBuffer(h->cmd, &binfo) != VK_SUCCESS) return 1;
    for (int k = first; k < first + count; ++k) {
        /* With the LUTs on the compute queue (recorded above) the frame records none; a frame after the first in
         * the command buffer follows one (the readback copies' write-after-write: a barrier of the spine's). */
        bool force = !h->async && (s->force_luts || k > 0);
        if (s->record(s->user, h->cmd, force, k > first) != 0) return 1;
    }
    if (vkEndCommandBuffer(h->cmd) != VK_SUCCESS) return 1;
    if (h->async) waits = host_async_frame(h->async, luts_waited, &wait, &signal);
    VkCommandBufferSubmitInfo cinfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = h->cmd};
    VkSubmitInfo2 sinfo = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .waitSemaphoreInfoCount = waits,
                           .pWaitSemaphoreInfos = &wait, .commandBufferInfoCount = 1, .pCommandBufferInfos = &cinfo,
                           .signalSemaphoreInfoCount = h->async ? 1 : 0, .pSignalSemaphoreInfos = &signal};
    double t0 = now_ms();
    VkResult vr = vkQueueSubmit2(h->queue, 1, &sinfo, h->fence);
    if (s->no_wait && vr == VK_SUCCESS) return 0;   /* the caller waits for h->fence (a ring of its own) */
    if (vr == VK_SUCCESS) vr = vkWaitForFences(h->device, 1, &h->fence, VK_TRUE, UINT64_MAX);
    if (s->wall_ms) *s->wall_ms = now_ms() - t0;
    if (vr == VK_SUCCESS) vr = vkResetFences(h->device, 1, &h->fence);
    if (vr != VK_SUCCESS) {
        fprintf(stderr, "vksky: %s's submission failed (VkResult %d)\n", s->what, (int)vr);
        return 1;
    }
    return 0;
}

/* A render's frame k: the renderer's frame of the view, LUTs forced and following as host_commands_submit says. */
typedef struct view_frames {
    vksky_renderer *r;
    const host_view *v;
} view_frames;

static int record_view(void *user, VkCommandBuffer cmd, bool force_luts, bool follows_frame)
{
    const view_frames *f = user;
    host_view v = *f->v;
    v.force_luts = force_luts, v.follows_frame = follows_frame;
    return host_record(f->r, cmd, &v, 0);
}

int host_commands_render(host_commands *h, vksky_renderer *r, const host_view *v, FILE *trace, double *wall_ms)
{
    int n = h->frames > 1 ? h->frames : 1;
    /* --async-luts: each frame is its own pair of submissions (the LUTs on the compute queue, the frame on the
     * graphics queue), which synchronization validation checks across submissions and queues. */
    view_frames frames = {r, v};
    host_submission s = {.luts = &r, .luts_count = 1, .force_luts = v->force_luts, .record = record_view,
                         .user = &frames, .trace = trace, .wall_ms = wall_ms, .what = "the frame"};
    if (h->async) {
        for (int k = 0; k < n; ++k)
            if (host_commands_submit(h, &s, k, 1)) return 1;
        return 0;
    }
    return host_commands_submit(h, &s, 0, n);
}

void host_timings_frame_end(vksky_renderer *r)
{
    vksky_renderer_stats stats = {0};
    vksky_pass_timing timed[64];
    uint32_t n = 0;
    vksky_renderer_get_stats(r, &stats);
    if (vksky_renderer_get_timings(r, timed, 64, &n) != VKSKY_SUCCESS || n > 64) n = 0;   /* no timestamps: none */
    const char *names[64];
    double ms[64];
    for (uint32_t k = 0; k < n; ++k) names[k] = timed[k].name, ms[k] = timed[k].gpu_ms;
    startup_frame_end_values(stats.pipelines_ms, (int)stats.variant_builds, (int)stats.lut_cache, names, ms, n);
}

/* A wait of the ring: traced, and skipped when it is the one VKSKY_DROP_BARRIER names. Returns whether to wait. */
static bool ring_wait(const host_ring *ring, const char *name, long frame, int slot, const char *what)
{
    if (ring->trace) fprintf(ring->trace, "sync %s frame=%ld slot=%d %s\n", name, frame, slot, what);
    return !(ring->drop && !strcmp(ring->drop, name));
}

/* Under the lock: frames whose consume returned, in submission order, are retired and their slots released. */
static void advance(host_ring *ring)
{
    while (ring->consumed < ring->claimed) {
        host_ring_slot *slot = &ring->slots[ring->consumed % ring->count];
        if (slot->released != ring->consumed) break;   /* still being consumed */
        if (slot->rc && !ring->status) ring->status = slot->rc;
        if (!ring->status && slot->done_job && ring->retire) ring->retire(ring->user, slot->done_job);
        free(slot->done_job);
        slot->done_job = NULL;
        ++ring->consumed;   /* the slot is free: the producer may record into it again */
    }
    pthread_cond_broadcast(&ring->changed);
}

static void *consumer(void *arg)
{
    host_ring *ring = arg;
    pthread_mutex_lock(&ring->lock);
    for (;;) {
        while (ring->claimed == ring->submitted && !ring->closing) pthread_cond_wait(&ring->changed, &ring->lock);
        if (ring->claimed == ring->submitted) break;   /* closing, and every frame claimed */
        long frame = ring->claimed++;
        int s = (int)(frame % ring->count);
        host_ring_slot *slot = &ring->slots[s];
        void *job = slot->job;
        slot->job = NULL;
        bool stopped = ring->status != 0;
        pthread_mutex_unlock(&ring->lock);
        int rc = 0;
        if (!stopped && job) {
            /* GPU -> host: the frame's copies wrote the slot's buffers and its last barrier made them available to
             * HOST_READ; the fence says the GPU got there. Without the wait the host reads the buffer before (or
             * while) the copy writes it: RAW. get_readback_slot invalidates non-coherent memory. */
            stage_mark t0 = stage_mark_now();
            if (ring_wait(ring, "ring.gpu_done", frame, s, "waiter=consumer on=fence hazard=RAW (copy -> host read)") &&
                vkWaitForFences(ring->device, 1, &slot->fence, VK_TRUE, UINT64_MAX) != VK_SUCCESS)
                rc = 1;
            stage_add_since(STAGE_GPU_WAIT, t0);
            vksky_readback px;
            if (rc == 0 && vksky_renderer_get_readback_slot(ring->r, (uint32_t)s, &px) != VKSKY_SUCCESS) rc = 1;
            int delay = frame % 2 ? ring->delay_odd_ms : ring->delay_ms;
            if (rc == 0 && delay > 0) {
                struct timespec ts = {delay / 1000, (long)(delay % 1000) * 1000000L};
                nanosleep(&ts, NULL);
            }
            if (rc == 0) {
                frame_ring_pixels pixels = {px.linear_rgba16f, px.display_rgba8};
                rc = ring->consume(ring->user, &pixels, job);
            } else {
                fprintf(stderr, "vksky: the readback ring could not read frame %ld\n", frame);
            }
        }
        pthread_mutex_lock(&ring->lock);
        slot->rc = rc, slot->released = frame, slot->done_job = job;
        advance(ring);
    }
    pthread_mutex_unlock(&ring->lock);
    return NULL;
}

int host_ring_wait_turn(host_ring *ring, long frame)
{
    pthread_mutex_lock(&ring->lock);
    while (!ring->status && ring->consumed < frame) pthread_cond_wait(&ring->changed, &ring->lock);
    int status = ring->status;
    pthread_mutex_unlock(&ring->lock);
    return status;
}

int host_ring_create(host_ring *ring, vksky_context *ctx, vksky_renderer *r, int slots, int consumers,
                     host_ring_consume_fn consume, host_ring_retire_fn retire, void *user, FILE *trace)
{
    vksky_context_handles k;
    vksky_context_get_handles(ctx, &k);
    if (consumers < 1) consumers = 1;
    if (consumers > HOST_RING_MAX_CONSUMERS) consumers = HOST_RING_MAX_CONSUMERS;
    if (consumers > slots - 1) consumers = slots - 1 < 1 ? 1 : slots - 1;
    *ring = (host_ring){.r = r, .device = k.device, .queue = k.queue, .count = slots, .consumers = consumers,
                        .consume = consume, .retire = retire, .user = user, .trace = trace};
    const char *drop = getenv("VKSKY_DROP_BARRIER");
    ring->drop = drop && *drop ? drop : NULL;
    /* "EVEN:ODD": even and odd frames dawdle differently, so frames encoded at once finish out of order. */
    ring_delays(&ring->delay_ms, &ring->delay_odd_ms);
    for (int s = 0; s < slots; ++s) ring->slots[s].released = -1;
    pthread_mutex_init(&ring->lock, NULL);
    pthread_cond_init(&ring->changed, NULL);
    VkCommandPoolCreateInfo pinfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                     .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                     .queueFamilyIndex = k.queue_family};
    /* The pool is the producer's alone (the consumer never touches a command buffer): no lock around it. */
    bool ok = vksky_renderer_set_readback_slots(r, (uint32_t)slots) == VKSKY_SUCCESS &&
              vkCreateCommandPool(ring->device, &pinfo, NULL, &ring->pool) == VK_SUCCESS;
    for (int s = 0; ok && s < slots; ++s) {
        VkFenceCreateInfo finfo = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        ok = vkCreateFence(ring->device, &finfo, NULL, &ring->slots[s].fence) == VK_SUCCESS;
    }
    for (; ok && ring->started < consumers; ++ring->started)
        if (pthread_create(&ring->threads[ring->started], NULL, consumer, ring) != 0) break;
    if (!ok || ring->started == 0) {
        fprintf(stderr, "vksky: cannot make the readback ring (its slots, command buffers, fences or thread)\n");
        host_ring_finish(ring);
        return 1;
    }
    return 0;
}

int host_ring_submit(host_ring *ring, const host_view *v, void *job)
{
    long frame = ring->submitted;
    int s = (int)(frame % ring->count);
    host_ring_slot *slot = &ring->slots[s];
    /* Host -> GPU: the consumer reads the slot's pixels of frame `frame - count`; this frame's copies overwrite them
     * (WAR), and re-recording resets the command buffer and the fence that frame used. Wait until the consumer
     * released the slot (it waited for that frame's fence first, so the GPU is done with it too). */
    stage_mark t0 = stage_mark_now();
    pthread_mutex_lock(&ring->lock);
    if (frame >= ring->count &&
        ring_wait(ring, "ring.slot_free", frame, s, "waiter=producer on=consumer hazard=WAR (host read -> copy)"))
        while (!ring->status && frame - ring->consumed >= ring->count) pthread_cond_wait(&ring->changed, &ring->lock);
    int status = ring->status;
    pthread_mutex_unlock(&ring->lock);
    stage_add_since(STAGE_SLOT_WAIT, t0);
    if (status) {
        free(job);
        return status;
    }
    VkCommandBufferBeginInfo binfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                      .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    VkCommandBufferSubmitInfo cinfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    VkSubmitInfo2 sinfo = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1,
                           .pCommandBufferInfos = &cinfo};
    /* The slot's last command buffer freed (its frame is done: ring.slot_free) and a new one made, its fence reset. */
    if (slot->recorded) {
        vkFreeCommandBuffers(ring->device, ring->pool, 1, &slot->cmd);
        slot->cmd = VK_NULL_HANDLE;
    }
    VkCommandBufferAllocateInfo ainfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                         .commandPool = ring->pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                         .commandBufferCount = 1};
    if (ring->trace) fputs("commands\n", ring->trace);   /* the host's command buffer, as the CLI's trace names one */
    bool ok = (!slot->recorded || vkResetFences(ring->device, 1, &slot->fence) == VK_SUCCESS) &&
              (slot->cmd || vkAllocateCommandBuffers(ring->device, &ainfo, &slot->cmd) == VK_SUCCESS) &&
              vkBeginCommandBuffer(slot->cmd, &binfo) == VK_SUCCESS &&
              host_record(ring->r, slot->cmd, v, (uint32_t)s) == 0 && vkEndCommandBuffer(slot->cmd) == VK_SUCCESS &&
              (cinfo.commandBuffer = slot->cmd, vkQueueSubmit2(ring->queue, 1, &sinfo, slot->fence) == VK_SUCCESS);
    if (!ok) {
        fprintf(stderr, "vksky: frame %ld could not be recorded or submitted\n", frame);
        free(job);
        return 1;
    }
    pthread_mutex_lock(&ring->lock);
    slot->recorded = true;
    slot->job = job;
    ring->submitted = frame + 1;
    pthread_cond_broadcast(&ring->changed);
    pthread_mutex_unlock(&ring->lock);
    return 0;
}

/* The fences of every slot submitted since its last reuse: each frame in flight has one. */
static void wait_all(host_ring *ring)
{
    for (int s = 0; s < ring->count; ++s)
        if (ring->slots[s].recorded) vkWaitForFences(ring->device, 1, &ring->slots[s].fence, VK_TRUE, UINT64_MAX);
}

void host_ring_drain(host_ring *ring)
{
    /* Host -> GPU: frames in flight read the atmosphere uniform block (and the pipelines and LUTs a new atmosphere
     * may rebuild); vksky_renderer_set_scene is about to rewrite it: WAR. Wait for all of them. */
    long frame = ring->submitted;
    if (ring_wait(ring, "ring.drain", frame, (int)(frame % ring->count),
                  "waiter=producer on=fences hazard=WAR (uniform read -> host write)")) {
        stage_mark t0 = stage_mark_now();
        wait_all(ring);
        stage_add_since(STAGE_SLOT_WAIT, t0);
    }
}

int host_ring_settle(host_ring *ring)
{
    /* Not a GPU wait: the consumer has written every frame submitted so far (their fences waited by it). */
    pthread_mutex_lock(&ring->lock);
    while (!ring->status && ring->consumed < ring->submitted) pthread_cond_wait(&ring->changed, &ring->lock);
    int status = ring->status;
    pthread_mutex_unlock(&ring->lock);
    return status;
}

int host_ring_finish(host_ring *ring)
{
    if (ring->started) {
        pthread_mutex_lock(&ring->lock);
        ring->closing = true;
        pthread_cond_broadcast(&ring->changed);
        pthread_mutex_unlock(&ring->lock);
        for (int t = 0; t < ring->started; ++t) pthread_join(ring->threads[t], NULL);
    }
    wait_all(ring);   /* frames the consumer skipped after a failure or a stop may still run */
    for (int s = 0; s < ring->count; ++s) {
        host_ring_slot *slot = &ring->slots[s];
        if (slot->fence) vkDestroyFence(ring->device, slot->fence, NULL);
        free(slot->job);
        free(slot->done_job);
    }
    if (ring->pool) vkDestroyCommandPool(ring->device, ring->pool, NULL);   /* frees the command buffers */
    pthread_cond_destroy(&ring->changed);
    pthread_mutex_destroy(&ring->lock);
    return ring->status;
}
