/* --skip-existing (sequence_resume.h). */
#include "app/runs/sequence_resume.h"
#include "app/runs/exr_header.h"
#include "app/cli/options_sequence.h"
#include "io/exr_meta.h"
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/* A --render value's file for a frame: the pattern filled in, or a value without one %d as it is. */
static bool frame_file(const char *output, int frame, char *path, size_t size)
{
    if (sequence_pattern_kind(output) == 1) return sequence_output_path(output, frame, path, size);
    return (size_t)snprintf(path, size, "%s", output) < size;
}

static bool is_exr(const char *path)
{
    size_t n = strlen(path);
    return n > 4 && strcasecmp(path + n - 4, ".exr") == 0;
}

/* Is the EXR at `path` frame `frame` of the scene *f renders? Its header against the one this job would write: the
 * frame number, then the effective scene (view, sun, medium, size, quality knobs and the version: what the pixels
 * depend on). The command line is not compared: the same frame asked for in other words is the same picture. */
static bool exr_is_this_frame(const char *path, const options *f, int frame, char *why, size_t why_size)
{
    char err[512];
    int got = -1;
    int rc = io_exr_read_int_attr(path, EXR_HEADER_FRAME, &got, err, sizeof err);
    if (rc != 0) {
        snprintf(why, why_size, rc < 0 ? "cannot be read as an EXR" : "has no " EXR_HEADER_FRAME " (no frame of a "
                 "vksky sequence)");
        return false;
    }
    if (got != frame) {
        snprintf(why, why_size, "is frame %d, not %d", got, frame);
        return false;
    }
    exr_header h;
    if (exr_header_build(&h, f, frame) != 0) {
        snprintf(why, why_size, "cannot be checked (out of memory)");
        return false;
    }
    char *scene = NULL;
    rc = io_exr_read_string_attr(path, EXR_HEADER_SCENE, &scene, err, sizeof err);
    bool same = rc == 0 && !strcmp(scene, h.scene_json);
    if (!same) snprintf(why, why_size, "is frame %d of another scene (its " EXR_HEADER_SCENE " is not this job's)", frame);
    free(scene);
    exr_header_free(&h);
    return same;
}

bool sequence_resume_exists(const options *f, int frame)
{
    for (int k = 0; k < f->output_count; ++k) {
        char path[PATH_MAX];
        struct stat st;
        if (!frame_file(f->outputs[k], frame, path, sizeof path) || stat(path, &st) != 0 || !S_ISREG(st.st_mode))
            return false;
    }
    return f->output_count > 0;
}

bool sequence_resume_skip(const options *f, int frame, int count, int job_done, int job_size)
{
    char first[PATH_MAX] = "";
    /* Every file there first: a missing one means the frame is rendered anyway (no note needed). */
    for (int k = 0; k < f->output_count; ++k) {
        char path[PATH_MAX];
        struct stat st;
        if (!frame_file(f->outputs[k], frame, path, sizeof path) || stat(path, &st) != 0 || !S_ISREG(st.st_mode))
            return false;
        if (k == 0) snprintf(first, sizeof first, "%s", path);
    }
    for (int k = 0; k < f->output_count; ++k) {
        char path[PATH_MAX], why[160];
        if (!frame_file(f->outputs[k], frame, path, sizeof path) || !is_exr(path)) continue;
        if (!exr_is_this_frame(path, f, frame, why, sizeof why)) {
            fprintf(stderr, "vksky: frame %d: %s %s; rendering it again\n", frame, path, why);
            return false;
        }
    }
    fprintf(stderr, "vksky: frame %d (%d of %d; %d/%d of this job): %s, skipped (written before)\n", frame, frame + 1,
            count, job_done, job_size, first);
    return true;
}
