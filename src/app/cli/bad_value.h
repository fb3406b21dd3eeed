/* The one line a bad flag or field value gets: "vksky: WHAT: 'TEXT' WHY" on stderr (the text cut at 60 characters,
 * control characters shown as '?'). Returns 2, the exit status for bad input. */
#ifndef VKSKY_APP_BAD_VALUE_H
#define VKSKY_APP_BAD_VALUE_H
#include <stdio.h>
int bad_value(const char *what, const char *text, const char *why);

/* Where the options' loader and a frame's values (options_parse, options_frame: the flags' values applied, everything derived again) write their lines, bad
 * values and notes: stderr, unless this thread set a stream of its own. The library captures a frame's line for its
 * host's callback (lib/api_scene.c) this way, on the setting thread alone: pointing the process's stderr at the
 * capture took other threads' lines too (a sequence's progress lines, printed by the readback ring's consumers while
 * the producer sets the next frame's values: the encode_frames flake). */
FILE *options_report_stream(void);
/* This thread's stream (NULL: stderr again). */
void options_report_to(FILE *stream);
/* Where the loader's notes go (--max-error's pick and its notes, on stdout for the command line): stdout, unless this
 * thread set a stream of its own. The library drops them (its host prints what it wants), on the loading thread
 * alone. */
FILE *options_notes_stream(void);
/* This thread's stream (NULL: stdout again). */
void options_notes_to(FILE *stream);
#endif
