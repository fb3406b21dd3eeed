/* --sun-visibility / "sun_visibility" (see options_sunvis.h). */
#include "app/cli/options_sunvis.h"
#include "model/sun_visibility.h"

_Static_assert(MODEL_SUN_VISIBILITY_PENUMBRA == 0 && MODEL_SUN_VISIBILITY_LESSON_FADE == 1,
               "sunvis_words is indexed by the model's values");

const char *const sunvis_words[SUNVIS_WORD_COUNT] = {"penumbra", "lesson-fade"};

const char *sunvis_name(int kind)
{
    return kind == MODEL_SUN_VISIBILITY_LESSON_FADE ? sunvis_words[1] : sunvis_words[0];
}
