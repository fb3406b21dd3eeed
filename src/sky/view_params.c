/* A view -> the push constants and choices of a frame (see sky/view_params.h). */
#include "sky/view_params.h"
#include <math.h>

static const double DEG = 3.14159265358979323846 / 180.0;

sky_view sky_view_default(void)
{
    return (sky_view){
        .altitude_km = 0.001, .yaw_deg = 0.0, .pitch_deg = 10.0, .fov_deg = 75.0,
        .sun_azimuth_deg = 0.0, .sun_elevation_deg = 20.0, .steps = 32, .max_steps = 0, .steps_ramp_km = 100.0,
        .sample_offset = 0.5, .step_distribution = 2.0, .mode = SKY_CHOICE_MARCH, .pass_kind = SKY_PASS_AUTO, .skyview_steps = 30,
        .exposure_ev = 0.0, .tonemap = VKSKY_TONEMAP_ACES, .bloom = true,
        .bloom_strength = 0.04, .bloom_threshold = 1.0};
}

static void dir_from_angles(double az_deg, double el_deg, double out[3])
{
    double az = az_deg * DEG, el = el_deg * DEG;
    out[0] = cos(el) * cos(az);
    out[1] = sin(el);
    out[2] = cos(el) * sin(az);
}

void sky_view_basis(const sky_view *v, double f[3], double right[3], double up[3])
{
    dir_from_angles(v->yaw_deg, v->pitch_deg, f);
    if (fabs(v->pitch_deg) >= 90.0 - 1e-9) {
        dir_from_angles(v->yaw_deg + 90.0, 0.0, right);
    } else {
        /* right = normalize(cross(f, +Y)) */
        double rx = -f[2], rz = f[0], n = sqrt(rx * rx + rz * rz);
        right[0] = rx / n, right[1] = 0.0, right[2] = rz / n;
    }
    /* up = cross(right, f) */
    up[0] = right[1] * f[2] - right[2] * f[1];
    up[1] = right[2] * f[0] - right[0] * f[2];
    up[2] = right[0] * f[1] - right[1] * f[0];
}

SkyPush sky_view_push(const sky_view *v, uint32_t width, uint32_t height, double aspect)
{
    /* The ray matrix: camera basis scaled by tan(fov/2) and the aspect ratio, built in double. */
    double f[3], right[3], up[3];
    sky_view_basis(v, f, right, up);
    /* A tile addresses the whole image: its pixels' directions are those of the same pixels of an untiled frame. */
    if (v->whole_width > 0 && v->whole_height > 0) {
        width = (uint32_t)v->whole_width, height = (uint32_t)v->whole_height;
        aspect = (double)v->whole_width / (double)v->whole_height;
    }
    double ty = tan(0.5 * v->fov_deg * DEG), tx = ty * aspect;
    double rx[3] = {right[0] * tx, right[1] * tx, right[2] * tx}, uy[3] = {up[0] * ty, up[1] * ty, up[2] * ty};
    if (v->ray_given)
        for (int i = 0; i < 3; ++i) f[i] = v->ray_forward[i], rx[i] = v->ray_right[i], uy[i] = v->ray_up[i];
    double sun[3];
    dir_from_angles(v->sun_azimuth_deg, v->sun_elevation_deg, sun);
    int max_steps = v->max_steps > v->steps ? v->max_steps : v->steps;
    return (SkyPush){
        .forward = {(float)f[0], (float)f[1], (float)f[2], (float)v->altitude_km},
        /* w: 1 / width (the cube map: 1 / face size = 1 / width as well) */
        .right = {(float)rx[0], (float)rx[1], (float)rx[2], 1.0f / (float)width},
        .up = {(float)uy[0], (float)uy[1], (float)uy[2], 1.0f / (float)height},
        .sun_dir = {(float)sun[0], (float)sun[1], (float)sun[2], (float)v->step_distribution},
        .march = {(float)v->steps, (float)max_steps, (float)v->sample_offset, (float)v->steps_ramp_km},
        .projection = {(float)v->projection, (float)v->tile_x, (float)v->tile_y, 0.0f},
    };
}

SkyPush sky_view_skyview_push(const sky_view *v)
{
    SkyPush p = sky_view_push(v, 1, 1, 1.0);
    p.march = (vksky_vec4){(float)v->skyview_steps, (float)v->skyview_steps, (float)v->sample_offset,
                           (float)v->steps_ramp_km};
    return p;
}

sky_pass_kind sky_view_pass_kind(const sky_view *v, VkPhysicalDeviceType device_type)
{
    if (v->pass_kind != SKY_PASS_AUTO) return v->pass_kind;
    return device_type == VK_PHYSICAL_DEVICE_TYPE_CPU ? SKY_PASS_FRAGMENT : SKY_PASS_COMPUTE;
}

sky_mode sky_view_resolve_mode(const sky_view *v, double atmosphere_top_km)
{
    if (v->mode == SKY_CHOICE_MARCH) return SKY_MODE_MARCH;
    if (v->mode == SKY_CHOICE_FILL) return SKY_MODE_FILL;
    bool inside = v->altitude_km < atmosphere_top_km;
    if (v->mode == SKY_CHOICE_SKYVIEW) return inside ? SKY_MODE_SKYVIEW : SKY_MODE_MARCH;
    return inside ? SKY_MODE_SKYVIEW : SKY_MODE_MARCH;
}

double sky_view_horizon_sine(double altitude_km, double ground_radius_km)
{
    double h = altitude_km > 0.0 ? altitude_km : 0.0, r = ground_radius_km + h;
    return -sqrt(h * (2.0 * ground_radius_km + h)) / r;
}

double sky_view_march_blend(double altitude_km, double atmosphere_top_km)
{
    double x = (altitude_km - 0.25 * atmosphere_top_km) / (0.75 * atmosphere_top_km);
    return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x;
}

double sky_view_horizon_march_blend(double altitude_km, double atmosphere_top_km)
{
    double x = (altitude_km - 0.1 * atmosphere_top_km) / (0.2 * atmosphere_top_km);
    return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x;
}

void sky_view_set_horizon(SkyPush *push, const sky_view *v, double ground_radius_km, double atmosphere_top_km,
                          bool resolve)
{
    push->horizon = (vksky_vec4){(float)sky_view_horizon_sine(v->altitude_km, ground_radius_km), resolve ? 1.0f : 0.0f,
                                 (float)sky_view_march_blend(v->altitude_km, atmosphere_top_km),
                                 (float)sky_view_horizon_march_blend(v->altitude_km, atmosphere_top_km)};
}

TonemapPush sky_view_tonemap_push(const sky_view *v, bool encode_srgb_in_shader)
{
    /* Photometric: a camera's saturation-based exposure, H = L / (1.2 2^EV100) (ISO 12232, K = 12.5 and q = 0.65
     * folded into the 1.2), on HDR values that hold L x light_scale. */
    double multiplier = v->ev100 ? 1.0 / (v->light_scale * 1.2 * exp2(v->exposure_ev)) : exp2(v->exposure_ev);
    /* Auto exposure: the multiplier comes from the GPU meter (the frame spine sets the slot, meter.y). */
    if (v->auto_exposure) multiplier = 1.0;
    return (TonemapPush){.meter = {v->auto_exposure ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f},
                         .params = {(float)multiplier, (float)v->tonemap,
                                    v->bloom ? (float)v->bloom_strength : 0.0f, encode_srgb_in_shader ? 1.0f : 0.0f},
                         .dither = {v->no_dither ? 0.0f : 1.0f, (float)v->tile_x, (float)v->tile_y,
                                    (float)v->whole_height}};
}
