/* bad_value.h */
#include "app/cli/bad_value.h"
#include <stdio.h>

int bad_value(const char *what, const char *text, const char *why)
{
    char shown[64];
    size_t k = 0;
    for (; text[k] && k + 1 < sizeof shown; ++k) shown[k] = (unsigned char)text[k] < 0x20 ? '?' : text[k];
    shown[k] = '\0';
    fprintf(stderr, "vksky: %s: '%s' %s\n", what, shown, why);
    return 2;
}
