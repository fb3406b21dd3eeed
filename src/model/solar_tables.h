/* The periodic-term tables of NREL's Solar Position Algorithm (internal to the model module; solar_position.c
 * is their one reader). Reda & Andreas, "Solar Position Algorithm for Solar Radiation Applications", NREL/TP-560-34302
 * (2003, revised 2008), Table A4.2 (Earth heliocentric longitude L, latitude B, radius R: VSOP87 terms A, B, C with
 * each term A cos(B + C JME)) and Table A4.3 (nutation in longitude and obliquity, Meeus ch. 22). */
#ifndef VKSKY_MODEL_SOLAR_TABLES_H
#define VKSKY_MODEL_SOLAR_TABLES_H

typedef struct spa_term {
    double a, b, c;   /* amplitude (1e-8 rad or AU), phase (rad), frequency (rad per Julian millennium) */
} spa_term;

typedef struct spa_series {
    const spa_term *terms;
    int count;
} spa_series;

typedef struct spa_nutation_term {
    signed char y[5];     /* multipliers of X0..X4 (elongation, sun and moon anomalies, moon latitude, node) */
    double a, b, c, d;    /* delta psi = (a + b JCE) sin(arg), delta epsilon = (c + d JCE) cos(arg), 0.0001 arcsec */
} spa_nutation_term;

#define SPA_NUTATION_TERMS 63
extern const spa_series spa_longitude[6], spa_latitude[2], spa_radius[5];   /* L0..L5, B0..B1, R0..R4 */
extern const spa_nutation_term spa_nutation[SPA_NUTATION_TERMS];
#endif
