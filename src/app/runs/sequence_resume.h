/* Resuming a sequence (issue 30): --skip-existing renders only the frames whose files are not already written by this
 * job. Files are written by an atomic rename (io/atomic_file.h), so a file that exists is whole: a job killed or
 * pre-empted mid-sequence leaves whole frames and temp files, never half a frame under a frame's name. An EXR says
 * which frame of which scene it is (vksky:frame, vksky:scene: app/runs/exr_header.h); one that is another frame or another
 * scene (a stale file, an older version, another job's files under the same pattern) is rendered again, with a note.
 * A PNG carries no scene: its existence is the check (render an EXR beside it for the header's). */
#ifndef VKSKY_APP_SEQUENCE_RESUME_H
#define VKSKY_APP_SEQUENCE_RESUME_H
#include "app/cli/options_struct.h"

/* Frame `frame` (f: its options, sequence_frame_options) has every --render file, and each EXR among them is that
 * frame of that scene: true, and the progress line of a skipped frame goes to stderr ("frame F (F+1 of count;
 * job_done/job_size of this job): FILE, skipped (written before)"). Else false: render it (a note on stderr when a
 * file exists but is not this job's). */
/* Every --render file of frame `frame` exists (a candidate for sequence_resume_skip; no output, no note). */
bool sequence_resume_exists(const options *f, int frame);
bool sequence_resume_skip(const options *f, int frame, int count, int job_done, int job_size);
#endif
