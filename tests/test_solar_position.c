/* NREL's Solar Position Algorithm (src/model/solar_position.c) against
 *  1. the published test case of Reda & Andreas (NREL/TP-560-34302, Table A5.1 and NREL's spa_tester output):
 *     2003-10-17 12:30:30 UTC-7, 39.742476 N 105.1786 W, 1830.14 m, 820 mbar, 11 C, delta T 67 s;
 *  2. an independent low-precision ephemeris (the Astronomical Almanac's sun, good to ~0.01 deg for 1950-2050)
 *     over a spread of dates, times and places: geometric elevation and azimuth agree to 0.03 deg;
 *  3. closed-form sanity: equinox noon on the equator has the sun near the zenith; the sun rises and sets at the
 *     published times of the test case's day (spa_tester: 06:12:43 and 17:20:19) and is up in between;
 *     spa_tester's rise and set come from the SPA's separate interpolated rise/transit/set step (appendix A.2), so
 *     they are checked to a window (1 min at sunrise, 2 min at sunset) rather than to the second;
 *  4. invalid inputs are refused. */
#include "model/solar_position.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "check.h"

static const double PI = 3.14159265358979323846;
static double rad(double d) { return d * PI / 180.0; }
static double deg(double r) { return r * 180.0 / PI; }
static double angle_diff(double a, double b) { double d = fmod(a - b + 540.0, 360.0) - 180.0; return fabs(d); }

static solar_place place(double lat, double lon, double elev)
{
    return (solar_place){.latitude_deg = lat, .longitude_deg = lon, .elevation_m = elev, .pressure_mbar = 1010.0,
                         .temperature_c = 10.0};
}

static void published_case(void)
{
    solar_moment m = {2003, 10, 17, 12, 30, 30.0, -7.0, 67.0};
    solar_place p = {.latitude_deg = 39.742476, .longitude_deg = -105.1786, .elevation_m = 1830.14,
                     .pressure_mbar = 820.0, .temperature_c = 11.0};
    solar_position s;
    CHECK(solar_position_compute(&m, &p, &s), "published case refused");
    printf("published case: zenith %.6f (expected 50.11162, diff %.2e), azimuth %.6f (expected 194.34024, diff %.2e)\n",
           s.zenith_deg, s.zenith_deg - 50.11162, s.azimuth_deg, s.azimuth_deg - 194.34024);
    printf("                JD %.6f (2452930.312847), declination %.6f (-9.31434), hour angle %.6f (11.105900)\n",
           s.julian_day, s.declination_deg, s.hour_angle_deg);
    CHECK(fabs(s.zenith_deg - 50.11162) < 0.01, "zenith %.6f, expected 50.11162 +- 0.01", s.zenith_deg);
    CHECK(fabs(s.azimuth_deg - 194.34024) < 0.01, "azimuth %.6f, expected 194.34024 +- 0.01", s.azimuth_deg);
    /* The algorithm claims 0.0003 deg; the published values have 5 decimals. */
    CHECK(fabs(s.zenith_deg - 50.11162) < 2e-5 && fabs(s.azimuth_deg - 194.34024) < 2e-5,
          "zenith/azimuth off the published values by more than the rounding of their 5 decimals");
    CHECK(fabs(s.julian_day - 2452930.312847) < 1e-6, "Julian day %.6f, expected 2452930.312847", s.julian_day);
    CHECK(fabs(s.declination_deg - -9.31434) < 1e-5, "declination %.6f, expected -9.31434", s.declination_deg);
    CHECK(fabs(s.hour_angle_deg - 11.105900) < 1e-5, "hour angle %.6f, expected 11.105900", s.hour_angle_deg);
}

/* The Astronomical Almanac's low-precision sun (section C, "low precision formulas for the Sun"), then the local
 * horizon by spherical trigonometry: a different, much shorter algorithm. */
static void almanac_sun(const solar_moment *m, double lat, double lon, double *elevation, double *azimuth)
{
    /* Days from J2000.0 (UT) by a day count of our own (not the SPA's Julian day formula). */
    int y = m->year, days = 0;
    static const int cum[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
    for (int k = 2000; k < y; ++k) days += 365 + ((k % 4 == 0 && k % 100 != 0) || k % 400 == 0);
    for (int k = y; k < 2000; ++k) days -= 365 + ((k % 4 == 0 && k % 100 != 0) || k % 400 == 0);
    bool leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
    days += cum[m->month - 1] + (leap && m->month > 2) + m->day - 1;
    double n = days - 0.5 + (m->hour + m->minute / 60.0 + m->second / 3600.0 - m->utc_offset_h) / 24.0;
    double L = 280.460 + 0.9856474 * n, g = rad(357.528 + 0.9856003 * n);
    double lambda = rad(L + 1.915 * sin(g) + 0.020 * sin(2 * g)), eps = rad(23.439 - 0.0000004 * n);
    double alpha = atan2(cos(eps) * sin(lambda), cos(lambda)), delta = asin(sin(eps) * sin(lambda));
    double gmst = 280.460 + 360.9856474 * n;   /* the Almanac's own (lower-precision) sidereal time, degrees */
    double h = rad(gmst + lon) - alpha, phi = rad(lat);
    *elevation = deg(asin(sin(phi) * sin(delta) + cos(phi) * cos(delta) * cos(h)));
    /* Azimuth from north through east: the east component is -cos(delta) sin(h). */
    *azimuth = fmod(deg(atan2(-cos(delta) * sin(h), sin(delta) * cos(phi) - cos(delta) * cos(h) * sin(phi))) + 360.0, 360.0);
}

static void against_almanac(void)
{
    double worst_e = 0.0, worst_a = 0.0;
    int n = 0;
    srand(14);
    for (int i = 0; i < 400; ++i) {
        solar_moment m = {1960 + rand() % 80, 1 + rand() % 12, 1 + rand() % 28, rand() % 24, rand() % 60, rand() % 60,
                          (rand() % 25) - 12, SOLAR_DELTA_T_DEFAULT_S};
        double lat = -89.0 + 178.0 * rand() / (double)RAND_MAX, lon = -180.0 + 360.0 * rand() / (double)RAND_MAX;
        solar_position s;
        solar_place p = place(lat, lon, 0.0);
        if (!solar_position_compute(&m, &p, &s)) { CHECK(0, "valid moment refused"); continue; }
        double e, a;
        almanac_sun(&m, lat, lon, &e, &a);
        /* Parallax (<= 0.0025 deg) is in the SPA's geometric elevation and not in the almanac's: inside the tolerance. */
        worst_e = fmax(worst_e, fabs(s.elevation_geometric_deg - e));
        /* Azimuth is ill-conditioned near the zenith (and undefined at it): compare where cos(elevation) > 0.1. */
        if (cos(rad(e)) > 0.1) worst_a = fmax(worst_a, angle_diff(s.azimuth_deg, a) * cos(rad(e))), ++n;
    }
    printf("vs the Almanac's low-precision sun, 400 moments 1960-2039: worst elevation %.4f deg, worst azimuth x "
           "cos(elevation) %.4f deg (%d compared)\n", worst_e, worst_a, n);
    CHECK(worst_e < 0.03, "elevation differs from the almanac's by %.4f deg", worst_e);
    CHECK(worst_a < 0.03, "azimuth differs from the almanac's by %.4f deg", worst_a);
}

static void sanity(void)
{
    /* March equinox 2024: 03:06 UT on 20 March; the equation of time is about -7.5 min, so apparent noon at
     * longitude 0 is near 12:07 UT: the sun must pass within 0.5 deg of the zenith, near 12:07, from the east. */
    solar_place eq = place(0.0, 0.0, 0.0);
    double best = -90.0;
    int best_minute = 0;
    for (int minute = 0; minute < 60 * 24; ++minute) {
        solar_moment m = {2024, 3, 20, minute / 60, minute % 60, 0.0, 0.0, SOLAR_DELTA_T_DEFAULT_S};
        solar_position s;
        solar_position_compute(&m, &eq, &s);
        if (s.elevation_deg > best) best = s.elevation_deg, best_minute = minute;
        if (minute == 9 * 60) CHECK(fabs(s.azimuth_deg - 90.0) < 1.0, "equinox morning sun not in the east: %.3f", s.azimuth_deg);
        if (minute == 15 * 60) CHECK(fabs(s.azimuth_deg - 270.0) < 1.0, "equinox afternoon sun not in the west: %.3f", s.azimuth_deg);
    }
    printf("equinox 2024 at 0 N 0 E: highest %.4f deg at %02d:%02d UT\n", best, best_minute / 60, best_minute % 60);
    CHECK(best > 89.5, "equinox noon at the equator: the sun's highest elevation is %.4f, expected > 89.5", best);
    CHECK(best_minute >= 12 * 60 + 5 && best_minute <= 12 * 60 + 10, "equinox noon at minute %d", best_minute);

    /* The test case's day: sunrise 06:12:43, sunset 17:20:19 local (spa_tester), i.e. the geometric centre at
     * -(0.26667 + 0.5667) deg: the sign of (elevation + 0.8333) differs a minute either side of sunrise and two
     * either side of sunset. */
    solar_place p = {.latitude_deg = 39.742476, .longitude_deg = -105.1786, .elevation_m = 1830.14,
                     .pressure_mbar = 820.0, .temperature_c = 11.0};
    const int at[4][3] = {{6, 11, 43}, {6, 13, 43}, {17, 18, 19}, {17, 22, 19}};
    double e[4];
    for (int k = 0; k < 4; ++k) {
        solar_moment m = {2003, 10, 17, at[k][0], at[k][1], at[k][2], -7.0, 67.0};
        solar_position s;
        solar_position_compute(&m, &p, &s);
        e[k] = s.elevation_geometric_deg + 0.26667 + SOLAR_REFRACTION_HORIZON_DEG;
    }
    CHECK(e[0] < 0 && e[1] > 0, "no sunrise between 06:11:43 and 06:13:43 (%.3f, %.3f)", e[0], e[1]);
    CHECK(e[2] > 0 && e[3] < 0, "no sunset between 17:18:19 and 17:22:19 (%.3f, %.3f)", e[2], e[3]);
    for (int hour = 0; hour < 24; ++hour) {
        solar_moment m = {2003, 10, 17, hour, 0, 0.0, -7.0, 67.0};
        solar_position s;
        solar_position_compute(&m, &p, &s);
        bool up = hour >= 7 && hour <= 17, down = hour <= 5 || hour >= 18;
        CHECK(!up || s.elevation_deg > 0, "sun below the horizon at %02d:00", hour);
        CHECK(!down || s.elevation_deg < 0, "sun above the horizon at %02d:00", hour);
    }
    /* Southern hemisphere midsummer noon: the sun stands north of a southern observer below the tropic. */
    solar_moment m = {2025, 12, 21, 12, 0, 0.0, 10.0, SOLAR_DELTA_T_DEFAULT_S};
    solar_position s;
    solar_position_compute(&m, &(solar_place){-40.0, 150.0, 0.0, 1010.0, 10.0}, &s);
    CHECK(s.azimuth_deg < 30.0 || s.azimuth_deg > 330.0, "southern noon sun at azimuth %.2f, expected north", s.azimuth_deg);
    CHECK(fabs(s.elevation_geometric_deg - (90.0 - 40.0 + 23.44)) < 1.5, "southern midsummer noon elevation %.2f", s.elevation_geometric_deg);
}

static void invalid(void)
{
    solar_place p = place(10, 10, 0);
    solar_position s;
    const solar_moment bad[] = {{2026, 2, 29, 12, 0, 0, 0, 69}, {2026, 2, 30, 12, 0, 0, 0, 69}, {2026, 4, 31, 12, 0, 0, 0, 69},
                                {2026, 13, 1, 12, 0, 0, 0, 69}, {2026, 1, 1, 24, 0, 0, 0, 69}, {2026, 1, 1, 12, 60, 0, 0, 69},
                                {2026, 1, 1, 12, 0, 60, 0, 69}, {2026, 1, 1, 12, 0, 0, 19, 69}, {1500, 1, 1, 12, 0, 0, 0, 69}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) CHECK(!solar_position_compute(&bad[i], &p, &s), "bad moment %zu accepted", i);
    CHECK(solar_date_valid(2024, 2, 29) && solar_date_valid(2000, 2, 29) && !solar_date_valid(1900, 2, 29), "leap years");
    solar_moment ok = {2026, 6, 1, 12, 0, 0, 0, 69};
    CHECK(!solar_position_compute(&ok, &(solar_place){91, 0, 0, 1010, 10}, &s), "latitude 91 accepted");
    CHECK(!solar_position_compute(&ok, &(solar_place){0, 180.5, 0, 1010, 10}, &s), "longitude 180.5 accepted");
    CHECK(!solar_position_compute(&ok, &(solar_place){NAN, 0, 0, 1010, 10}, &s), "NaN latitude accepted");
}

int main(void)
{
    published_case();
    against_almanac();
    sanity();
    invalid();
    if (check_failures) printf("%d failure(s)\n", check_failures);
    else printf("solar_position: all checks pass\n");
    return check_failures ? 1 : 0;
}
