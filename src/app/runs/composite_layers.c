/* The composite's inputs (composite_layers.h): the layer choice, reading, and the fixes a real render needs.
 *
 * Blender's multilayer EXR names a channel <ViewLayer>.<Pass>.<Channel>: "ViewLayer.Combined.R",
 * "ViewLayer.Position.X", "ViewLayer.Depth.Z", and the compositor's output "Composite.Combined.R". A view layer is
 * a candidate when it has a Combined pass; "Composite" is the compositor's (graded) image, never the render's, so
 * it is used only when named. */
#include "app/runs/composite_layers.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const COMPOSITOR = "Composite";

/* --- The file's channels ------------------------------------------------------------------------------------ */

static const io_exr_channel *find_channel(const io_exr_info *info, const char *name)
{
    for (int i = 0; i < info->channel_count; ++i)
        if (!strcmp(info->channels[i].name, name)) return &info->channels[i];
    return NULL;
}

/* "<prefix>.<c>" for each of the channel letters in `letters` present? (prefix "" = top level: "<c>"). */
static bool has_layer(const io_exr_info *info, const char *prefix, const char *letters)
{
    char name[520];
    for (const char *c = letters; *c; ++c) {
        snprintf(name, sizeof name, "%.510s%s%c", prefix, *prefix ? "." : "", *c);
        if (!find_channel(info, name)) return false;
    }
    return true;
}

/* The channel list for a message: "R, G, B, ViewLayer.Combined.R, ..." (the first dozen). */
static void list_channels(const io_exr_info *info, char *out, size_t size)
{
    out[0] = '\0';
    size_t used = 0;
    for (int i = 0; i < info->channel_count && i < 12; ++i) {
        int n = snprintf(out + used, size - used, "%s%s", i ? ", " : "", info->channels[i].name);
        if (n < 0 || (size_t)n >= size - used) break;
        used += (size_t)n;
    }
    if (info->channel_count > 12 && used + 8 < size) strcat(out, ", ...");
    if (info->channel_count == 0) snprintf(out, size, "no channels");
}

/* The view layers with a pass `pass` ("Combined"): the names before ".<pass>.<first letter>", in file order,
 * comma-separated into `list`; `skip_compositor` leaves out "Composite". Returns how many; `first` the first. */
static int view_layers_with(const io_exr_info *info, const char *pass, char letter, bool skip_compositor,
                            char *first, size_t first_size, char *list, size_t list_size)
{
    char suffix[64];
    snprintf(suffix, sizeof suffix, ".%s.%c", pass, letter);
    size_t ls = strlen(suffix), used = 0;
    int count = 0;
    if (list_size) list[0] = '\0';
    for (int i = 0; i < info->channel_count; ++i) {
        const char *n = info->channels[i].name;
        size_t ln = strlen(n);
        if (ln <= ls || strcmp(n + ln - ls, suffix) || ln - ls >= 256) continue;
        int vl = (int)(ln - ls);
        if (skip_compositor && vl == (int)strlen(COMPOSITOR) && !strncmp(n, COMPOSITOR, (size_t)vl)) continue;
        if (count == 0 && first) snprintf(first, first_size, "%.*s", vl, n);
        int k = snprintf(list + used, list_size - used, "%s%.*s", count ? ", " : "", vl, n);
        if (k > 0 && (size_t)k < list_size - used) used += (size_t)k;
        ++count;
    }
    return count;
}

/* The view layer of a named layer: "RenderLayer.Combined" -> "RenderLayer"; false (none implied) without a dot. */
static bool view_layer_of(const char *layer, char *out, size_t size)
{
    const char *dot = layer ? strrchr(layer, '.') : NULL;
    if (dot) snprintf(out, size, "%.*s", (int)(dot - layer), layer);
    return dot != NULL;
}

/* --- The choice --------------------------------------------------------------------------------------------- */

static int pick_view_layer(const composite_options *co, const io_exr_info *bi, char *vl, size_t size)
{
    char from_beauty[256] = "", from_position[256] = "", list[600];
    bool by_beauty = view_layer_of(co->beauty_layer, from_beauty, sizeof from_beauty);
    bool by_position = !co->position && view_layer_of(co->position_layer, from_position, sizeof from_position);
    const char *named[3] = {co->view_layer, by_beauty ? from_beauty : NULL, by_position ? from_position : NULL};
    const char *flag[3] = {"--view-layer", "--beauty-layer", "--position-layer"};
    /* Every flag that names a view layer must name the same one: the beauty and the position of one render. */
    int given = -1;
    for (int k = 0; k < 3; ++k) {
        if (!named[k]) continue;
        if (given >= 0 && strcmp(named[given], named[k])) {
            fprintf(stderr, "vksky: --composite: %s %s is from view layer '%s' but %s %s from '%s': the beauty and "
                            "the position must come from one view layer (one render)\n",
                    flag[k], k == 2 ? co->position_layer : k == 1 ? co->beauty_layer : co->view_layer, named[k],
                    flag[given], given == 2 ? co->position_layer : given == 1 ? co->beauty_layer : co->view_layer,
                    named[given]);
            return 2;
        }
        given = k;
    }
    if (given >= 0) {
        snprintf(vl, size, "%s", named[given]);
        return 0;
    }
    int count = view_layers_with(bi, "Combined", 'R', true, vl, size, list, sizeof list);
    if (count > 1) {
        fprintf(stderr, "vksky: --composite: %s has %d view layers (%s): choose one with --view-layer NAME\n",
                co->input, count, list);
        return 2;
    }
    if (count == 0) {
        vl[0] = '\0';
        if (!has_layer(bi, "", "RGB") && view_layers_with(bi, "Combined", 'R', false, NULL, 0, list, sizeof list)) {
            fprintf(stderr, "vksky: --composite: %s has only the compositor's output (Composite.Combined), not the "
                            "render's: save the view layer's passes, or name it with --view-layer Composite\n",
                    co->input);
            return 2;
        }
    }
    return 0;
}

static int no_layer(const io_exr_info *info, const char *path, const char *what, const char *prefix,
                    const char *letters, const char *how)
{
    char have[600];
    list_channels(info, have, sizeof have);
    fprintf(stderr, "vksky: --composite: %s: no %s layer '%s' (channels %s%s%s); %sthe file has %s\n", path, what,
            prefix, prefix, *prefix ? "." : "", letters, how, have);
    return 2;
}

int composite_pick_inputs(const composite_options *co, const io_exr_info *bi, const io_exr_info *pi,
                          const io_exr_info *di, composite_inputs *in)
{
    memset(in, 0, sizeof *in);
    in->position_path = co->position ? co->position : co->input;
    int rc = pick_view_layer(co, bi, in->view_layer, sizeof in->view_layer);
    if (rc) return rc;
    const char *vl = in->view_layer;
    char name[520];

    /* The beauty: as named, else <view layer>.Combined, else the top-level R, G, B(, A). */
    if (co->beauty_layer) snprintf(in->beauty.prefix, sizeof in->beauty.prefix, "%s", co->beauty_layer);
    else if (*vl) snprintf(in->beauty.prefix, sizeof in->beauty.prefix, "%s.Combined", vl);
    if (!has_layer(bi, in->beauty.prefix, "RGB"))
        return no_layer(bi, co->input, "beauty", in->beauty.prefix, "R,G,B[,A]",
                        co->beauty_layer ? "" : "expected <ViewLayer>.Combined.R,G,B,A or R,G,B,A (or --beauty-layer NAME); ");
    in->beauty.letters = has_layer(bi, in->beauty.prefix, "RGBA") ? "RGBA" : "RGB";

    /* The depth, from --depth FILE: Z, <any>.Depth.Z or R. */
    if (co->depth) {
        in->has_depth = true, in->depth_path = co->depth;
        char first[256] = "", list[600];
        if (has_layer(di, "", "Z")) in->depth.letters = "Z";
        else if (view_layers_with(di, "Depth", 'Z', false, first, sizeof first, list, sizeof list) == 1)
            snprintf(in->depth.prefix, sizeof in->depth.prefix, "%s.Depth", first), in->depth.letters = "Z";
        else if (has_layer(di, "", "R")) in->depth.letters = "R";
        else {
            char have[600];
            list_channels(di, have, sizeof have);
            fprintf(stderr, "vksky: --depth: %s: no depth channel: expected Z, one <ViewLayer>.Depth.Z or R; the file "
                            "has %s\n", co->depth, have);
            return 2;
        }
        return 0;
    }

    /* The position: as named; else in its own file (the view layer's, a single <any>.Position, or X,Y,Z / R,G,B);
     * else the view layer's Position pass, or its Depth pass. */
    const io_exr_info *pinfo = co->position ? pi : bi;
    layer_pick *p = &in->position;
    if (co->position_layer) {
        snprintf(p->prefix, sizeof p->prefix, "%s", co->position_layer);
    } else if (co->position) {
        char first[256] = "", list[600];
        snprintf(name, sizeof name, "%s.Position", vl);
        if (*vl && has_layer(pinfo, name, "XYZ")) snprintf(p->prefix, sizeof p->prefix, "%.500s", name);
        else if (view_layers_with(pinfo, "Position", 'X', false, first, sizeof first, list, sizeof list) == 1)
            snprintf(p->prefix, sizeof p->prefix, "%s.Position", first);
    } else {
        snprintf(p->prefix, sizeof p->prefix, "%s%sPosition", vl, *vl ? "." : "");
        snprintf(name, sizeof name, "%s%sDepth", vl, *vl ? "." : "");
        if (!has_layer(pinfo, p->prefix, "XYZ") && has_layer(pinfo, name, "Z")) {
            in->has_depth = true, in->depth_path = co->input;
            snprintf(in->depth.prefix, sizeof in->depth.prefix, "%.500s", name);
            in->depth.letters = "Z";
            return 0;
        }
        if (!has_layer(pinfo, p->prefix, "XYZ")) {
            char list[600];
            int others = view_layers_with(pinfo, "Position", 'X', false, NULL, 0, list, sizeof list);
            char how[800];
            snprintf(how, sizeof how, "%s%s%senable the Position (or Depth) pass of that view layer, or give "
                     "--position FILE.exr or --depth FILE.exr; ", others ? "view layers with a Position pass: " : "",
                     others ? list : "", others ? " (not used: another view layer is another render); " : "");
            return no_layer(pinfo, in->position_path, "position", p->prefix, "X,Y,Z", how);
        }
    }
    /* X, Y, Z; a position with just R, G, B (a plain image) is read as X, Y, Z. */
    p->letters = has_layer(pinfo, p->prefix, "XYZ") ? "XYZ" : has_layer(pinfo, p->prefix, "RGB") ? "RGB" : NULL;
    if (!p->letters) return no_layer(pinfo, in->position_path, "position", p->prefix, "X,Y,Z or R,G,B", "");
    in->has_position = true;
    snprintf(name, sizeof name, "%s%s%c", p->prefix, *p->prefix ? "." : "", p->letters[0]);
    const io_exr_channel *ch = find_channel(pinfo, name);
    in->position_half = ch && ch->pixel_type == 1;
    return 0;
}

/* "<prefix>.<letter>" for each letter of a pick into names[at...]. */
static int add_names(const layer_pick *p, char (*buf)[520], const char **names, int at)
{
    for (const char *c = p->letters; *c; ++c, ++at) {
        snprintf(buf[at], sizeof buf[at], "%.510s%s%c", p->prefix, *p->prefix ? "." : "", *c);
        names[at] = buf[at];
    }
    return at;
}

int composite_read_band(const char *beauty_path, const composite_inputs *in, int width, int first_row, int rows,
                        float *beauty, float *position)
{
    const layer_pick *second = in->has_depth ? &in->depth : &in->position;
    const char *second_path = in->has_depth ? in->depth_path : in->position_path;
    bool one_file = !strcmp(second_path, beauty_path);   /* one read: one pass over the file's chunks */
    char buf[8][520];
    const char *names[8];
    int nb = add_names(&in->beauty, buf, names, 0), count = add_names(second, buf, names, nb);
    size_t n = (size_t)width * rows;
    float *tmp = malloc(n * (size_t)count * sizeof(float));
    char err[512];
    if (!tmp) {
        fprintf(stderr, "vksky: --composite: out of memory for %dx%d pixels\n", width, rows);
        return 1;
    }
    int rc = one_file ? io_exr_read_rows(beauty_path, names, count, first_row, rows, tmp, err, sizeof err) : 0;
    /* Two files: the beauty's values first, the second's after them (the same layout as one read). */
    if (!one_file) {
        rc = io_exr_read_rows(beauty_path, names, nb, first_row, rows, tmp, err, sizeof err);
        if (rc == 0)
            rc = io_exr_read_rows(second_path, names + nb, count - nb, first_row, rows, tmp + n * (size_t)nb, err,
                                  sizeof err);
    }
    if (rc != 0) {
        fprintf(stderr, "vksky: --composite: %s\n", err);
        free(tmp);
        return 2;
    }
    int ns = count - nb;
    for (size_t i = 0; i < n; ++i) {
        const float *b = one_file ? tmp + (size_t)count * i : tmp + (size_t)nb * i;
        const float *p = one_file ? b + nb : tmp + n * (size_t)nb + (size_t)ns * i;
        for (int c = 0; c < 4; ++c) {
            beauty[4 * i + c] = c < nb ? b[c] : 1.0f;   /* no alpha: covered */
            position[4 * i + c] = c < ns ? p[c] : c == 3 ? 1.0f : 0.0f;
        }
    }
    free(tmp);
    return 0;
}

/* --- Fit to composite ------------------------------------------------------------------------------------------ */

/* A pixel's position as a renderer leaves it when nothing was hit by the sample it came from: (0, 0, 0) (Blender,
 * Cycles' one-sample Position pass) or not finite. */
static bool position_missing(const float *p)
{
    return !(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2])) || (p[0] == 0.0f && p[1] == 0.0f && p[2] == 0.0f);
}

void composite_fix_positions(const float *beauty, float *position, const float *depth, const composite_band *band,
                             const composite_view *v, bool position_half, composite_fixups *out)
{
    int width = band->width, height = band->frame_height;
    size_t n = (size_t)width * band->rows;
    size_t core0 = (size_t)(band->core_row - band->first_row) * width, core1 = core0 + (size_t)band->core_rows * width;
    /* Depth (camera-space Z, Blender's and Nuke's convention: distance along the view axis, not along the ray) ->
     * the point on the pixel's ray at that depth: camera + z (forward + ndc.x tx right + ndc.y ty up). A renderer's
     * "nothing here" depth (huge: Blender writes 1e10) is no position. */
    double ty = tan(0.5 * v->fov_y_deg * 3.14159265358979323846 / 180.0), tx = ty * width / height;
    for (size_t i = 0; depth && i < n; ++i) {
        float z = depth[4 * i], *p = position + 4 * i;
        double nx = (2.0 * ((double)(i % (size_t)width) + 0.5) / width - 1.0) * tx;
        double ny = (1.0 - 2.0 * ((double)(i / (size_t)width + (size_t)band->first_row) + 0.5) / height) * ty;
        bool ok = isfinite(z) && z > 0.0f && z < 1e9f;
        for (int k = 0; k < 3; ++k)
            p[k] = ok ? (float)(v->camera[k] + z * (v->forward[k] + nx * v->right[k] + ny * v->up[k])) : NAN;
        p[3] = 1.0f;
    }
    /* 1: missing; 2: overflowed half (inf where the renderer had a finite point beyond 65504 units: no position,
     * and not one to borrow from a neighbour, which is nearer). */
    unsigned char *missing = calloc(n, 1);
    if (!missing) return;   /* nothing repaired: those pixels keep the beauty */
    for (size_t i = 0; i < n; ++i) {
        const float *p = position + 4 * i;
        bool overflow = position_half && (isinf(p[0]) || isinf(p[1]) || isinf(p[2]));
        missing[i] = overflow ? 2 : position_missing(p);
        if (i < core0 || i >= core1) continue;   /* counted in the band whose core it is */
        out->overflowed += overflow && beauty[4 * i + 3] > 0.0f;
        out->opaque += missing[i] == 1 && beauty[4 * i + 3] >= 0.999f;   /* an opaque film: hit nothing, alpha 1 */
    }
    /* Edge pixels: the nearest neighbour (within 3 pixels) with a position and some coverage; among the equally
     * near, the one whose coverage is closest to this pixel's: the pixels along one edge of one surface are
     * covered alike (a horizon row, a silhouette), the interior behind them and the other surface less so. Read
     * from the original positions only (a repaired pixel lends nothing). */
    for (size_t i = core0; i < core1; ++i) {
        float *p = position + 4 * i, alpha = beauty[4 * i + 3];
        if (!(alpha > 0.0f) || missing[i] != 1) continue;
        int x = (int)(i % (size_t)width), y = (int)(i / (size_t)width), best_d2 = 1 << 30;
        long best = -1;
        float best_da = 2.0f;
        for (int dy = -COMPOSITE_BAND_MARGIN; dy <= COMPOSITE_BAND_MARGIN; ++dy)
            for (int dx = -COMPOSITE_BAND_MARGIN; dx <= COMPOSITE_BAND_MARGIN; ++dx) {
                int xx = x + dx, yy = y + dy, d2 = dx * dx + dy * dy;
                if (xx < 0 || yy < 0 || xx >= width || yy >= band->rows || d2 > best_d2) continue;
                size_t j = (size_t)yy * width + xx;
                float a = beauty[4 * j + 3], da = fabsf(a - alpha);
                if (missing[j] || !(a > 0.0f) || (d2 == best_d2 && da >= best_da)) continue;
                best = (long)j, best_d2 = d2, best_da = da;
            }
        if (best >= 0) {
            memcpy(p, position + 4 * (size_t)best, 3 * sizeof(float));
            ++out->repaired;
        } else {
            p[0] = p[1] = p[2] = NAN;
            ++out->unrepaired;
        }
    }
    for (size_t i = 0; i < n; ++i)
        if (position_missing(position + 4 * i)) position[4 * i] = position[4 * i + 1] = position[4 * i + 2] = NAN;
    free(missing);
}
