/* The frames of a sequence as values (sequence.c), without the renderer: what a host of include/vksky.h needs to
 * render one (app/runs/sequence_host.c) — each frame's options, its files, its progress lines. */
#ifndef VKSKY_APP_SEQUENCE_FRAMES_H
#define VKSKY_APP_SEQUENCE_FRAMES_H
#include "app/cli/options_struct.h"
#include <stdint.h>

/* A read-back frame's pixels: linear (RGBA half) and display (RGBA8), row 0 at the top. */
typedef struct frame_ring_pixels {
    const uint16_t *linear;
    const uint8_t *display;
} frame_ring_pixels;

/* Whether the options ask for a sequence (progress lines, frame numbers in the EXR header). */
bool sequence_active(const options *o);
/* Frame `frame`'s options (base itself when nothing is animated). 0 ok, 2 bad (one line printed). */
int sequence_frame_options(const options *base, int frame, options *out);
/* The animated flags' names and values at frame `frame` (what sequence_frame_options sets): their count. */
int sequence_frame_values(const options *base, int frame, const char **names, double *values);
/* An animated command line's quality chosen by the scene (auto, --max-error): chosen once for every scene class the
 * sequence's frames pass through, base parsed again under it (base->argv must be the command line). 0 ok, 2 bad. */
int sequence_choose_quality(options *base);
/* A frame's files (its --render values, EXRs with their header) from its read-back pixels: 0, or 1 with the line
 * printed. */
int sequence_write_frame(const options *o, const frame_ring_pixels *px, int frame, bool sequence);
/* The same, with the first file's path (for the progress line) into `first` (PATH_MAX bytes, the caller's). Safe on
 * several threads at once (frames encoded together). */
int sequence_write_outputs(const options *o, const frame_ring_pixels *px, int frame, bool sequence, char *first);
/* A frame's progress line, and the sequence's summary (stderr; nothing with --quiet). */
void sequence_frame_line(const options *base, int i, int done, const char *path, bool luts);
void sequence_summary_line(const options *base, int done, int skipped, int lut_computations);
#endif
