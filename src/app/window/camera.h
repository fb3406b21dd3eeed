/* Fly camera in planet-centric kilometres (double precision), and the sun relative to the camera's local frame.
 *
 * The renderer never sees an absolute position (float32 has ~0.5 m resolution at 6360 km): each frame the
 * camera is reduced to what the renderer's convention needs, an altitude plus directions in the LOCAL frame at
 * the camera, where +Y is local up (p/|p|) and azimuth 0 / 90 are two tangent axes carried along as the camera
 * moves (parallel transport: no pole, no sudden twist). */
#ifndef VKSKY_APP_CAMERA_H
#define VKSKY_APP_CAMERA_H
#include "app/cli/options_struct.h"   /* sky_view, the view values a frame is made of */

#define CAMERA_MIN_ALTITUDE_KM 0.0005     /* never inside the planet: half a metre above the ground */
#define CAMERA_SPEED_KM_S 0.2
#define CAMERA_BOOST 10.0

typedef struct camera_quat { double w, x, y, z; } camera_quat;

typedef struct camera {
    double pos[3];          /* planet-centric km */
    double ground_radius_km;   /* Rb: the scene's planet (model_atmosphere.bottom_radius), not always the Earth's */
    double altitude_km;     /* |pos| - Rb, tracked with a cancellation-free update (see camera_move) */
    camera_quat frame;      /* local -> world: local X = azimuth 0, local Y = up, local Z = azimuth 90 */
    camera_quat orient;     /* body -> world: body X = forward, body Y = up, body Z = right (renderer basis) */
    double sun_azimuth_deg, sun_elevation_deg;   /* in the local frame */
} camera;

/* Input for one frame: movement in body/local axes (-1, 0, 1 each); look and sun deltas in degrees. */
typedef struct camera_input {
    double forward, right, up;   /* W/S, D/A, Space/C; `up` is along local up, not the view's up */
    bool boost;
    double yaw_deg, pitch_deg;   /* mouse look: yaw right, pitch up */
    double sun_azimuth_deg, sun_elevation_deg;   /* sun moves (elevation is clamped to [-90, 90]) */
} camera_input;

/* Start at (0, Rb + h, 0) over a planet of radius Rb = ground_radius_km, looking along (yaw, pitch) of `v`, with its
 * sun. */
void camera_init(camera *c, const sky_view *v, double ground_radius_km);
void camera_update(camera *c, const camera_input *in, double dt_s);
/* Altitude, view yaw/pitch and sun in the local frame; other fields of `v` are kept. */
void camera_to_view(const camera *c, sky_view *v);
#endif
