/* NREL's Solar Position Algorithm, step by step as in Reda & Andreas (2008), section 3: Julian dates (3.1), the
 * Earth's heliocentric position (3.2), geocentric sun (3.3), nutation (3.4), obliquity (3.5), aberration and
 * apparent longitude (3.6-3.7), sidereal time (3.8), right ascension and declination (3.9-3.10), hour angle (3.11),
 * topocentric parallax (3.12-3.13), elevation with refraction (3.14) and azimuth (3.15). */
#include "model/solar_position.h"
#include "model/solar_tables.h"
#include <math.h>

static const double PI = 3.14159265358979323846;
static double rad(double deg) { return deg * PI / 180.0; }
static double deg(double r) { return r * 180.0 / PI; }
static double wrap360(double d) { double w = fmod(d, 360.0); return w < 0.0 ? w + 360.0 : w; }

bool solar_date_valid(int year, int month, int day)
{
    static const int days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    if (year < 1583 || year > 6000 || month < 1 || month > 12 || day < 1) return false;
    bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    return day <= days[month - 1] + (month == 2 && leap);
}

/* 3.1.1: the Julian day of a UT calendar moment (Meeus ch. 7; Gregorian dates only, see solar_date_valid). */
static double julian_day(int year, int month, double day_fraction)
{
    if (month < 3) year -= 1, month += 12;
    double a = floor(year / 100.0);
    return floor(365.25 * (year + 4716)) + floor(30.6001 * (month + 1)) + day_fraction + 2.0 - a + floor(a / 4.0) - 1524.5;
}

/* 3.2: sum_i (sum_k A cos(B + C JME)) JME^i / 1e8 over the series L0..Ln (or B, R). */
static double series_sum(const spa_series *s, int n, double jme)
{
    double total = 0.0, power = 1.0;
    for (int i = 0; i < n; ++i, power *= jme) {
        double part = 0.0;
        for (int k = 0; k < s[i].count; ++k) part += s[i].terms[k].a * cos(s[i].terms[k].b + s[i].terms[k].c * jme);
        total += part * power;
    }
    return total / 1e8;
}

static double cubic(double a, double b, double c, double d, double x) { return ((d * x + c) * x + b) * x + a; }

/* 3.4: nutation in longitude and obliquity (degrees). */
static void nutation(double jce, double *dpsi, double *deps)
{
    const double x[5] = {
        cubic(297.85036, 445267.111480, -0.0019142, 1.0 / 189474.0, jce),    /* moon's mean elongation from the sun */
        cubic(357.52772, 35999.050340, -0.0001603, -1.0 / 300000.0, jce),    /* sun's mean anomaly */
        cubic(134.96298, 477198.867398, 0.0086972, 1.0 / 56250.0, jce),      /* moon's mean anomaly */
        cubic(93.27191, 483202.017538, -0.0036825, 1.0 / 327270.0, jce),     /* moon's argument of latitude */
        cubic(125.04452, -1934.136261, 0.0020708, 1.0 / 450000.0, jce)};     /* moon's ascending node */
    double psi = 0.0, eps = 0.0;
    for (int i = 0; i < SPA_NUTATION_TERMS; ++i) {
        const spa_nutation_term *t = &spa_nutation[i];
        double arg = 0.0;
        for (int j = 0; j < 5; ++j) arg += x[j] * t->y[j];
        psi += (t->a + t->b * jce) * sin(rad(arg));
        eps += (t->c + t->d * jce) * cos(rad(arg));
    }
    *dpsi = psi / 36000000.0;
    *deps = eps / 36000000.0;
}

/* 3.5.1: mean obliquity of the ecliptic (arcseconds), U = JME / 10 (Laskar's polynomial). */
static double mean_obliquity_arcsec(double jme)
{
    static const double c[11] = {84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67, -39.05, 7.12, 27.87, 5.79, 2.45};
    double u = jme / 10.0, e = 0.0;
    for (int i = 10; i >= 0; --i) e = e * u + c[i];
    return e;
}

static bool in_range(double v, double lo, double hi) { return v >= lo && v <= hi; }   /* false for NaN */

bool solar_position_compute(const solar_moment *when, const solar_place *where, solar_position *out)
{
    if (!solar_date_valid(when->year, when->month, when->day) || when->hour < 0 || when->hour > 23 ||
        when->minute < 0 || when->minute > 59 || !in_range(when->second, 0.0, 60.0) || when->second >= 60.0 ||
        !in_range(when->utc_offset_h, -18.0, 18.0) || !in_range(when->delta_t_s, -8000.0, 8000.0) ||
        !in_range(where->latitude_deg, -90.0, 90.0) || !in_range(where->longitude_deg, -180.0, 180.0) ||
        !in_range(where->elevation_m, -6500000.0, 1e7) || !in_range(where->pressure_mbar, 0.0, 5000.0) ||
        !in_range(where->temperature_c, -272.99, 6000.0))
        return false;
    /* 3.1: Julian day (UT), ephemeris day (TT), centuries and millennia from J2000.0. */
    double ut_hours = when->hour + when->minute / 60.0 + when->second / 3600.0 - when->utc_offset_h;
    double jd = julian_day(when->year, when->month, when->day + ut_hours / 24.0);
    double jde = jd + when->delta_t_s / 86400.0;
    double jc = (jd - 2451545.0) / 36525.0, jce = (jde - 2451545.0) / 36525.0, jme = jce / 10.0;
    /* 3.2: the Earth's heliocentric longitude, latitude (degrees) and distance (AU). */
    double l = wrap360(deg(series_sum(spa_longitude, 6, jme)));
    double b = deg(series_sum(spa_latitude, 2, jme));
    double r = series_sum(spa_radius, 5, jme);
    /* 3.3: the geocentric sun is the opposite direction. */
    double theta = wrap360(l + 180.0), beta = -b;
    /* 3.4-3.5: nutation and the true obliquity. */
    double dpsi, deps;
    nutation(jce, &dpsi, &deps);
    double eps = mean_obliquity_arcsec(jme) / 3600.0 + deps;
    /* 3.6-3.7: aberration, apparent longitude. */
    double lambda = theta + dpsi - 20.4898 / (3600.0 * r);
    /* 3.8: apparent sidereal time at Greenwich (degrees). */
    double nu0 = wrap360(280.46061837 + 360.98564736629 * (jd - 2451545.0) + jc * jc * (0.000387933 - jc / 38710000.0));
    double nu = nu0 + dpsi * cos(rad(eps));
    /* 3.9-3.10: geocentric right ascension and declination. */
    double sl = sin(rad(lambda)), ce = cos(rad(eps)), se = sin(rad(eps));
    double alpha = wrap360(deg(atan2(sl * ce - tan(rad(beta)) * se, cos(rad(lambda)))));
    double delta = deg(asin(sin(rad(beta)) * ce + cos(rad(beta)) * se * sl));
    /* 3.11: local hour angle (longitude east positive). */
    double h = wrap360(nu + where->longitude_deg - alpha);
    /* 3.12-3.13: parallax for an observer on the WGS-ish ellipsoid (flattening 0.99664719, radius 6378140 m). */
    double xi = rad(8.794 / (3600.0 * r)), phi = rad(where->latitude_deg);
    double u = atan(0.99664719 * tan(phi));
    double x = cos(u) + where->elevation_m / 6378140.0 * cos(phi);
    double y = 0.99664719 * sin(u) + where->elevation_m / 6378140.0 * sin(phi);
    double hr = rad(h), dr = rad(delta);
    double denom = cos(dr) - x * sin(xi) * cos(hr);
    double dalpha = atan2(-x * sin(xi) * sin(hr), denom);
    double delta_t = atan2((sin(dr) - y * sin(xi)) * cos(dalpha), denom);   /* topocentric declination (rad) */
    double ht = hr - dalpha;                                                /* topocentric hour angle (rad) */
    /* 3.14: elevation, then Bennett's refraction (Saemundsson form) for the local pressure and temperature. */
    double e0 = deg(asin(sin(phi) * sin(delta_t) + cos(phi) * cos(delta_t) * cos(ht)));
    double refraction = 0.0;
    if (e0 >= -(0.26667 + SOLAR_REFRACTION_HORIZON_DEG))
        refraction = where->pressure_mbar / 1010.0 * 283.0 / (273.0 + where->temperature_c) * 1.02 /
                     (60.0 * tan(rad(e0 + 10.3 / (e0 + 5.11))));
    double e = e0 + refraction;
    /* 3.15: astronomers' azimuth (westward from south), then the compass's (eastward from north). */
    double gamma = deg(atan2(sin(ht), cos(ht) * sin(phi) - tan(delta_t) * cos(phi)));
    *out = (solar_position){.zenith_deg = 90.0 - e, .azimuth_deg = wrap360(gamma + 180.0), .elevation_deg = e,
                            .elevation_geometric_deg = e0, .declination_deg = delta, .hour_angle_deg = h,
                            .julian_day = jd};
    return true;
}
