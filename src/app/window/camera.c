#include "app/window/camera.h"
#include <math.h>

static const double DEG = 3.14159265358979323846 / 180.0;
#define MAX_PITCH_DEG 89.9   /* the renderer's basis needs a horizontal right vector: stay off the poles */

/* --- A few quaternion helpers (unit quaternions, rotations only) ------------------------------------------- */

static camera_quat quat_mul(camera_quat a, camera_quat b)
{
    return (camera_quat){a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
                         a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

static camera_quat quat_conj(camera_quat q) { return (camera_quat){q.w, -q.x, -q.y, -q.z}; }

/* Rounding drifts a quaternion off unit length over thousands of frames; renormalise after each update. */
static camera_quat quat_normalize(camera_quat q)
{
    double n = sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    return (camera_quat){q.w / n, q.x / n, q.y / n, q.z / n};
}

static camera_quat quat_axis_angle(const double axis[3], double angle_rad)
{
    double s = sin(0.5 * angle_rad);
    return (camera_quat){cos(0.5 * angle_rad), axis[0] * s, axis[1] * s, axis[2] * s};
}

static void quat_rotate(camera_quat q, const double v[3], double out[3])
{
    camera_quat p = quat_mul(quat_mul(q, (camera_quat){0, v[0], v[1], v[2]}), quat_conj(q));
    out[0] = p.x, out[1] = p.y, out[2] = p.z;
}

/* The smallest rotation taking unit vector a to unit vector b: half-angle form (1 + a.b, a x b), normalised.
 * Well conditioned for the nearly equal vectors of one frame's move (never used near a = -b). */
static camera_quat quat_from_to(const double a[3], const double b[3])
{
    camera_quat q = {1.0 + a[0] * b[0] + a[1] * b[1] + a[2] * b[2], a[1] * b[2] - a[2] * b[1],
                     a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    return quat_normalize(q);
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static const double AXIS_X[3] = {1, 0, 0}, AXIS_Y[3] = {0, 1, 0}, AXIS_Z[3] = {0, 0, 1};

/* --- Camera ------------------------------------------------------------------------------------------------ */

static void local_up(const camera *c, double up[3])
{
    double n = sqrt(dot3(c->pos, c->pos));
    up[0] = c->pos[0] / n, up[1] = c->pos[1] / n, up[2] = c->pos[2] / n;
}

/* The view axis in the local frame: forward (body X) taken to world, then back through the local frame. */
static void forward_local(const camera *c, double f[3])
{
    double w[3];
    quat_rotate(c->orient, AXIS_X, w);
    quat_rotate(quat_conj(c->frame), w, f);
}

void camera_init(camera *c, const sky_view *v, double ground_radius_km)
{
    double h = v->altitude_km < CAMERA_MIN_ALTITUDE_KM ? CAMERA_MIN_ALTITUDE_KM : v->altitude_km;
    *c = (camera){.pos = {0.0, ground_radius_km + h, 0.0}, .ground_radius_km = ground_radius_km, .altitude_km = h,
                  .frame = {1, 0, 0, 0},
                  .sun_azimuth_deg = v->sun_azimuth_deg, .sun_elevation_deg = v->sun_elevation_deg};
    /* dir(yaw, pitch) = R_y(-yaw) R_z(pitch) X: pitch tilts X toward Y, then yaw turns it toward Z. */
    double pitch = fmax(-MAX_PITCH_DEG, fmin(MAX_PITCH_DEG, v->pitch_deg));
    c->orient = quat_mul(quat_axis_angle(AXIS_Y, -v->yaw_deg * DEG), quat_axis_angle(AXIS_Z, pitch * DEG));
}

/* Move by world displacement d. The altitude is updated without forming |p| - Rb from two ~6360 km numbers:
 * |p + d|^2 - Rb^2 = h (2 Rb + h) + 2 r (up . d) + |d|^2, and h' = (|p + d|^2 - Rb^2) / (|p + d| + Rb)
 * (the model's cancellation-free altitude along a ray). The local frame and the view are carried along by the
 * rotation that takes the old up to the new one, so flying level over the curved ground stays level. */
static void camera_move(camera *c, const double d[3])
{
    const double rb = c->ground_radius_km;
    double up[3], p[3], new_up[3];
    local_up(c, up);
    double r = rb + c->altitude_km;
    for (int i = 0; i < 3; ++i) p[i] = c->pos[i] + d[i];
    double r_new = sqrt(dot3(p, p));
    double h = (c->altitude_km * (2.0 * rb + c->altitude_km) + 2.0 * r * dot3(up, d) + dot3(d, d)) / (r_new + rb);
    if (h < CAMERA_MIN_ALTITUDE_KM) h = CAMERA_MIN_ALTITUDE_KM;   /* clamp: slide along the ground */
    for (int i = 0; i < 3; ++i) new_up[i] = p[i] / r_new;
    /* Keep position and altitude consistent by construction: |pos| = Rb + h exactly up to rounding. */
    for (int i = 0; i < 3; ++i) c->pos[i] = new_up[i] * (rb + h);
    c->altitude_km = h;
    camera_quat transport = quat_from_to(up, new_up);
    c->frame = quat_normalize(quat_mul(transport, c->frame));
    c->orient = quat_normalize(quat_mul(transport, c->orient));
}

/* Mouse look: yaw about the local up (world), pitch about the body's right axis, so the right axis stays
 * horizontal (no roll; the renderer's camera has none). Pitch stays within +-89.9 degrees. */
static void camera_look(camera *c, double yaw_deg, double pitch_deg)
{
    double up[3], f[3];
    local_up(c, up);
    c->orient = quat_mul(quat_axis_angle(up, -yaw_deg * DEG), c->orient);
    forward_local(c, f);
    double pitch = asin(fmax(-1.0, fmin(1.0, f[1]))) / DEG;
    double target = fmax(-MAX_PITCH_DEG, fmin(MAX_PITCH_DEG, pitch + pitch_deg));
    c->orient = quat_normalize(quat_mul(c->orient, quat_axis_angle(AXIS_Z, (target - pitch) * DEG)));
}

/* The sun lives in the local frame (it follows the camera): azimuth wraps to (-180, 180], elevation clamps. */
static void sun_update(camera *c, double d_azimuth_deg, double d_elevation_deg)
{
    double az = fmod(c->sun_azimuth_deg + d_azimuth_deg, 360.0);
    c->sun_azimuth_deg = az > 180.0 ? az - 360.0 : az <= -180.0 ? az + 360.0 : az;
    c->sun_elevation_deg = fmax(-90.0, fmin(90.0, c->sun_elevation_deg + d_elevation_deg));
}

void camera_update(camera *c, const camera_input *in, double dt_s)
{
    sun_update(c, in->sun_azimuth_deg, in->sun_elevation_deg);
    camera_look(c, in->yaw_deg, in->pitch_deg);
    double f[3], right[3], up[3], d[3];
    quat_rotate(c->orient, AXIS_X, f);
    quat_rotate(c->orient, AXIS_Z, right);
    local_up(c, up);
    for (int i = 0; i < 3; ++i) d[i] = in->forward * f[i] + in->right * right[i] + in->up * up[i];
    double len = sqrt(dot3(d, d));
    if (len == 0.0 || dt_s <= 0.0) return;
    /* Diagonal moves are as fast as straight ones. */
    double step = CAMERA_SPEED_KM_S * (in->boost ? CAMERA_BOOST : 1.0) * dt_s / (len > 1.0 ? len : 1.0);
    for (int i = 0; i < 3; ++i) d[i] *= step;
    camera_move(c, d);
}

void camera_to_view(const camera *c, sky_view *v)
{
    double f[3];
    forward_local(c, f);
    v->altitude_km = c->altitude_km;
    v->yaw_deg = atan2(f[2], f[0]) / DEG;
    v->pitch_deg = asin(fmax(-1.0, fmin(1.0, f[1]))) / DEG;
    v->sun_azimuth_deg = c->sun_azimuth_deg;
    v->sun_elevation_deg = c->sun_elevation_deg;
}
