/* bad_value.h */
#include "app/cli/bad_value.h"

static _Thread_local FILE *report_stream;   /* NULL: stderr */

FILE *options_report_stream(void) { return report_stream ? report_stream : stderr; }

void options_report_to(FILE *stream) { report_stream = stream; }

static _Thread_local FILE *notes_stream;   /* NULL: stdout */

FILE *options_notes_stream(void) { return notes_stream ? notes_stream : stdout; }

void options_notes_to(FILE *stream) { notes_stream = stream; }

int bad_value(const char *what, const char *text, const char *why)
{
    char shown[64];
    size_t k = 0;
    for (; text[k] && k + 1 < sizeof shown; ++k) shown[k] = (unsigned char)text[k] < 0x20 ? '?' : text[k];
    shown[k] = '\0';
    fprintf(options_report_stream(), "vksky: %s: '%s' %s\n", what, shown, why);
    return 2;
}
