/* Environment maps and bands through the API (vksky_frame_band, issue 25), against the command-line tool's own band
 * renderer (app/runs/tiles.c: its own renderer, its own readback, its own PNG writer):
 *   api_bands VKSKY_BIN: for an equirect map, a cube map and a fisheye, a host renders the map in bands of 16 rows
 *   (each drawn with one row more above and below, the rows the host drops, as tiles.c does) through a readback
 *   renderer of a command line's scene, and puts the bands together: its display pixels equal `vksky --render` of the
 *   same map in the same bands (VKSKY_TILE_PIXELS; within 1/255). Then auto exposure: each band meters only its own rows (meter_first_row/meter_rows), the host
 *   adds count ln(log_average) over the bands; the log-average equals the one-band frame's meter within 1e-3 EV and
 *   counts the same pixels.
 * Validation + synchronization validation on throughout; any message fails. */
#include "api_host.h"
#include "io/png_io.h"
#include <math.h>
#include <stdint.h>

enum { BAND = 16 };   /* the CLI's bands at VKSKY_TILE_PIXELS = width x 16 */

typedef struct map_case {
    const char *projection;         /* the CLI's word */
    vksky_projection type;
    uint32_t width, height;         /* the whole image: --width W makes these */
} map_case;

/* The CLI's map: `vksky --render` at a fixed exposure, read back as RGBA. */
static uint8_t *cli_map(const char *vksky, const char *dir, const map_case *m, char *const *args, int argc)
{
    char path[512], cmd[2000], err[200];
    snprintf(path, sizeof path, "%s/cli_%s.png", dir, m->projection);
    int n = snprintf(cmd, sizeof cmd, "VKSKY_TILE_PIXELS=%u %s --validate --quiet --render %s", m->width * BAND, vksky,
                     path);
    for (int i = 1; i < argc; ++i) n += snprintf(cmd + n, sizeof cmd - (size_t)n, " %s", args[i]);
    if (system(cmd) != 0) {
        fprintf(stderr, "FAIL: %s\n", cmd);
        exit(1);
    }
    int w = 0, h = 0;
    uint8_t *rgba = NULL;
    if (io_read_png(path, &w, &h, &rgba, err, sizeof err) != 0 || w != (int)m->width || h != (int)m->height) {
        fprintf(stderr, "FAIL: %s: %s (%dx%d)\n", path, err, w, h);
        exit(1);
    }
    return rgba;
}

/* One frame recorded, submitted and waited for; its readback. */
static vksky_readback render(host *h, vksky_renderer *r, const vksky_frame *f)
{
    host_begin(h);
    vksky_result res = vksky_record(r, h->cmd, f);
    HOST_CHECK(res == VKSKY_SUCCESS, "vksky_record: %s", vksky_result_name(res));
    host_end_submit_wait(h);
    vksky_readback px = {0};
    res = vksky_renderer_get_readback(r, &px);
    HOST_CHECK(res == VKSKY_SUCCESS && px.display_rgba8, "vksky_renderer_get_readback: %s", vksky_result_name(res));
    if (!px.display_rgba8) exit(1);
    return px;
}

static vksky_renderer *band_renderer(vksky_context *c, const vksky_scene *scene, uint32_t width, uint32_t height)
{
    vksky_readback_config rb = {.type = VKSKY_STRUCTURE_TYPE_READBACK_CONFIG};
    vksky_renderer_desc d = host_readback_desc(&rb, scene, width, height, false);
    return host_renderer(c, &d);
}

/* The map in bands of BAND rows, each with a row above and below (dropped), into `out` (whole image, RGBA8); with
 * auto exposure, the bands' metered sums of logs and counts. */
static void render_bands(host *h, vksky_renderer *r, const map_case *m, bool metered, uint8_t *out, double *log_sum,
                         double *count)
{
    *log_sum = *count = 0.0;
    for (uint32_t y = 0; y < m->height; y += BAND) {
        uint32_t rows = m->height - y < BAND ? m->height - y : BAND;
        vksky_auto_exposure ae = {.type = VKSKY_STRUCTURE_TYPE_AUTO_EXPOSURE};
        vksky_frame_band band = {.type = VKSKY_STRUCTURE_TYPE_FRAME_BAND, .next = metered ? &ae : NULL,
                                 .projection = m->type, .whole_width = m->width, .whole_height = m->height,
                                 .first_row = (int32_t)y - 1, .meter_first_row = 1, .meter_rows = rows};
        vksky_frame f = {.next = &band, .exposure = 12.0};
        vksky_readback px = render(h, r, &f);
        memcpy(out + 4 * (size_t)y * m->width, px.display_rgba8 + 4 * (size_t)m->width, 4 * (size_t)rows * m->width);
        vksky_exposure e;
        if (metered && vksky_renderer_get_exposure(r, 0, &e) == VKSKY_SUCCESS && e.pixel_count > 0.0)
            *log_sum += e.pixel_count * log(e.log_average), *count += e.pixel_count;
    }
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: api_bands VKSKY_BIN\n");
        return 2;
    }
    char dir[] = "/tmp/vksky_api_bands_XXXXXX";
    if (!mkdtemp(dir)) return 1;
    vksky_context *c = host_own_context();
    host h;
    host_from_context(&h, c);
    host_create_target(&h, 4, 4, VK_FORMAT_R8G8B8A8_SRGB);   /* its command buffer and fence (the image unused) */
    const map_case cases[] = {{"equirect", VKSKY_PROJECTION_TYPE_EQUIRECT, 64, 32},
                              {"cubemap", VKSKY_PROJECTION_TYPE_CUBE, 12, 72},
                              {"fisheye", VKSKY_PROJECTION_TYPE_FISHEYE, 40, 40}};
    for (size_t k = 0; k < sizeof cases / sizeof *cases; ++k) {
        const map_case *m = &cases[k];
        char width[16];
        snprintf(width, sizeof width, "%u", m->width);
        /* --render-scale 1: bands are drawn at full size (the CLI's band renderer ignores the flag); --no-bloom: the CLI
         * draws this size in one band, with bloom for a fisheye, and bloom crosses band borders. */
        char *args[] = {"vksky", "--projection", (char *)m->projection, "--width", width, "--altitude", "0.001",
                        "--sun-elevation", "12", "--sun-azimuth", "40", "--exposure", "12", "--quality", "medium",
                        "--render-scale", "1", "--no-bloom"};
        int nargs = (int)(sizeof args / sizeof *args);
        uint8_t *want = cli_map(argv[1], dir, m, args, nargs);
        vksky_scene *scene = host_scene_of_args(nargs, args);
        vksky_renderer *banded = band_renderer(c, scene, m->width, BAND + 2);
        uint8_t *got = calloc(4 * (size_t)m->width * m->height, 1);
        double log_sum, count;
        render_bands(&h, banded, m, false, got, &log_sum, &count);
        int worst = 0;
        for (size_t i = 0; i < 4 * (size_t)m->width * m->height; ++i) {
            int d = abs((int)got[i] - (int)want[i]);
            if (d > worst) worst = d;
        }
        printf("%s %ux%u in bands of %d rows: display vs vksky --render: max %d of 255\n", m->projection, m->width,
               m->height, BAND, worst);
        HOST_CHECK(worst <= 1, "%s: the API's bands differ from the CLI's map by %d of 255", m->projection, worst);

        /* The whole map as one band into the host's own image (a renderer without readback: `vksky --bench` of a map),
         * copied out by the host: the CLI's map too. */
        {
            host t;
            host_from_context(&t, c);
            host_create_target(&t, m->width, m->height, VK_FORMAT_R8G8B8A8_SRGB);
            vksky_renderer_desc d = host_readback_desc(NULL, scene, m->width, m->height, false);
            vksky_renderer *own = host_renderer(c, &d);
            vksky_frame_band whole_band = {.type = VKSKY_STRUCTURE_TYPE_FRAME_BAND, .projection = m->type,
                                           .whole_width = m->width, .whole_height = m->height};
            vksky_frame f = {.next = &whole_band, .exposure = 12.0, .color = host_image(&t, VK_FORMAT_R8G8B8A8_SRGB)};
            host_begin(&t);
            vksky_result res = vksky_record(own, t.cmd, &f);
            HOST_CHECK(res == VKSKY_SUCCESS, "vksky_record into the host's image: %s", vksky_result_name(res));
            host_copy(&t);
            host_end_submit_wait(&t);
            const uint8_t *px = t.mapped;
            int worst_own = 0;
            for (size_t i = 0; i < 4 * (size_t)m->width * m->height; ++i) {
                int dd = abs((int)px[i] - (int)want[i]);
                if (dd > worst_own) worst_own = dd;
            }
            printf("%s %ux%u as one band into the host's image: vs vksky --render: max %d of 255\n", m->projection,
                   m->width, m->height, worst_own);
            HOST_CHECK(worst_own <= 1, "%s: the band into the host's image differs from the CLI's map by %d of 255",
                       m->projection, worst_own);
            vksky_renderer_destroy(own);
            host_destroy_target(&t);
        }

        /* Auto exposure: the bands' own rows, added by the host, against one band of the whole image. */
        render_bands(&h, banded, m, true, got, &log_sum, &count);
        vksky_renderer *whole = band_renderer(c, scene, m->width, m->height);
        vksky_auto_exposure ae = {.type = VKSKY_STRUCTURE_TYPE_AUTO_EXPOSURE};
        vksky_frame_band band = {.type = VKSKY_STRUCTURE_TYPE_FRAME_BAND, .next = &ae, .projection = m->type,
                                 .whole_width = m->width, .whole_height = m->height};
        vksky_frame f = {.next = &band};
        render(&h, whole, &f);
        vksky_exposure one;
        HOST_CHECK(vksky_renderer_get_exposure(whole, 0, &one) == VKSKY_SUCCESS, "get_exposure");
        double ev_bands = count > 0.0 ? log2(exp(log_sum / count) * 100.0 / 12.5) : NAN;
        printf("%s auto exposure: one band EV100 %.6f over %.0f px; %d-row bands %.6f over %.0f px\n", m->projection,
               one.ev100, one.pixel_count, BAND, ev_bands, count);
        HOST_CHECK(fabs(ev_bands - one.ev100) <= 1e-3 && count == one.pixel_count && count > 0.0,
                   "%s: banded EV100 %.6f (%.0f px) vs one band %.6f (%.0f px)", m->projection, ev_bands, count,
                   one.ev100, one.pixel_count);
        vksky_renderer_destroy(whole);
        vksky_renderer_destroy(banded);
        vksky_scene_destroy(scene);
        free(got);
        free(want);
    }
    host_destroy_target(&h);
    HOST_CHECK(vksky_context_validation_message_count(c) == 0, "%u validation messages",
               vksky_context_validation_message_count(c));
    vksky_context_destroy(c);
    char rm[600];
    snprintf(rm, sizeof rm, "rm -rf %s", dir);
    if (system(rm) != 0) fprintf(stderr, "api_bands: could not remove %s\n", dir);
    return host_failures ? 1 : 0;
}
