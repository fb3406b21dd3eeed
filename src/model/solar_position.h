/* The sun's position in the sky for a date, a time and a place: NREL's Solar Position Algorithm (Reda & Andreas,
 * "Solar Position Algorithm for Solar Radiation Applications", Solar Energy 76(5), 2004; NREL/TP-560-34302 rev. 2008),
 * uncertainty +-0.0003 deg for the years -2000 to 6000. Our own implementation of the paper's steps 3.1-3.15. */
#ifndef VKSKY_MODEL_SOLAR_POSITION_H
#define VKSKY_MODEL_SOLAR_POSITION_H
#include <stdbool.h>

typedef struct solar_moment {
    int year, month, day;        /* Gregorian calendar (valid: solar_date_valid) */
    int hour, minute;            /* local clock time */
    double second;
    double utc_offset_h;         /* local time minus UT, hours (UTC-7 = -7) */
    double delta_t_s;            /* TT - UT in seconds (SOLAR_DELTA_T_DEFAULT_S when unknown: the sun barely moves) */
} solar_moment;

typedef struct solar_place {
    double latitude_deg;         /* geodetic, north positive, [-90, 90] */
    double longitude_deg;        /* east positive, [-180, 180] */
    double elevation_m;          /* above sea level (topocentric parallax) */
    double pressure_mbar;        /* refraction: annual mean local pressure (1010 standard) */
    double temperature_c;        /* refraction: annual mean local temperature (10 standard) */
} solar_place;

typedef struct solar_position {
    double zenith_deg;           /* topocentric zenith angle with atmospheric refraction (the apparent sun) */
    double azimuth_deg;          /* compass azimuth: clockwise from north, [0, 360) */
    double elevation_deg;        /* 90 - zenith_deg */
    double elevation_geometric_deg;   /* topocentric elevation without refraction */
    double declination_deg;      /* geocentric declination */
    double hour_angle_deg;       /* local (observer) hour angle, [0, 360) */
    double julian_day;           /* UT Julian day */
} solar_position;

/* ~ TT - UT around 2020-2030 (IERS: 69.2 s in 2023). An error of a minute moves the sun by < 0.001 deg. */
#define SOLAR_DELTA_T_DEFAULT_S 69.0
/* Refraction is applied only while the sun's centre is above -(sun radius + refraction at the horizon). */
#define SOLAR_REFRACTION_HORIZON_DEG 0.5667

/* 0 < month <= 12, a day the month has (leap years: Gregorian rule), years 1583 (after the Gregorian reform) to
 * 6000 (the SPA's range). */
bool solar_date_valid(int year, int month, int day);
/* The sun for a moment and a place; false (out untouched) when an input is outside the ranges above. */
bool solar_position_compute(const solar_moment *when, const solar_place *where, solar_position *out);
#endif
