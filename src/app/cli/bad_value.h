/* The one line a bad flag or field value gets: "vksky: WHAT: 'TEXT' WHY" on stderr (the text cut at 60 characters,
 * control characters shown as '?'). Returns 2, the exit status for bad input. */
#ifndef VKSKY_APP_BAD_VALUE_H
#define VKSKY_APP_BAD_VALUE_H
int bad_value(const char *what, const char *text, const char *why);
#endif
