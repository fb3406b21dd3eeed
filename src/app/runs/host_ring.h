/* The readback ring of a host of include/vksky.h (issue 25 item 1; issue 27's ring, the command line's only one):
 * the GPU renders frame N+1 while a consumer thread writes frame N. The ring is the host's — its slots in turn, its
 * command buffers and fences, its three waits (docs/synchronization.md, "The readback ring"):
 *
 *   ring.gpu_done   the consumer waits for the frame's fence before it reads the slot's pixels (GPU -> host, RAW);
 *   ring.slot_free  the producer waits for the consumer to release a slot before recording into it again (WAR);
 *   ring.drain      the producer waits for every frame in flight before vksky rewrites what they read (a new scene).
 *
 * The copies into a slot are vksky's: the frame spine's readback step, into the renderer's readback slot the frame
 * names (vksky_readback_target). Each wait is printed by --trace-barriers ("sync <name> ...") and left out by
 * VKSKY_DROP_BARRIER=<name> (tests/readback_ring_test.sh). No src/sky or src/lib header (tests/layering_test.sh). */
#ifndef VKSKY_APP_HOST_RING_H
#define VKSKY_APP_HOST_RING_H
#include <volk.h>
#include <vksky.h>
#include "app/runs/host_async.h"
#include "app/runs/sequence_frames.h"
#include <pthread.h>
#include <stdio.h>

#define HOST_RING_MAX_SLOTS 4
/* Consumer threads at most (frames encoded at once, issue 27); each holds a slot, the GPU renders into the one left. */
#define HOST_RING_MAX_CONSUMERS (HOST_RING_MAX_SLOTS - 1)

/* A frame as the command line gives it: its view (yaw, pitch, fov), its exposure, or auto exposure metered on the GPU.
 * An environment map (projection not perspective) is one band, the whole image (vksky_frame_band): no view. */
typedef struct host_view {
    double yaw_deg, pitch_deg, fov_deg, exposure;
    bool auto_exposure;
    bool force_luts;             /* the LUT passes even if the scene did not change (--bench) */
    vksky_projection projection; /* 0: perspective (the view's rays) */
    uint32_t whole_width, whole_height;   /* a map's size: the renderer's */
    /* A band of the whole image (app/runs/tiles.c, vksky_frame_band): its first row there, and the rows of the frame
     * auto exposure's meter counts (0: every row). */
    bool band;
    int32_t first_row;
    uint32_t meter_first_row, meter_rows;
    bool follows_frame;          /* an earlier frame was recorded into the same command buffer (VKSKY_FRAMES) */
    /* The host's own image the frame writes (frame.color: a renderer without readback, --bench without --render),
     * or NULL: the pixels into a readback slot. */
    const vksky_image *target;
    /* A spectral group's frame: its composite added into the GPU's sum (ABI 4; its `next` is ignored), or NULL. */
    const vksky_frame_spectral_sum *spectral_sum;
    /* This frame's tone map and bloom switch instead of the scene's (a spectral group's bloom-free frame, whose sum
     * the host's auto exposure meters: app/runs/spectral_host.c), or NULL. */
    const vksky_frame_display *display;
} host_view;

/* Records one frame of `v` into cmd (begun): its pixels into readback slot `slot` (or v->target), auto exposure's
 * result in meter slot `slot`. 0, or 1 (vksky's message printed). */
int host_record(vksky_renderer *r, VkCommandBuffer cmd, const host_view *v, uint32_t slot);

/* One frame at a time: the host's command buffer and fence, the frame recorded into it, submitted and waited for. */
typedef struct host_commands {
    VkDevice device;
    VkQueue queue;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    VkFence fence;
    host_async *async;           /* --async-luts: the LUT passes on the compute queue first (NULL: in the frame) */
    /* VKSKY_FRAMES=N (tests; host_frames_wanted): each render is N frames, the LUTs rebuilt in every frame after the
     * first, recorded back to back into the one command buffer (each its own pair of submissions with --async-luts).
     * The queue then sees frames in flight, and synchronization validation each frame's first use of an image after
     * the previous frame's last (the write-after-read barriers that only matter from the second frame on). */
    int frames;
} host_commands;
/* VKSKY_FRAMES: 1..16 (1 when unset). */
int host_frames_wanted(void);
/* 0, or 1 (the line printed). */
int host_commands_create(host_commands *h, vksky_context *ctx);
void host_commands_destroy(host_commands *h);
/* v into readback slot 0; trace: --trace-barriers's stream for the "commands" line (NULL: none); *wall_ms (may be NULL):
 * submit to fence. 0, or 1 (the line printed). */
int host_commands_render(host_commands *h, vksky_renderer *r, const host_view *v, FILE *trace, double *wall_ms);

/* One submission of frames through h, whatever records them (a render's frames, a composite's bands, the spectral
 * groups): with h->async, the LUT passes of luts[0 .. luts_count-1] first, in one submission on the compute queue
 * (rebuilt when force_luts or a later frame asks), and the frame's submission waits for them (host_async.h). */
typedef struct host_submission {
    vksky_renderer *const *luts;   /* the renderers whose LUTs the frames read */
    uint32_t luts_count;
    bool force_luts;               /* the first frame rebuilds the LUTs (frames after the first always do) */
    /* Records frame k into cmd: force_luts (the LUTs in this frame: never with h->async), follows_frame (another frame
     * precedes it in the command buffer). 0, or 1 after its line. */
    int (*record)(void *user, VkCommandBuffer cmd, bool force_luts, bool follows_frame);
    void *user;
    FILE *trace;                   /* --trace-barriers: the "commands" line (NULL: none) */
    double *wall_ms;               /* submit to fence (NULL: not measured) */
    bool no_wait;                  /* return after the submission: the caller waits for h->fence */
    const char *what;              /* "the frame": its error line's subject */
} host_submission;
/* Frames first .. first + count - 1 recorded into h's command buffer and submitted (and waited for, unless no_wait).
 * 0, or 1 after its line. */
int host_commands_submit(host_commands *h, const host_submission *s, int first, int count);

/* --timings: the first image's figures (app/runs/startup.h) from the renderer's stats and its last frame's pass
 * timings (after the host waited for that frame; later frames are not measured). */
void host_timings_frame_end(vksky_renderer *r);

/* The consumer, on one of the ring's threads: non-zero stops the ring. `job` is freed by the ring. With one consumer
 * thread frames are consumed in submission order; with several, frames N and N+1 are consumed at once, each on its
 * own thread: the function must be safe to run concurrently and order what must be ordered itself
 * (host_ring_wait_turn). */
typedef int (*host_ring_consume_fn)(void *user, const frame_ring_pixels *px, void *job);
/* Optional: once per consumed frame in submission order, under the ring's lock, after its consume returned (a progress
 * line, counts). Not called for frames after a failure. */
typedef void (*host_ring_retire_fn)(void *user, void *job);

typedef struct host_ring_slot {
    VkCommandBuffer cmd;
    VkFence fence;
    bool recorded;               /* since its last reuse */
    void *job;                   /* submitted, not yet claimed by a consumer */
    void *done_job;              /* consumed, not yet retired */
    long released;               /* the frame whose consume returned last in this slot (-1: none) */
    int rc;                      /* that consume's result */
} host_ring_slot;

typedef struct host_ring {
    vksky_renderer *r;
    VkDevice device;
    VkQueue queue;
    VkCommandPool pool;
    int count;
    host_ring_slot slots[HOST_RING_MAX_SLOTS];
    host_ring_consume_fn consume;
    host_ring_retire_fn retire;
    void *user;
    FILE *trace;                 /* --trace-barriers: the "sync" lines, and "commands" where a command buffer begins */
    const char *drop;            /* VKSKY_DROP_BARRIER */
    int delay_ms;                /* VKSKY_RING_DELAY_MS */
    int delay_odd_ms;            /* ... for odd frames ("EVEN:ODD"; else the same) */
    pthread_t threads[HOST_RING_MAX_CONSUMERS];
    int consumers, started;      /* consumer threads wanted / running */
    pthread_mutex_t lock;
    pthread_cond_t changed;
    long submitted, claimed;     /* frames handed over / taken by a consumer thread */
    long consumed;               /* frames 0 .. consumed-1 all released by their consumers (and retired) */
    int status;
    bool closing;
} host_ring;

/* The number of slots a run uses: VKSKY_READBACK_SLOTS (0 or 1: one frame at a time, no ring; default 2). */
int host_ring_slots_wanted(void);
/* Frames a sequence encodes at once (consumer threads) for images of `pixels`
 * (VKSKY_ENCODE_FRAMES, else one per 4 encode threads, at most 3, ~1 GiB in flight at most; app/runs/ring_order.h). */
int host_ring_consumers_wanted(long pixels);
/* A ring of `slots` (2..HOST_RING_MAX_SLOTS) over r (a readback renderer: given that many readback slots) with
 * `consumers` consumer threads (1..HOST_RING_MAX_CONSUMERS, fewer than slots). `retire` may be NULL. 0, or 1. */
int host_ring_create(host_ring *ring, vksky_context *ctx, vksky_renderer *r, int slots, int consumers,
                     host_ring_consume_fn consume, host_ring_retire_fn retire, void *user, FILE *trace);
/* For a consume function of frame `frame`: waits until every earlier frame's consume returned (their files are in
 * place), e.g. before a rename, so that frames appear in order. The ring's status (non-zero: one failed). */
int host_ring_wait_turn(host_ring *ring, long frame);
/* Records v into the next slot (after ring.slot_free), submits it, hands `job` (malloc'd) to the consumer. Returns the
 * consumer's status so far (non-zero: stop; the job was freed). */
int host_ring_submit(host_ring *ring, const host_view *v, void *job);
/* ring.drain: every frame submitted so far finished on the GPU. */
void host_ring_drain(host_ring *ring);
/* Every frame submitted so far written by the consumer; its status. */
int host_ring_settle(host_ring *ring);
/* Waits for the consumer, stops it, frees the slots. Its status. */
int host_ring_finish(host_ring *ring);
#endif
