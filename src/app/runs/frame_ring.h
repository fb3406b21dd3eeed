/* The readback ring (issue 27): a pipelined frame loop for sequences and banded renders. The GPU renders frame N+1
 * while a consumer thread reads back and writes frame N. A CPU consumer and a GPU producer share a few readback
 * buffers; three waits hand them over (docs/synchronization.md, "The readback ring"):
 *
 *   ring.gpu_done   the consumer waits for the frame's fence before it reads the slot's buffers (GPU -> host, RAW);
 *   ring.slot_free  the producer waits for the consumer to release a slot before recording into it again
 *                   (host -> GPU, WAR; also frees its command buffer and resets its fence only when nobody waits);
 *   ring.drain      the producer waits for every frame in flight before the host rewrites what they read (the
 *                   atmosphere uniform block: WAR).
 *
 * Each is printed by --trace-barriers ("sync <name> ...") and can be left out by VKSKY_DROP_BARRIER=<name> (the drop
 * tests: tests/readback_ring_test.sh). Frames are consumed in submission order, so the files are written in the
 * serial loop's order with the same bytes. */
#ifndef VKSKY_APP_FRAME_RING_H
#define VKSKY_APP_FRAME_RING_H
#include "sky/frame.h"
#include "app/runs/sequence_frames.h"
#include <pthread.h>
#include <stdio.h>

/* At most one slot per auto exposure meter result (VKSKY_METER_SLOTS, shaders/glsl/shared.h): a frame's meter slot
 * is its ring slot. */
#define FRAME_RING_MAX_SLOTS 4
/* Consumer threads at most (frames encoded at once); each holds a slot, the GPU renders into the one left. */
#define FRAME_RING_MAX_CONSUMERS (FRAME_RING_MAX_SLOTS - 1)

/* What the consumer reads: the frame's linear (RGBA half) and display (RGBA8) pixels, as the renderer lays them out
 * (renderer.h: readback_linear, readback_display): frame_ring_pixels (app/runs/sequence_frames.h). */

/* The consumer: called on one of the ring's threads, once per frame; `job` is the producer's (freed by the ring
 * afterwards with free()). With one consumer thread (the default) frames are consumed in submission order; with
 * several (frame_ring_create's `consumers`), frames N and N+1 are consumed at once, each on its own thread: the
 * function must be safe to run concurrently and order what must be ordered itself (frame_ring_wait_turn). Non-zero:
 * the ring stops (later frames are not consumed) and reports it. */
typedef int (*frame_ring_consume_fn)(void *user, const frame_ring_pixels *px, void *job);
/* Optional: called once per consumed frame in submission order, under the ring's lock, after its consume returned
 * (a progress line, counts). Not called for frames after a failure. */
typedef void (*frame_ring_retire_fn)(void *user, void *job);

typedef struct frame_ring_slot {
    gpu_buffer linear, display;
    VkCommandBuffer cmd;         /* NULL: not recorded since its last reuse */
    VkFence fence;
    void *job;                   /* submitted, not yet claimed by a consumer */
    void *done_job;              /* consumed, not yet retired */
    long released;               /* the frame whose consume returned last in this slot (-1: none) */
    int rc;                      /* that consume's result */
} frame_ring_slot;

typedef struct frame_ring {
    sky_renderer *r;
    gpu_buffer own_linear, own_display;   /* the renderer's buffers (slot 0's), given back at the end */
    int count;
    frame_ring_slot slots[FRAME_RING_MAX_SLOTS];
    frame_ring_consume_fn consume;
    frame_ring_retire_fn retire;
    void *user;
    FILE *trace;                 /* --trace-barriers: one "sync" line per wait */
    const char *drop;            /* VKSKY_DROP_BARRIER: a wait to leave out (tests) */
    int delay_ms;                /* VKSKY_RING_DELAY_MS: the consumer dawdles (widens races for the drop tests) */
    int delay_odd_ms;            /* ... for odd frames ("EVEN:ODD"; else the same) */
    pthread_t threads[FRAME_RING_MAX_CONSUMERS];
    int consumers, started;      /* consumer threads wanted / running */
    pthread_mutex_t lock;
    pthread_cond_t changed;
    long submitted, claimed;     /* frames handed over / taken by a consumer thread */
    long consumed;               /* frames 0 .. consumed-1 all released by their consumers (and retired) */
    int status;                  /* the first non-zero consumer result */
    bool closing;
} frame_ring;

/* The number of slots a run uses: VKSKY_READBACK_SLOTS (0 or 1: the serial loop, no ring; default 2). */
int frame_ring_slots_wanted(void);
/* Frames a sequence encodes at once (consumer threads) for images of `pixels`: VKSKY_ENCODE_FRAMES if set
 * (1..FRAME_RING_MAX_CONSUMERS), else one per 4 encode threads (--threads, default the cores: 16 cores -> 3 frames of
 * 5 threads each), at most 3, and no more than ~1 GiB of frames in flight. 1 on a 2-core machine: one consumer. */
int frame_ring_consumers_wanted(long pixels);
/* A ring of `slots` (2..FRAME_RING_MAX_SLOTS) over r (made with readback) with `consumers` consumer threads
 * (1..FRAME_RING_MAX_CONSUMERS, fewer than slots); starts them. `retire` may be NULL. 0, or 1 with a line printed. */
int frame_ring_create(frame_ring *ring, sky_renderer *r, int slots, int consumers, frame_ring_consume_fn consume,
                      frame_ring_retire_fn retire, void *user, FILE *trace);
/* For a consume function of frame `frame`: waits until every earlier frame's consume returned (their files are in
 * place), e.g. before a rename, so that frames appear in order. Returns the ring's status (non-zero: one failed). */
int frame_ring_wait_turn(frame_ring *ring, long frame);
/* Records f into the next slot (after ring.slot_free), submits it, and hands `job` (malloc'd) to the consumer.
 * Returns the consumer's status so far (non-zero: stop submitting; the job was freed). */
int frame_ring_submit(frame_ring *ring, const frame_desc *f, void *job);
/* ring.drain: waits until the GPU has finished every frame submitted so far (before the host rewrites what they
 * read). */
void frame_ring_drain(frame_ring *ring);
/* Wait until the consumer has written every frame submitted so far (e.g. before a line that must follow theirs).
 * Returns the consumer's status. */
int frame_ring_settle(frame_ring *ring);

/* Waits for the consumer to finish every frame, stops the thread, frees the slots, gives the renderer its buffers
 * back. Returns the consumer's status. */
int frame_ring_finish(frame_ring *ring);
#endif
