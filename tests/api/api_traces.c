/* Per-context traces (issue 25 item 2): two contexts on one host device, a renderer each, their frames recorded in
 * turn into two command buffers. Context A traces barriers (VKSKY_TRACE_BARRIERS), context B the pass list only
 * (VKSKY_TRACE_PASSES); a third context C has no trace. Checked:
 *  - separation: while A records, B's trace gets no line, and the other way round; C's frames add a line to
 *    neither; B's lines are all "pass ..." (the pass list), A's include barrier and batch lines;
 *  - completeness: in each of A's frames, the barrier lines not dropped add up to the images + buffers + memory
 *    counted by the batch lines (a vkCmdPipelineBarrier2 each): no barrier line missing or foreign; A's bloom passes
 *    (bloom on) are in A's trace and none in B's (bloom off);
 *  - independence: A's frame recorded once B and C are gone is line for line the frame recorded between them;
 *  - the frames run under validation + synchronization validation with no message. */
#include "api_host.h"

typedef struct trace_log {
    char lines[4096][160];
    int count;
} trace_log;

static void on_trace(void *user, const char *line)
{
    trace_log *t = user;
    if (t->count < 4096) snprintf(t->lines[t->count], sizeof t->lines[0], "%s", line);
    t->count++;
}

static bool starts(const char *s, const char *prefix) { return !strncmp(s, prefix, strlen(prefix)); }

/* Lines [from, to) of A's trace: barrier lines kept == the batches' counts. */
static void check_complete(const trace_log *t, int from, int to, const char *what)
{
    int barriers = 0, batched = 0, passes = 0;
    for (int i = from; i < to && i < 4096; ++i) {
        const char *l = t->lines[i];
        unsigned im = 0, bu = 0, me = 0;
        if (starts(l, "barrier ") && !strstr(l, " DROPPED")) barriers++;
        else if (starts(l, "batch ") && sscanf(strstr(l, "images="), "images=%u buffers=%u memory=%u", &im, &bu, &me) == 3)
            batched += (int)(im + bu + me);
        else if (starts(l, "pass ")) passes++;
        else HOST_CHECK(starts(l, "commands"), "%s: an unexpected line '%s'", what, l);
    }
    printf("%s: %d lines, %d passes, %d barriers, %d in batches\n", what, to - from, passes, barriers, batched);
    HOST_CHECK(barriers > 0 && barriers == batched, "%s: %d barrier lines, the batches count %d", what, barriers,
               batched);
    HOST_CHECK(passes > 0, "%s: no pass line", what);
}

static int count_bloom(const trace_log *t, int from, int to)
{
    int n = 0;
    for (int i = from; i < to && i < 4096; ++i) n += starts(t->lines[i], "pass ") && strstr(t->lines[i], "bloom");
    return n;
}

static vksky_renderer *make_renderer(vksky_context *c, bool bloom)
{
    vksky_renderer_desc d = {.abi_version = VKSKY_ABI_VERSION, .output = VKSKY_OUTPUT_DISPLAY, .width = 48,
                             .height = 32, .target_format = VK_FORMAT_R8G8B8A8_UNORM, .quality = "lesson",
                             .bloom = bloom, .units = VKSKY_UNITS_RELATIVE};
    vksky_renderer *r = NULL;
    if (vksky_renderer_create(c, &d, &r) != VKSKY_SUCCESS) {
        fprintf(stderr, "FAIL: vksky_renderer_create\n");
        exit(1);
    }
    return r;
}

static void frame(host *h, vksky_renderer *r)
{
    vksky_camera cam = {.origin_altitude_m = 1.0};
    vksky_camera_look(&cam, 0.0, 10.0, 75.0, 48.0 / 32.0, 0.1);
    vksky_frame f = {.camera = &cam, .color = host_image(h, VK_FORMAT_R8G8B8A8_UNORM), .force_luts = true};
    host_begin(h);
    HOST_CHECK(vksky_record(r, h->cmd, &f) == VKSKY_SUCCESS, "vksky_record");
    host_end_and_read(h);
}

int main(void)
{
    static trace_log ta, tb;
    host ha, hb, hc;
    host_create_device(&ha, NULL);
    hb = ha, hb.owns = false;   /* the same device, a target image and command buffer of their own */
    hc = hb;
    host_create_target(&ha, 48, 32, VK_FORMAT_R8G8B8A8_UNORM);
    host_create_target(&hb, 48, 32, VK_FORMAT_R8G8B8A8_UNORM);
    host_create_target(&hc, 48, 32, VK_FORMAT_R8G8B8A8_UNORM);
    vksky_context_desc cd = host_context_desc(&ha, NULL);
    vksky_context *a = NULL, *b = NULL, *c = NULL;
    if (vksky_context_create(&cd, &a) || vksky_context_create(&cd, &b) || vksky_context_create(&cd, &c)) return 1;
    HOST_CHECK(vksky_context_set_trace(a, 1u << 7, on_trace, &ta) == VKSKY_ERROR_INVALID_ARGUMENT,
               "an unknown trace bit is refused");
    HOST_CHECK(vksky_context_set_trace(NULL, VKSKY_TRACE_PASSES, on_trace, &ta) == VKSKY_ERROR_INVALID_ARGUMENT,
               "a NULL context is refused");
    vksky_context_set_trace(a, VKSKY_TRACE_BARRIERS, on_trace, &ta);
    vksky_context_set_trace(b, VKSKY_TRACE_PASSES, on_trace, &tb);

    vksky_renderer *ra = make_renderer(a, true);
    HOST_CHECK(tb.count == 0, "A's renderer's creation put %d lines into B's trace", tb.count);
    int a_made = ta.count;
    vksky_renderer *rb = make_renderer(b, false);
    HOST_CHECK(ta.count == a_made, "B's renderer's creation put %d lines into A's trace", ta.count - a_made);
    int b_made = tb.count;
    vksky_renderer *rc = make_renderer(c, true);
    HOST_CHECK(ta.count == a_made && tb.count == b_made, "C's creation (no trace) put lines into A's or B's trace");

    /* A, B, C, A, B in turn. */
    int a0 = ta.count, b0 = tb.count;
    frame(&ha, ra);
    int a1 = ta.count;
    HOST_CHECK(tb.count == b0, "A's frame put %d lines into B's trace", tb.count - b0);
    frame(&hb, rb);
    int b1 = tb.count;
    HOST_CHECK(ta.count == a1, "B's frame put %d lines into A's trace", ta.count - a1);
    frame(&hc, rc);
    HOST_CHECK(ta.count == a1 && tb.count == b1, "C (no trace) put lines into A's (%d) or B's (%d)", ta.count - a1,
               tb.count - b1);
    frame(&ha, ra);
    int a2 = ta.count;
    HOST_CHECK(tb.count == b1, "A's second frame put lines into B's trace");
    frame(&hb, rb);
    int b2 = tb.count;
    HOST_CHECK(ta.count == a2, "B's second frame put lines into A's trace");

    check_complete(&ta, a0, a1, "A frame 1");
    check_complete(&ta, a1, a2, "A frame 2");
    for (int i = b0; i < b2 && i < 4096; ++i) HOST_CHECK(starts(tb.lines[i], "pass "), "B: '%s'", tb.lines[i]);
    HOST_CHECK(b1 > b0 && b2 - b1 == b1 - b0, "B's frames: %d and %d pass lines", b1 - b0, b2 - b1);
    HOST_CHECK(count_bloom(&ta, a1, a2) > 0 && count_bloom(&tb, b0, b2) == 0,
               "bloom passes: %d in A's frame (bloom on), %d in B's (bloom off)", count_bloom(&ta, a1, a2),
               count_bloom(&tb, b0, b2));

    /* B and C gone: A's frame, line for line as recorded between them. */
    vksky_renderer_destroy(rb), vksky_renderer_destroy(rc);
    vksky_context_destroy(b), vksky_context_destroy(c);
    frame(&ha, ra);
    int a3 = ta.count;
    HOST_CHECK(a3 - a2 == a2 - a1, "A's frame alone: %d lines, between B's and C's: %d", a3 - a2, a2 - a1);
    for (int i = 0; a3 - a2 == a2 - a1 && a3 < 4096 && i < a3 - a2; ++i)
        HOST_CHECK(!strcmp(ta.lines[a1 + i], ta.lines[a2 + i]), "line %d: '%s' vs '%s'", i, ta.lines[a1 + i],
                   ta.lines[a2 + i]);
    HOST_CHECK(a3 < 4096, "the trace outgrew the test's log (%d lines)", a3);

    /* Off: no more lines. */
    vksky_context_set_trace(a, 0, NULL, NULL);
    frame(&ha, ra);
    HOST_CHECK(ta.count == a3, "A's trace off, %d lines still came", ta.count - a3);

    vksky_renderer_destroy(ra);
    vksky_context_destroy(a);
    host_destroy_target(&hc), host_destroy_target(&hb), host_destroy_target(&ha);
    host_destroy_device(&ha, NULL);
    HOST_CHECK(host_validation_messages == 0, "%u validation messages", host_validation_messages);
    printf("api_traces: A %d lines, B %d lines\n", a3, b2);
    return host_failures ? 1 : 0;
}
