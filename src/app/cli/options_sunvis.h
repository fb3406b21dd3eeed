/* --sun-visibility and the scene field "sun_visibility" (issue 17): the names of the sun visibility models, in the
 * order of their MODEL_SUN_VISIBILITY_* values, for the flag parser and the scene loader/dumper. */
#ifndef VKSKY_APP_OPTIONS_SUNVIS_H
#define VKSKY_APP_OPTIONS_SUNVIS_H

#define SUNVIS_WORD_COUNT 2
/* {"penumbra", "lesson-fade"}: index = MODEL_SUN_VISIBILITY_PENUMBRA, MODEL_SUN_VISIBILITY_LESSON_FADE. */
extern const char *const sunvis_words[SUNVIS_WORD_COUNT];

/* The name of a model (its index into sunvis_words; "penumbra" for anything else). */
const char *sunvis_name(int kind);

#endif
