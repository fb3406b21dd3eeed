/* The fly camera: directions round-trip through the local frame, the altitude stays consistent with the
 * double-precision position (checked against long double), the ground clamp holds, level flight over the
 * curved planet stays level (on the Earth and on Mars: the camera takes the scene's radius), and space is reachable.
 * No GPU. */
#include "app/window/camera.h"
#include <math.h>
#include "check.h"
#include <stdio.h>

static sky_view start_view(double alt, double yaw, double pitch)
{
    sky_view v = sky_view_default();
    v.altitude_km = alt, v.yaw_deg = yaw, v.pitch_deg = pitch;
    return v;
}

#define EARTH_RADIUS_KM 6360.0   /* the Earth scenes' ground */
#define MARS_RADIUS_KM 3389.5    /* scenes/mars.json: the NASA fact sheet's mean radius */

/* |pos| - Rb in long double: the independent altitude. */
static double altitude_ld(const camera *c, double rb)
{
    long double x = c->pos[0], y = c->pos[1], z = c->pos[2];
    return (double)(sqrtl(x * x + y * y + z * z) - (long double)rb);
}

static void fly(camera *c, camera_input in, double seconds, double dt)
{
    long n = lround(seconds / dt);
    for (long i = 0; i < n; ++i) camera_update(c, &in, dt);
}

static void test_round_trip(void)
{
    const double yaws[] = {0, 30, 90, -135, 179}, pitches[] = {-60, 0, 10, 45, 89};
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) {
            sky_view v = start_view(0.001, yaws[i], pitches[j]), out = v;
            camera c;
            camera_init(&c, &v, EARTH_RADIUS_KM);
            camera_to_view(&c, &out);
            CHECK(fabs(out.yaw_deg - yaws[i]) < 1e-9 && fabs(out.pitch_deg - pitches[j]) < 1e-9,
                  "yaw/pitch %g/%g came back as %.12f/%.12f", yaws[i], pitches[j], out.yaw_deg, out.pitch_deg);
            CHECK(out.altitude_km == 0.001, "altitude %.12f", out.altitude_km);
        }
}

/* The renderer's dir(az, el): yaw 90 looks along +Z; W for one second moves 0.2 km that way. */
static void test_forward_matches_renderer(void)
{
    sky_view v = start_view(0.001, 90, 0);
    camera c;
    camera_init(&c, &v, EARTH_RADIUS_KM);
    fly(&c, (camera_input){.forward = 1}, 1.0, 0.01);
    CHECK(fabs(c.pos[2] - 0.2) < 1e-6 && fabs(c.pos[0]) < 1e-9, "moved to %.9f %.9f %.9f", c.pos[0], c.pos[1], c.pos[2]);
}

static void test_ground_clamp(void)
{
    sky_view v = start_view(0.001, 0, -30);
    camera c;
    camera_init(&c, &v, EARTH_RADIUS_KM);
    fly(&c, (camera_input){.up = -1, .forward = 1, .boost = true}, 5.0, 1.0 / 60.0);
    CHECK(c.altitude_km == CAMERA_MIN_ALTITUDE_KM, "altitude %.12f after diving", c.altitude_km);
    CHECK(fabs(altitude_ld(&c, EARTH_RADIUS_KM) - CAMERA_MIN_ALTITUDE_KM) < 1e-9, "|pos| - Rb = %.12f", altitude_ld(&c, EARTH_RADIUS_KM));
}

/* Level flight for 2000 km: the transported frame keeps the view level (pitch 0 in the local frame) and the
 * heading fixed; the altitude only rises by the chord's sagitta per step. */
static void test_level_flight(double rb, const char *planet)
{
    sky_view v = start_view(1.0, 40, 0), out = v;
    camera c;
    camera_init(&c, &v, rb);
    fly(&c, (camera_input){.forward = 1, .boost = true}, 1000.0, 1.0 / 60.0);
    camera_to_view(&c, &out);
    double travelled = atan2(sqrt(c.pos[0] * c.pos[0] + c.pos[2] * c.pos[2]), c.pos[1]) * rb;
    CHECK(fabs(travelled - 2000.0) < 1.0, "%s: travelled %.3f km over the ground", planet, travelled);
    CHECK(fabs(out.pitch_deg) < 1e-6 && fabs(out.yaw_deg - 40.0) < 1e-6, "%s: after level flight yaw %.9f pitch %.9f",
          planet, out.yaw_deg, out.pitch_deg);
    CHECK(out.altitude_km > 1.0 && out.altitude_km < 1.01, "%s: altitude %.9f", planet, out.altitude_km);
    CHECK(fabs(out.altitude_km - altitude_ld(&c, rb)) < 1e-9, "%s: tracked %.12f vs |pos| - Rb %.12f", planet, out.altitude_km,
          altitude_ld(&c, rb));
}

static void test_space_and_limits(void)
{
    sky_view v = start_view(0.001, 0, 10), out = v;
    camera c;
    camera_init(&c, &v, EARTH_RADIUS_KM);
    fly(&c, (camera_input){.up = 1, .boost = true}, 300.0, 0.1);
    camera_to_view(&c, &out);
    CHECK(fabs(out.altitude_km - 600.001) < 1e-6, "altitude %.9f after 300 s up at 2 km/s", out.altitude_km);
    camera_update(&c, &(camera_input){.pitch_deg = 500, .sun_elevation_deg = 500, .sun_azimuth_deg = 200}, 0.0);
    camera_to_view(&c, &out);
    CHECK(out.pitch_deg <= 89.9 + 1e-9 && out.pitch_deg > 89.0, "pitch %.9f after looking far up", out.pitch_deg);
    CHECK(out.sun_elevation_deg == 90.0, "sun elevation %.9f not clamped to 90", out.sun_elevation_deg);
    CHECK(fabs(out.sun_azimuth_deg - (-160.0)) < 1e-9, "sun azimuth %.9f, expected -160", out.sun_azimuth_deg);
}

int main(void)
{
    test_round_trip();
    test_forward_matches_renderer();
    test_ground_clamp();
    test_level_flight(EARTH_RADIUS_KM, "Earth");
    test_level_flight(MARS_RADIUS_KM, "Mars");   /* the scene's planet, not the Earth's radius */
    test_space_and_limits();
    return check_report("test_camera");
}
