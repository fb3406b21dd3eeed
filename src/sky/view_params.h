/* A view (camera, sun, march settings, tone map) and what a frame makes of it: the push constants of the sky
 * pass, the sky-view LUT pass and the tone map, and the sky mode and pass kind it resolves to. Plain arithmetic on
 * the view; no renderer state (the spine passes in the little it needs: the atmosphere's top, the device type). */
#ifndef VKSKY_SKY_VIEW_PARAMS_H
#define VKSKY_SKY_VIEW_PARAMS_H
#include "sky/passes.h"

typedef enum sky_mode_choice { SKY_CHOICE_MARCH, SKY_CHOICE_SKYVIEW, SKY_CHOICE_AUTO, SKY_CHOICE_FILL } sky_mode_choice;

typedef struct sky_view {
    double altitude_km;                     /* camera altitude above the ground, >= 0 */
    double yaw_deg, pitch_deg, fov_deg;     /* view axis: same convention as the sun's azimuth/elevation */
    double sun_azimuth_deg, sun_elevation_deg;
    int steps;                              /* view march steps (the minimum when max_steps > steps) */
    int max_steps;                          /* > steps: Hillaire's variable count, growing with path length (0: fixed) */
    double steps_ramp_km;                   /* path length at which the variable count reaches max_steps */
    double sample_offset;                   /* sample position within a step: 0.5 midpoint, 0.3 Hillaire */
    double step_distribution;               /* step ends at t_max (i/N)^p: 1 uniform, 2 quadratic (Hillaire) */
    sky_mode_choice mode;                   /* per-pixel march, sky-view LUT lookup, or auto */
    sky_pass_kind pass_kind;                /* fragment or compute sky pass */
    int skyview_steps;                      /* march steps of the sky-view LUT texels */
    double exposure_ev;                     /* tone map exposure, in stops (ev100: EV100, the camera's) */
    bool ev100;                             /* photometric: exposure_ev is EV100, the HDR holds cd/m2 x light_scale */
    double light_scale;                     /* photometric: the HDR image's units per cd/m2 (a power of two) */
    bool auto_exposure;                     /* exposure from the GPU meter of the same frame (sky/meter.h; issue 32):
                                               exposure_ev is then not used */
    double auto_exposure_ease;              /* temporal adaptation: the fraction of the way from the last frame's EV100
                                               to the metered one (0: none; the window: 1 - exp(-dt / tau)) */
    int tonemap;                            /* VKSKY_TONEMAP_* */
    bool bloom;
    double bloom_strength, bloom_threshold;
    int projection;                         /* sky_projection (sky/projection.h): pixel -> direction */
    int tile_x, tile_y;                     /* tiled renders: this frame's pixel offset in the whole image */
    int whole_width, whole_height;          /* tiled renders: the whole image (0: the frame is the whole image) */
    bool no_dither;                         /* the 8-bit display output without its triangular dither */
    /* The library's host camera (its matrices): the rays' basis in the march frame given instead of yaw, pitch and
     * fov: a pixel's ray is ray_forward + x ray_right + y ray_up, x and y in [-1, 1] (y = 1: top row). */
    bool ray_given;
    double ray_forward[3], ray_right[3], ray_up[3];
} sky_view;

sky_view sky_view_default(void);

/* The sky pass kind a frame of this view uses (auto: fragment on a CPU device, compute otherwise). */
sky_pass_kind sky_view_pass_kind(const sky_view *v, VkPhysicalDeviceType device_type);
/* The sky mode a frame of this view uses (auto: the sky-view LUT inside the atmosphere, the march from space);
 * atmosphere_top_km: the atmosphere's top altitude above the ground. */
sky_mode sky_view_resolve_mode(const sky_view *v, double atmosphere_top_km);
/* The camera's unit basis in the world (+Y up): forward (the view axis), right = forward x +Y, up = right x forward.
 * A pixel's ray is forward + x tan(fov/2) aspect right + y tan(fov/2) up, x and y in [-1, 1] (y = 1: top row). */
void sky_view_basis(const sky_view *v, double forward[3], double right[3], double up[3]);
/* Camera + sun -> the sky pass's push constants (the ray matrix built from the camera basis). width x height: the
 * sky image's texels; aspect: the output image's width / height (a scaled sky rounds its size, not the view). */
SkyPush sky_view_push(const sky_view *v, uint32_t width, uint32_t height, double aspect);
/* The sky-view LUT pass's push constants (its own march settings). */
SkyPush sky_view_skyview_push(const sky_view *v);
/* The sine of the horizon's elevation seen from altitude h above a sphere of radius R (both km), in double:
 * -sqrt(h (2R + h)) / (R + h) (no planet-scale subtraction); 0 at h = 0. */
double sky_view_horizon_sine(double altitude_km, double ground_radius_km);
/* The push's horizon: its sine for this view's altitude over a planet of radius R; `resolve`: the sky pass writes the
 * output's own pixels (render scale 1) and resolves their coverage of sky and ground itself. */
void sky_view_set_horizon(SkyPush *push, const sky_view *v, double ground_radius_km, double atmosphere_top_km,
                          bool resolve);
/* The sky-view lookup's weight of the per-pixel march at this altitude: 0 below a quarter of the atmosphere's height, 1 at
 * its top, linear between (the lookup and the march meet where --sky-mode auto switches). */
double sky_view_march_blend(double altitude_km, double atmosphere_top_km);
/* The same for the rays near the horizon and below 3 degrees of elevation (shaders/glsl/horizon.glsl), where the LUT
 * is furthest off high up: 0 below a tenth of the atmosphere's height, 1 from three tenths (10 and 30 km on Earth). */
double sky_view_horizon_march_blend(double altitude_km, double atmosphere_top_km);
TonemapPush sky_view_tonemap_push(const sky_view *v, bool encode_srgb_in_shader);
#endif
