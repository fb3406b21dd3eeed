/* The readback ring (frame_ring.h). The producer is the caller's thread: it records and submits. The consumer is
 * one thread of ours: it waits for each frame's fence, reads the slot and hands the pixels to the consume function.
 * Every Vulkan object a thread touches is either its own (the queue, the command pool and the fences' resets are
 * the producer's) or one the spec lets two threads use at once (vkWaitForFences, vkInvalidateMappedMemoryRanges). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include "app/runs/frame_ring.h"
#include "app/runs/ring_order.h"
#include "app/runs/stage_times.h"
#include <stdlib.h>
#include <string.h>
#include <time.h>

int frame_ring_slots_wanted(void)
{
    const char *env = getenv("VKSKY_READBACK_SLOTS");
    int n = env && *env ? atoi(env) : 2;
    if (n < 2) return 0;   /* 0 or 1: the serial loop */
    return n > FRAME_RING_MAX_SLOTS ? FRAME_RING_MAX_SLOTS : n;
}

/* A wait of the ring: traced, and skipped when it is the one VKSKY_DROP_BARRIER names. Returns whether to wait. */
static bool ring_wait(const frame_ring *ring, const char *name, long frame, int slot, const char *what)
{
    if (ring->trace) fprintf(ring->trace, "sync %s frame=%ld slot=%d %s\n", name, frame, slot, what);
    return !(ring->drop && !strcmp(ring->drop, name));
}

/* Under the lock: frames whose consume returned, in submission order, are retired and their slots released. */
static void advance(frame_ring *ring)
{
    while (ring->consumed < ring->claimed) {
        frame_ring_slot *slot = &ring->slots[ring->consumed % ring->count];
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
    frame_ring *ring = arg;
    pthread_mutex_lock(&ring->lock);
    for (;;) {
        while (ring->claimed == ring->submitted && !ring->closing) pthread_cond_wait(&ring->changed, &ring->lock);
        if (ring->claimed == ring->submitted) break;   /* closing, and every frame claimed */
        long frame = ring->claimed++;
        int s = (int)(frame % ring->count);
        frame_ring_slot *slot = &ring->slots[s];
        void *job = slot->job;
        slot->job = NULL;
        bool stopped = ring->status != 0;
        pthread_mutex_unlock(&ring->lock);
        int rc = 0;
        if (!stopped && job) {
            /* GPU -> host: the frame's copies wrote the slot's buffers and its last barrier made them available to
             * HOST_READ; the fence says the GPU got there. Without the wait the host reads the buffer before (or
             * while) the copy writes it: RAW. On non-coherent memory, the invalidate makes the writes visible. */
            stage_mark t0 = stage_mark_now();
            if (ring_wait(ring, "ring.gpu_done", frame, s, "waiter=consumer on=fence hazard=RAW (copy -> host read)"))
                VK_CHECK(vkWaitForFences(ring->r->ctx->device, 1, &slot->fence, VK_TRUE, UINT64_MAX));
            stage_add_since(STAGE_GPU_WAIT, t0);
            gpu_buffer_invalidate(ring->r->ctx, &slot->linear);
            gpu_buffer_invalidate(ring->r->ctx, &slot->display);
            int delay = frame % 2 ? ring->delay_odd_ms : ring->delay_ms;
            if (delay > 0) {
                struct timespec ts = {delay / 1000, (long)(delay % 1000) * 1000000L};
                nanosleep(&ts, NULL);
            }
            frame_ring_pixels px = {slot->linear.mapped, slot->display.mapped};
            rc = ring->consume(ring->user, &px, job);
        }
        pthread_mutex_lock(&ring->lock);
        slot->rc = rc, slot->released = frame, slot->done_job = job;
        advance(ring);
    }
    pthread_mutex_unlock(&ring->lock);
    return NULL;
}

int frame_ring_consumers_wanted(long pixels) { return ring_consumers_wanted(pixels, FRAME_RING_MAX_CONSUMERS); }

int frame_ring_wait_turn(frame_ring *ring, long frame)
{
    pthread_mutex_lock(&ring->lock);
    while (!ring->status && ring->consumed < frame) pthread_cond_wait(&ring->changed, &ring->lock);
    int status = ring->status;
    pthread_mutex_unlock(&ring->lock);
    return status;
}

int frame_ring_create(frame_ring *ring, sky_renderer *r, int slots, int consumers, frame_ring_consume_fn consume,
                      frame_ring_retire_fn retire, void *user, FILE *trace)
{
    if (consumers < 1) consumers = 1;
    if (consumers > FRAME_RING_MAX_CONSUMERS) consumers = FRAME_RING_MAX_CONSUMERS;
    if (consumers > slots - 1) consumers = slots - 1 < 1 ? 1 : slots - 1;
    *ring = (frame_ring){.r = r, .count = slots, .consumers = consumers, .consume = consume, .retire = retire,
                         .user = user, .trace = trace, .own_linear = r->readback_linear,
                         .own_display = r->readback_display};
    const char *drop = getenv("VKSKY_DROP_BARRIER");
    ring->drop = drop && *drop ? drop : NULL;
    /* "EVEN:ODD": even and odd frames dawdle differently, so frames encoded at once finish out of order. */
    ring_delays(&ring->delay_ms, &ring->delay_odd_ms);
    const gpu_context *ctx = r->ctx;
    for (int s = 0; s < slots; ++s) {
        frame_ring_slot *slot = &ring->slots[s];
        slot->released = -1;
        /* Slot 0 is the renderer's own pair of buffers; the others are the same sizes. */
        if (s == 0) {
            slot->linear = r->readback_linear, slot->display = r->readback_display;
        } else {
            gpu_buffer_create(ctx, &slot->linear, "readback linear (ring)", r->readback_linear.size,
                              VK_BUFFER_USAGE_TRANSFER_DST_BIT);
            gpu_buffer_create(ctx, &slot->display, "readback display (ring)", r->readback_display.size,
                              VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        }
        VkFenceCreateInfo finfo = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VK_CHECK(vkCreateFence(ctx->device, &finfo, NULL, &slot->fence));
        gpu_set_name(ctx, VK_OBJECT_TYPE_FENCE, (uint64_t)slot->fence, "readback ring slot");
    }
    pthread_mutex_init(&ring->lock, NULL);
    pthread_cond_init(&ring->changed, NULL);
    for (; ring->started < consumers; ++ring->started)
        if (pthread_create(&ring->threads[ring->started], NULL, consumer, ring) != 0) break;
    if (ring->started == 0) {
        fprintf(stderr, "vksky: cannot start the readback thread\n");
        frame_ring_finish(ring);
        return 1;
    }
    return 0;
}

int frame_ring_submit(frame_ring *ring, const frame_desc *f, void *job)
{
    long frame = ring->submitted;
    int s = (int)(frame % ring->count);
    frame_ring_slot *slot = &ring->slots[s];
    /* Host -> GPU: the consumer reads the slot's buffers of frame `frame - count`; this frame's copies overwrite
     * them (WAR), and re-recording frees the command buffer and resets the fence that frame used. Wait until the
     * consumer released the slot (it waited for that frame's fence first, so the GPU is done with it too). */
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
    const gpu_context *ctx = ring->r->ctx;
    if (slot->cmd) {
        vkFreeCommandBuffers(ctx->device, ctx->command_pool, 1, &slot->cmd);
        VK_CHECK(vkResetFences(ctx->device, 1, &slot->fence));
    }
    /* The frame spine copies into the renderer's readback pair: this slot's for this frame. */
    ring->r->readback_linear = slot->linear, ring->r->readback_display = slot->display;
    slot->cmd = gpu_begin_commands(ctx);
    /* Auto exposure: the meter's result slot is the ring slot's, free once the consumer released it (as the
     * readback buffers). */
    frame_desc fd = *f;
    fd.meter_slot = (uint32_t)s;
    frame_record(ring->r, slot->cmd, &fd);
    VK_CHECK(vkEndCommandBuffer(slot->cmd));
    VkCommandBufferSubmitInfo cinfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = slot->cmd};
    VkSubmitInfo2 sinfo = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2, .commandBufferInfoCount = 1,
                           .pCommandBufferInfos = &cinfo};
    VK_CHECK(vkQueueSubmit2(ctx->queue, 1, &sinfo, slot->fence));
    pthread_mutex_lock(&ring->lock);
    slot->job = job;
    ring->submitted = frame + 1;
    pthread_cond_broadcast(&ring->changed);
    pthread_mutex_unlock(&ring->lock);
    return 0;
}

/* The fences of every slot recorded since its last reuse: each frame in flight has one. */
static void wait_all(frame_ring *ring)
{
    for (int s = 0; s < ring->count; ++s)
        if (ring->slots[s].cmd)
            VK_CHECK(vkWaitForFences(ring->r->ctx->device, 1, &ring->slots[s].fence, VK_TRUE, UINT64_MAX));
}

void frame_ring_drain(frame_ring *ring)
{
    /* Host -> GPU: frames in flight read the atmosphere uniform block (and the pipelines and LUTs a new atmosphere
     * may rebuild); the host is about to rewrite it: WAR. Wait for all of them. */
    long frame = ring->submitted;
    if (ring_wait(ring, "ring.drain", frame, (int)(frame % ring->count),
                  "waiter=producer on=fences hazard=WAR (uniform read -> host write)")) {
        stage_mark t0 = stage_mark_now();
        wait_all(ring);
        stage_add_since(STAGE_SLOT_WAIT, t0);
    }
}

int frame_ring_settle(frame_ring *ring)
{
    /* Not a GPU wait: the consumer has written every frame submitted so far (their fences waited by it). */
    pthread_mutex_lock(&ring->lock);
    while (!ring->status && ring->consumed < ring->submitted) pthread_cond_wait(&ring->changed, &ring->lock);
    int status = ring->status;
    pthread_mutex_unlock(&ring->lock);
    return status;
}

int frame_ring_finish(frame_ring *ring)
{
    if (ring->started) {
        pthread_mutex_lock(&ring->lock);
        ring->closing = true;
        pthread_cond_broadcast(&ring->changed);
        pthread_mutex_unlock(&ring->lock);
        for (int t = 0; t < ring->started; ++t) pthread_join(ring->threads[t], NULL);
    }
    wait_all(ring);   /* frames the consumer skipped after a failure or a stop may still run */
    const gpu_context *ctx = ring->r->ctx;
    for (int s = 0; s < ring->count; ++s) {
        frame_ring_slot *slot = &ring->slots[s];
        if (slot->cmd) vkFreeCommandBuffers(ctx->device, ctx->command_pool, 1, &slot->cmd);
        if (slot->fence) vkDestroyFence(ctx->device, slot->fence, NULL);
        free(slot->job);
        free(slot->done_job);
        if (s > 0) {
            gpu_buffer_destroy(ctx, &slot->linear);
            gpu_buffer_destroy(ctx, &slot->display);
        }
    }
    ring->r->readback_linear = ring->own_linear, ring->r->readback_display = ring->own_display;
    pthread_cond_destroy(&ring->changed);
    pthread_mutex_destroy(&ring->lock);
    return ring->status;
}
