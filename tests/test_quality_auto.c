/* --quality auto (issue 16): for every scene class the configuration it picks is a point on the measured
 * speed/accuracy front of that class (quality_table.h, measured by tools/tradeoff): no measured configuration is
 * both faster and more accurate, its error is within the stated budget (max(1 %, 1.25 x the best error of the
 * class)), and nothing cheaper meets that budget. The lesson's preset still resolves by name. No GPU. */
#include "app/quality.h"
#include "app/quality_table.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

static int failures;
#define CHECK(cond, ...) do { if (!(cond)) { printf("FAIL: "); printf(__VA_ARGS__); printf("\n"); ++failures; } } while (0)

/* The table row of a configuration on a scene class (by name; the presets measured under their own names). */
static const quality_measurement *row_of(const char *config, int scene)
{
    for (int i = 0; i < quality_table_count; ++i)
        if (quality_table[i].scene == scene && !strcmp(quality_table[i].config, config)) return &quality_table[i];
    return NULL;
}

int main(void)
{
    for (int scene = 0; scene < 6; ++scene) {
        const quality_scene *s = &quality_scenes[scene];
        double measured = 0;
        const char *name = NULL;
        const quality_config *q = quality_auto(s->altitude_km, s->sun_elevation_deg, &measured, &name);
        CHECK(q != NULL, "%s: auto picked nothing", s->name);
        if (!q) continue;
        const quality_measurement *m = row_of(q->name, scene);
        CHECK(m != NULL, "%s: '%s' has no measurement", s->name, q->name);
        if (!m) continue;
        double best = INFINITY;
        for (int i = 0; i < quality_table_count; ++i)
            if (quality_table[i].scene == scene) best = fmin(best, quality_table[i].err_mean);
        double budget = fmax(0.01, 1.25 * best);
        CHECK(m->err_mean <= budget, "%s: '%s' error %g over the budget %g", s->name, q->name, m->err_mean, budget);
        for (int i = 0; i < quality_table_count; ++i) {
            const quality_measurement *o = &quality_table[i];
            if (o->scene != scene) continue;
            CHECK(!(o->gpu_ms < m->gpu_ms && o->err_mean < m->err_mean), "%s: '%s' is dominated by '%s'", s->name,
                  q->name, o->config);
            CHECK(!(o->gpu_ms < m->gpu_ms && o->err_mean <= budget), "%s: '%s' (%g ms) is cheaper within the budget",
                  s->name, o->config, o->gpu_ms);
        }
        printf("%-13s auto = %-16s %.4f ms (H200 1080p sky), mean error %.3g %% (best measured %.3g %%)\n", s->name,
               q->name, m->gpu_ms, 100 * m->err_mean, 100 * best);
    }
    const quality_config *lesson = quality_preset("lesson");
    CHECK(lesson && lesson->mode == SKY_CHOICE_MARCH && lesson->steps == 32 && lesson->render_scale == 1.0,
          "--quality lesson is not the 32-step march at full size");
    CHECK(quality_preset("auto") == NULL, "auto is not a fixed preset");
    if (failures) printf("%d failures\n", failures);
    return failures != 0;
}
