/* --quality auto (issue 16): for every scene class the configuration it picks is a point on the measured
 * speed/accuracy front of that class, in the table of each device kind (quality_table.h: sky GPU ms on an H100;
 * quality_table_cpu.h: CPU ms per frame on lavapipe; both measured by tools/tradeoff): no measured configuration is
 * both faster and more accurate, its error is within the stated budget (max(1 %, 1.25 x the best error of the
 * class)), and nothing cheaper meets that budget. The lesson's preset still resolves by name. No GPU. */
#include "app/quality/quality.h"
#include "app/quality/quality_table.h"
#include "app/quality/quality_table_cpu.h"
#include "app/quality/quality_horizon_table.h"
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "check.h"

/* The table row of a configuration on a scene class (by name; the presets measured under their own names). */
static const quality_measurement *row_of(const quality_measurement *table, int count, const char *config, int scene)
{
    for (int i = 0; i < count; ++i)
        if (table[i].scene == scene && !strcmp(table[i].config, config)) return &table[i];
    return NULL;
}

static void check_table(const quality_measurement *table, int count, bool cpu_device, const char *device)
{
    for (int scene = 0; scene < QUALITY_SCENE_COUNT; ++scene) {
        if (!row_of(table, count, "medium", scene)) continue;   /* a class this table has no rows for */
        const quality_scene *s = &quality_scenes[scene];
        double measured = 0;
        const quality_config *q = quality_auto(quality_class_bit(s->altitude_km, s->sun_elevation_deg), cpu_device,
                                               &measured);
        CHECK(q != NULL, "%s %s: auto picked nothing", device, s->name);
        if (!q) continue;
        const quality_measurement *m = row_of(table, count, q->name, scene);
        CHECK(m != NULL, "%s %s: '%s' has no measurement", device, s->name, q->name);
        if (!m) continue;
        double best = INFINITY;
        for (int i = 0; i < count; ++i)
            if (table[i].scene == scene) best = fmin(best, table[i].err_mean);
        double budget = fmax(0.01, 1.25 * best);
        CHECK(m->err_mean <= budget, "%s %s: '%s' error %g over the budget %g", device, s->name, q->name, m->err_mean,
              budget);
        for (int i = 0; i < count; ++i) {
            const quality_measurement *o = &table[i];
            if (o->scene != scene) continue;
            CHECK(!(o->gpu_ms < m->gpu_ms && o->err_mean < m->err_mean), "%s %s: '%s' is dominated by '%s'", device,
                  s->name, q->name, o->config);
            CHECK(!(o->gpu_ms < m->gpu_ms && o->err_mean <= budget), "%s %s: '%s' (%g ms) is cheaper within the budget",
                  device, s->name, o->config, o->gpu_ms);
        }
        printf("%-4s %-13s auto = %-26s %9.4f ms, mean error %.3g %% (best measured %.3g %%)\n", device, s->name,
               q->name, m->gpu_ms, 100 * m->err_mean, 100 * best);
    }
}

/* A sequence's class set (every pair of classes, and all six): the one configuration auto keeps for all frames is
 * within each class's budget, and no measured configuration that is within every class's budget costs less on its
 * dearest class. Searched here over the sweep's configurations by name, not over table rows as quality.c does. */
static void check_sets(const quality_measurement *table, int count, bool cpu_device, const char *device)
{
    double budget[QUALITY_SCENE_COUNT];
    for (int c = 0; c < QUALITY_SCENE_COUNT; ++c) {
        double best = INFINITY;
        for (int i = 0; i < count; ++i)
            if (table[i].scene == c) best = fmin(best, table[i].err_mean);
        budget[c] = fmax(0.01, 1.25 * best);
    }
    unsigned measured_classes = 0;   /* the classes this table has rows for */
    for (int i = 0; i < count; ++i) measured_classes |= 1u << table[i].scene;
    unsigned sets[24];
    int set_count = 0;
    for (int a = 0; a < QUALITY_SCENE_COUNT; ++a)
        for (int b = a + 1; b < QUALITY_SCENE_COUNT && set_count < 23; b += 2)
            if (measured_classes >> a & 1u && measured_classes >> b & 1u) sets[set_count++] = 1u << a | 1u << b;
    sets[set_count++] = measured_classes;
    for (int k = 0; k < set_count; ++k) {
        double measured = 0;
        const quality_config *q = quality_auto(sets[k], cpu_device, &measured);
        double cheapest = INFINITY;   /* the dearest-class cost of the best configuration that serves the set */
        for (int n = -4; n < quality_sweep_count; ++n) {
            const char *name = n < 0 ? quality_presets[n + 4].name : quality_sweep[n].name;
            double cost = 0;
            bool serves = true;
            for (int c = 0; c < QUALITY_SCENE_COUNT; ++c) {
                if (!(sets[k] >> c & 1u)) continue;
                const quality_measurement *m = row_of(table, count, name, c);
                serves = serves && m && m->err_mean <= budget[c];
                if (m) cost = fmax(cost, m->gpu_ms);
            }
            if (serves) cheapest = fmin(cheapest, cost);
        }
        CHECK((q != NULL) == isfinite(cheapest), "%s set 0x%x: auto picked %s, the search found %g", device, sets[k],
              q ? q->name : "nothing", cheapest);
        if (!q) continue;
        double cost = 0;
        for (int c = 0; c < QUALITY_SCENE_COUNT; ++c) {
            if (!(sets[k] >> c & 1u)) continue;
            const quality_measurement *m = row_of(table, count, q->name, c);
            CHECK(m && m->err_mean <= budget[c], "%s set 0x%x: '%s' is over %s's budget", device, sets[k], q->name,
                  quality_scenes[c].name);
            if (m) cost = fmax(cost, m->gpu_ms);
        }
        CHECK(cost <= cheapest, "%s set 0x%x: '%s' costs %g, %g serves the set", device, sets[k], q->name, cost,
              cheapest);
    }
}

/* Issue 31: a table measured with other shaders or knobs than this build's fails, unless its rows are marked as
 * estimates (then the note is printed here, and --max-error prints it beside its pick). */
static void check_key(bool cpu_device, const char *device, bool marked_estimate)
{
    char key[96];
    quality_table_key(cpu_device, key, sizeof key);
    const char *recorded = quality_table_recorded_key(cpu_device);
    if (!strcmp(key, recorded)) {
        CHECK(quality_table_estimate(cpu_device) == NULL, "%s table: measured with this build, yet an estimate", device);
        return;
    }
    CHECK(marked_estimate, "%s table: measured with key %s, this build's is %s: re-measure it (tools/tradeoff "
          "--emit-table) or mark its rows as estimates", device, recorded, key);
    const char *why = quality_table_estimate(cpu_device);
    CHECK(why != NULL, "%s table: keys differ but no estimate note", device);
    fprintf(stderr, "note: the %s table's rows are estimates (%s): key %s, this build %s\n", device, why ? why : "?",
            recorded, key);
}

/* --max-error on the horizon bound (issue 26 item 5): on every class the horizon table covers and every budget, the
 * pick is the cheapest configuration whose frame mean AND horizon-band max (tools/tradeoff_horizon.h's table read
 * here directly) are within the budget, a configuration without a horizon row on a covered class refused; and at
 * least one budget on each table must refuse the configuration the frame mean alone would pick (so the refusal is
 * exercised, not merely allowed). Searched here over the table's rows, not through quality.c's pick_from. */
static const quality_horizon *horizon_row(const char *config, int scene)
{
    for (int i = 0; i < quality_horizon_table_count; ++i)
        if (quality_horizon_table[i].scene == scene && !strcmp(quality_horizon_table[i].config, config))
            return &quality_horizon_table[i];
    return NULL;
}

static void check_horizon_refusals(const quality_measurement *table, int count, bool cpu_device, const char *device)
{
    static const double budgets[] = {0.003, 0.005, 0.01, 0.02, 0.05, 0.1, 0.15, 0.25, 0.5, 0.7};
    int refused = 0;
    for (int scene = 0; scene < QUALITY_SCENE_COUNT; ++scene) {
        bool covered = false;
        for (int i = 0; i < quality_horizon_table_count; ++i) covered = covered || quality_horizon_table[i].scene == scene;
        if (!covered || !row_of(table, count, "medium", scene)) continue;
        for (size_t b = 0; b < sizeof budgets / sizeof budgets[0]; ++b) {
            double e = budgets[b];
            const quality_measurement *by_mean = NULL, *by_both = NULL;
            for (int i = 0; i < count; ++i) {
                const quality_measurement *m = &table[i];
                if (m->scene != scene || m->err_mean > e) continue;
                if (!by_mean || m->gpu_ms < by_mean->gpu_ms) by_mean = m;
                const quality_horizon *h = horizon_row(m->config, scene);
                if (h && h->max <= e && (!by_both || m->gpu_ms < by_both->gpu_ms)) by_both = m;
            }
            double measured = 0;
            const quality_config *q = quality_pick(e, 1u << scene, cpu_device, &measured);
            CHECK((q != NULL) == (by_both != NULL), "%s %s --max-error %g: picked %s, expected %s", device,
                  quality_scenes[scene].name, e, q ? q->name : "nothing", by_both ? by_both->config : "nothing");
            if (q && by_both) {
                const quality_measurement *m = row_of(table, count, q->name, scene);
                CHECK(m && fabs(m->gpu_ms - by_both->gpu_ms) < 1e-9, "%s %s --max-error %g: picked %s, the cheapest "
                      "within the mean and the horizon bound is %s", device, quality_scenes[scene].name, e, q->name,
                      by_both->config);
                const quality_horizon *h = horizon_row(q->name, scene);
                CHECK(h && h->max <= e, "%s %s --max-error %g: %s's horizon max %g over the budget", device,
                      quality_scenes[scene].name, e, q->name, h ? h->max : INFINITY);
            }
            /* A refusal on a measured horizon max (not merely a missing row): the bound at work. */
            const quality_horizon *hm = by_mean ? horizon_row(by_mean->config, scene) : NULL;
            if (hm && hm->max > e && (!by_both || by_both->gpu_ms > by_mean->gpu_ms)) {
                ++refused;
                printf("%s %-13s --max-error %-5g refuses %s on the horizon bound (mean %.4f, horizon max %.4f) -> %s\n",
                       device, quality_scenes[scene].name, e, by_mean->config, by_mean->err_mean,
                       horizon_row(by_mean->config, scene) ? horizon_row(by_mean->config, scene)->max : INFINITY,
                       by_both ? by_both->config : "nothing");
            }
        }
    }
    CHECK(refused > 0, "%s: no budget refuses a measured configuration on its horizon max: the check is not exercised",
          device);
}

int main(void)
{
#ifdef QUALITY_TABLE_ESTIMATE
    check_key(false, "GPU", true);
#else
    check_key(false, "GPU", false);
#endif
#ifdef QUALITY_TABLE_CPU_ESTIMATE
    check_key(true, "CPU", true);
#else
    check_key(true, "CPU", false);
#endif
    check_sets(quality_table, quality_table_count, false, "GPU");
    check_sets(quality_table_cpu, quality_table_cpu_count, true, "CPU");
    check_table(quality_table, quality_table_count, false, "GPU");
    check_table(quality_table_cpu, quality_table_cpu_count, true, "CPU");
    check_horizon_refusals(quality_table, quality_table_count, false, "GPU");
    check_horizon_refusals(quality_table_cpu, quality_table_cpu_count, true, "CPU");
    /* The CPU device's daytime point is --quality cpu, within 1 % on every daytime class. */
    const quality_config *cpu = quality_preset("cpu");
    CHECK(cpu != NULL, "--quality cpu does not resolve");
    for (int scene = 0; cpu && scene < 3; ++scene) {
        const quality_measurement *m = row_of(quality_table_cpu, quality_table_cpu_count, cpu->name, scene);
        CHECK(m && m->err_mean <= 0.01, "--quality cpu on %s: not measured within 1 %%", quality_scenes[scene].name);
    }
    const quality_config *lesson = quality_preset("lesson");
    CHECK(lesson && lesson->mode == SKY_CHOICE_MARCH && lesson->steps == 32 && lesson->render_scale == 1.0,
          "--quality lesson is not the 32-step march at full size");
    CHECK(quality_preset("auto") == NULL, "auto is not a fixed preset");
    if (check_failures) printf("%d check_failures\n", check_failures);
    return check_failures != 0;
}
