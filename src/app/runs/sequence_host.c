/* The frames of a sequence through include/vksky.h (sequence_host.h): the serial loop and the pipelined one, as
 * app/runs/sequence.c's (their lines, order and files), over the public API. */
#include "app/runs/sequence_host.h"
#include "app/runs/host_ring.h"
#include "app/runs/host_print.h"
#include "app/runs/sequence_frames.h"
#include "app/runs/sequence_resume.h"
#include "app/runs/stage_times.h"
#include "app/runs/startup.h"
#include "app/runs/stop.h"
#include "app/scene/light.h"
#include "io/atomic_file.h"
#include "io/encode_settings.h"
#include <limits.h>
#include <stdlib.h>

static int frame_count(const options *o) { return o->frame_count > 0 ? o->frame_count : 1; }

/* Frame i's scene: its animated values set on the command line's scene, and the renderer given it. Frames in flight
 * (the ring) are waited for first only when the scene changes what they read (ring.drain). *luts: whether the next
 * frame computes the LUTs. 0, or 1 (the line printed). */
static int set_frame_scene(const options *base, int i, vksky_scene *scene, vksky_renderer *r, host_ring *ring,
                           bool first, bool *luts)
{
    const char *names[OPTIONS_MAX_ANIMATE];
    double values[OPTIONS_MAX_ANIMATE];
    int n = sequence_frame_values(base, i, names, values);
    if (vksky_scene_set_values(scene, (uint32_t)n, names, values, host_print_message, NULL) != VKSKY_SUCCESS) return 1;
    if (ring && !first && vksky_renderer_scene_changes(r, scene)) host_ring_drain(ring);
    if (vksky_renderer_set_scene(r, scene) != VKSKY_SUCCESS) return 1;
    *luts = vksky_renderer_luts_stale(r);
    return 0;
}

/* The view and exposure a frame's options give (auto exposure metered on the GPU, as the CLI's loops do). */
static host_view view_of(const options *f)
{
    return (host_view){.yaw_deg = f->view.yaw_deg, .pitch_deg = f->view.pitch_deg, .fov_deg = f->view.fov_deg,
                       .exposure = f->view.exposure_ev, .auto_exposure = light_auto_exposure_wanted(f)};
}

/* One frame, waited for; its LUTs into the cache on a miss; --timings' first image. */
static int render_one(host_commands *h, vksky_renderer *r, const host_view *v, FILE *trace, bool timings)
{
    /* --timings: the first frame's files are done when the second frame begins (or the run ends). */
    startup_outputs_done();
    startup_frame_begin();
    if (host_commands_render(h, r, v, trace, NULL)) return 1;
    /* A LUT cache miss: the LUTs this frame computed, into the cache (a hit, none, or stored already: nothing). */
    if (vksky_renderer_store_luts(r) != VKSKY_SUCCESS) return 1;
    if (timings) host_timings_frame_end(r);
    return 0;
}

static int serial_loop(const options *base, host_commands *h, vksky_scene *scene, vksky_renderer *r, FILE *trace)
{
    bool sequence = sequence_active(base);
    int done = 0, skipped = 0, lut_computations = 0;
    int range = base->frame_last - base->frame_first + 1;
    for (int i = base->frame_first; i <= base->frame_last && !stop_requested(); ++i) {   /* stop: between frames */
        options f;
        if (sequence_frame_options(base, i, &f)) return 1;   /* parsed before (sequence_check): not expected */
        /* --skip-existing: a frame this job wrote before (whole, by the atomic rename) is kept (sequence_resume.h). */
        if (base->skip_existing && sequence_resume_skip(&f, i, frame_count(base), done + skipped + 1, range)) {
            ++skipped;
            continue;
        }
        bool luts = false;
        if (set_frame_scene(base, i, scene, r, NULL, true, &luts)) return 1;
        lut_computations += luts;
        host_view v = view_of(&f);
        if (render_one(h, r, &v, trace, base->timings)) return 1;
        if (v.auto_exposure && !sequence && !base->quiet) {
            vksky_exposure e;
            if (vksky_renderer_get_exposure(r, 0, &e) != VKSKY_SUCCESS) return 1;
            fprintf(stderr, "vksky: auto exposure: EV100 %.4f (log-average luminance %.6g %s over %.0f pixels, metered "
                            "on the GPU)\n", e.ev100, e.log_average, f.view.ev100 ? "cd/m2" : "(relative units)",
                    e.pixel_count);
        }
        vksky_readback px;
        if (vksky_renderer_get_readback_slot(r, 0, &px) != VKSKY_SUCCESS) return 1;
        frame_ring_pixels pixels = {px.linear_rgba16f, px.display_rgba8};
        char path[PATH_MAX];
        if (sequence_write_outputs(&f, &pixels, i, sequence, path) != 0) return 1;
        ++done;
        if (sequence) sequence_frame_line(base, i, done + skipped, path, luts);
    }
    if (stop_requested()) return 1;   /* frames already written are whole and stay; stop_status says the rest */
    if (sequence) sequence_summary_line(base, done, skipped, lut_computations);
    return 0;
}

static int render_serial(const options *base, vksky_context *ctx, vksky_scene *scene, vksky_renderer *r,
                         host_async *async, FILE *trace)
{
    host_commands h;
    int status = host_commands_create(&h, ctx);
    h.async = async, h.frames = host_frames_wanted();
    if (status == 0) status = serial_loop(base, &h, scene, r, trace);
    host_commands_destroy(&h);
    return status;
}

/* The pipelined loop's job for a frame: what the consumer needs to write it. */
typedef struct frame_job {
    options f;
    int frame;
    long seq;              /* its place among the frames submitted to the ring */
    bool luts;
    char path[PATH_MAX];   /* its first file (the progress line's) */
} frame_job;

typedef struct consumer_state {
    const options *base;
    host_ring *ring;
    int share;     /* encode threads of each frame when several are encoded at once (io_encode_threads_local) */
    int done;      /* frames written (retired, in order) */
    int skipped;   /* frames kept (--skip-existing): counted by the producer while the consumers are idle */
} consumer_state;

typedef struct commit_turn {
    host_ring *ring;
    long seq;
} commit_turn;

/* io_commit_gate_fn: a frame's files are renamed into place only after every earlier frame's, so frames encoded at
 * once still appear in order (a stop keeps the first frames, never a gap; --skip-existing resumes after them). */
static void commit_gate(void *user)
{
    const commit_turn *t = user;
    host_ring_wait_turn(t->ring, t->seq);
}

/* host_ring_consume_fn: a frame's files, on one of the ring's threads (several frames at once with
 * VKSKY_ENCODE_FRAMES or many cores: host_ring_consumers_wanted). */
static int consume_frame(void *user, const frame_ring_pixels *px, void *job)
{
    consumer_state *c = user;
    frame_job *j = job;
    commit_turn turn = {c->ring, j->seq};
    io_encode_threads_local(c->share);
    io_atomic_set_commit_gate(c->ring->consumers > 1 ? commit_gate : NULL, &turn);
    int rc = stop_requested() || sequence_write_outputs(&j->f, px, j->frame, true, j->path) != 0;
    io_atomic_set_commit_gate(NULL, NULL);
    return rc;
}

/* host_ring_retire_fn: the frame's line, in frame order. */
static void retire_frame(void *user, void *job)
{
    consumer_state *c = user;
    const frame_job *j = job;
    ++c->done;
    sequence_frame_line(c->base, j->frame, c->done + c->skipped, j->path, j->luts);
}

static int render_ring(const options *base, vksky_context *ctx, vksky_scene *scene, vksky_renderer *r, int slots,
                       FILE *trace)
{
    host_ring ring;
    /* Several frames encode at once where there are cores to spare (host_ring_consumers_wanted), each on a share of
     * the encode threads: what stays serial per frame (its float conversion, header, fsync) then overlaps. */
    int consumers = host_ring_consumers_wanted((long)base->width * base->height);
    if (consumers > 1 && slots < consumers + 1) slots = consumers + 1;
    int threads = io_encode_threads_all();
    int share = consumers > 1 ? threads / consumers : 0;
    if (consumers > 1 && threads > 1 && share < 2) share = 2;   /* a PNG's blocks need > 1 (png_parallel.h) */
    consumer_state state = {.base = base, .ring = &ring, .share = share};
    if (host_ring_create(&ring, ctx, r, slots, consumers, consume_frame, retire_frame, &state, trace)) return 1;
    stage_begin();
    int lut_computations = 0, status = 0;
    bool first = true;
    for (int i = base->frame_first; i <= base->frame_last && !stop_requested() && status == 0; ++i) {
        stage_mark produce_start = stage_mark_now();
        frame_job *j = calloc(1, sizeof *j);
        if (!j || sequence_frame_options(base, i, &j->f)) {
            free(j);
            status = 1;
            break;
        }
        /* --skip-existing: the progress lines stay in frame order and the counts settled, so the frames before this
         * one are written (the consumer idle) before a kept frame's line is printed. Only where the files exist. */
        if (base->skip_existing && sequence_resume_exists(&j->f, i)) {
            status = host_ring_settle(&ring);
            if (status == 0 && sequence_resume_skip(&j->f, i, frame_count(base), state.done + state.skipped + 1,
                                                    base->frame_last - base->frame_first + 1)) {
                ++state.skipped;
                free(j);
                continue;
            }
            if (status) {
                free(j);
                break;
            }
        }
        j->frame = i, j->seq = ring.submitted;
        if (set_frame_scene(base, i, scene, r, &ring, first, &j->luts)) {
            free(j);
            status = 1;
            break;
        }
        first = false;
        lut_computations += j->luts;
        host_view v = view_of(&j->f);
        long seq = j->seq;   /* j belongs to the ring once submitted (a consumer frees it) */
        status = host_ring_submit(&ring, &v, j);
        /* A LUT cache miss on the first frame: its LUTs into the cache for the next start, as the serial loop does
         * (vksky_renderer_store_luts: a submission of its own after this frame's, waited for; nothing on a hit).
         * Only the first frame's: a store waits for the queue, and an animated medium's later frames would each
         * stall the ring. */
        if (status == 0 && seq == 0 && vksky_renderer_store_luts(r) != VKSKY_SUCCESS) status = 1;
        stage_add_since(STAGE_PRODUCE, produce_start);
    }
    int consumed = host_ring_finish(&ring);
    if (status == 0) status = consumed;
    if (base->timings && status == 0)
        stage_report(stderr, "sequence", state.done, "frame", ring.consumers, share ? share : threads);
    if (stop_requested()) return 1;   /* frames already written are whole and stay; stop_status says the rest */
    if (status == 0) sequence_summary_line(base, state.done, state.skipped, lut_computations);
    return status;
}

int sequence_host_render(const options *base, vksky_context *ctx, vksky_scene *scene, vksky_renderer *r,
                         host_async *async, FILE *trace)
{
    /* The ring pays off from two frames on; one frame keeps the serial path, as do the LUTs on the compute queue (one
     * frame at a time: host_async.h) and the tests' VKSKY_FRAMES loop. */
    int slots = async || getenv("VKSKY_FRAMES") ? 0 : host_ring_slots_wanted();
    if (slots >= 2 && sequence_active(base) && base->frame_last > base->frame_first)
        return render_ring(base, ctx, scene, r, slots, trace);
    return render_serial(base, ctx, scene, r, async, trace);
}
