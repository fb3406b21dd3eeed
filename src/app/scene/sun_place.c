/* --date/--time/--latitude/...: parsing and the SPA call (see sun_place.h for the azimuth mapping). */
#include "app/scene/sun_place.h"
#include "app/cli/bad_value.h"
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sun_place_init(sun_place *p) { *p = (sun_place){0}; }

bool sun_place_any(const sun_place *p) { return p->has_date || p->has_time || p->has_latitude || p->has_longitude; }

/* Exactly `n` digits at s; their value. */
static bool digits(const char *s, int n, int *out)
{
    int v = 0;
    for (int i = 0; i < n; ++i) {
        if (!isdigit((unsigned char)s[i])) return false;
        v = 10 * v + (s[i] - '0');
    }
    *out = v;
    return true;
}

int sun_place_parse_date(sun_place *p, const char *what, const char *text)
{
    static const char *const months[12] = {"January", "February", "March", "April", "May", "June", "July",
                                           "August", "September", "October", "November", "December"};
    int y, m, d;
    if (strlen(text) != 10 || !digits(text, 4, &y) || text[4] != '-' || !digits(text + 5, 2, &m) || text[7] != '-' ||
        !digits(text + 8, 2, &d))
        return bad_value(what, text, "is not a date; expected YYYY-MM-DD (e.g. 2026-06-21)");
    if (y < 1583 || y > 6000) return bad_value(what, text, "is outside the years 1583 to 6000 (Gregorian calendar, SPA's range)");
    if (m < 1 || m > 12) return bad_value(what, text, "has no such month; expected a month 01 to 12");
    if (!solar_date_valid(y, m, d)) {
        char why[120];
        int last = 28;
        while (last < 31 && solar_date_valid(y, m, last + 1)) ++last;
        snprintf(why, sizeof why, "is not a calendar date: %s %d has days 01 to %02d", months[m - 1], y, last);
        return bad_value(what, text, why);
    }
    p->when.year = y, p->when.month = m, p->when.day = d;
    p->has_date = true;
    return 0;
}

int sun_place_parse_time(sun_place *p, const char *what, const char *text)
{
    int h, m, s = 0;
    size_t n = strlen(text), fraction = 0;   /* "HH:MM:SS.ffffff": up to 6 decimals (--animate time's frames) */
    while (n > 9 && fraction < n - 9 && isdigit((unsigned char)text[9 + fraction])) ++fraction;
    bool fractional = n > 9 && text[8] == '.' && fraction >= 1 && fraction <= 6 && 9 + fraction == n;
    if ((n != 5 && n != 8 && !fractional) || !digits(text, 2, &h) || text[2] != ':' || !digits(text + 3, 2, &m) ||
        (n >= 8 && (text[5] != ':' || !digits(text + 6, 2, &s))))
        return bad_value(what, text, "is not a time; expected HH:MM or HH:MM:SS[.ffffff], 24-hour local clock (e.g. 06:30)");
    if (h > 23 || m > 59 || s > 59) return bad_value(what, text, "is not a time of day; expected 00:00:00 to 23:59:59");
    p->when.hour = h, p->when.minute = m, p->when.second = n >= 8 ? strtod(text + 6, NULL) : 0.0;
    p->has_time = true;
    return 0;
}

void sun_place_format_date(const sun_place *p, char out[16])
{
    snprintf(out, 16, "%04d-%02d-%02d", p->when.year % 10000, p->when.month % 100, p->when.day % 100);
}

void sun_place_format_time(const sun_place *p, char out[16])
{
    double s = p->when.second >= 0.0 && p->when.second < 60.0 ? p->when.second : 0.0;
    if (s == floor(s)) {
        snprintf(out, 16, "%02d:%02d:%02d", p->when.hour % 100, p->when.minute % 100, (int)s);
        return;
    }
    /* Six decimals read back as the same double: the parser reads at most six, and a double holds 15 digits. */
    unsigned long us = (unsigned long)lround(s * 1e6);
    if (us > 59999999ul) us = 59999999ul;
    snprintf(out, 16, "%02u:%02u:%02lu.%06lu", (unsigned)p->when.hour % 100u, (unsigned)p->when.minute % 100u,
             us / 1000000ul % 100ul, us % 1000000ul);
    size_t n = strlen(out);
    while (out[n - 1] == '0') out[--n] = '\0';
}

int sun_place_resolve(const sun_place *p, double *elevation_deg, double *azimuth_deg)
{
    if (!p->has_date || !p->has_time || !p->has_latitude || !p->has_longitude) {
        char missing[80] = "";
        const char *names[4] = {"--date", "--time", "--latitude", "--longitude"};
        const bool have[4] = {p->has_date, p->has_time, p->has_latitude, p->has_longitude};
        for (int i = 0; i < 4; ++i)
            if (!have[i]) strcat(strcat(missing, missing[0] ? ", " : ""), names[i]);
        fprintf(options_report_stream(),
                "vksky: %s: missing %s; the sun from a date and place needs --date, --time, --latitude and "
                "--longitude (or the scene's sun.date, time, latitude_deg, longitude_deg)\n",
                p->has_date ? "--date" : p->has_time ? "--time" : p->has_latitude ? "--latitude" : "--longitude", missing);
        return 2;
    }
    /* Standard refraction (1010 mbar, 10 C: the SPA's reference atmosphere) and today's delta T. */
    solar_moment when = p->when;
    solar_place where = p->where;
    when.delta_t_s = SOLAR_DELTA_T_DEFAULT_S;
    where.pressure_mbar = 1010.0, where.temperature_c = 10.0;
    solar_position s;
    if (!solar_position_compute(&when, &where, &s)) {
        fprintf(options_report_stream(),
                "vksky: --date: the date, time or place is outside the solar position algorithm's range\n");
        return 2;
    }
    *elevation_deg = s.elevation_deg;
    *azimuth_deg = s.azimuth_deg;   /* compass azimuth = vksky azimuth (sun_place.h) */
    return 0;
}
