/* The flags of a sequence (issue 14 item 4): --animate PARAM=FROM:TO, --frame-count N, --frame-range A:B,
 * --skip-existing (issue 30), and the printf-style --render patterns they need. Hooks called by options.c; the
 * frames themselves: app/sequence. */
#ifndef VKSKY_APP_OPTIONS_SEQUENCE_H
#define VKSKY_APP_OPTIONS_SEQUENCE_H
#include "app/cli/options_struct.h"
#include <stddef.h>

/* Apply one of these flags (x: its parsed number, for numeric ones): 0 ok, 2 bad value (message printed), -1 not one
 * of them (the caller applies it). */
int options_sequence_apply(options *o, const char *flag_name, const char *value, double x);
/* After all flags: the frame range inside the sequence, a frame-number pattern in every --render when N > 1, only
 * with --render. 0 ok, 2 bad (one line printed). */
int options_sequence_resolve(options *o);
/* Does the command line name a sequence flag (--animate, --frame-count, --frame-range, whatever its value)? Asked
 * before any flag is applied: --quality auto chooses a sequence's configuration from the scene alone, the same on
 * every device (docs/sequences.md), so that the frames of a split sequence do not depend on where each job ran. */
bool options_sequence_named(int argc, char **argv);

/* A --render value's frame number: 0 no conversion, 1 exactly one %d (flags '0', a width up to 9: %04d, %6d), -1 any
 * other use of '%' ("%%" is a literal '%'). */
int sequence_pattern_kind(const char *pattern);
/* The pattern with the frame number in it ("%%" -> "%"); false when it does not fit out_size. A value without a
 * %d (kind 0, or -1 outside a sequence) is a plain file name: the caller uses it as it is. */
bool sequence_output_path(const char *pattern, int frame, char *out, size_t out_size);
/* Decimal hours as the local clock time --time reads, to the millisecond: "HH:MM:SS.mmm" (an animated time's frames). */
void sequence_time_text(double hours, char out[16]);
#endif
