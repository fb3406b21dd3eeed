/* The planet's edge per pixel (issue 26), shared by the sky passes (fragment and compute; march, sky-view lookup)
 * and, for the box coverage, the tone map's read of the sky (hdr_upsample.glsl), which resolves it per output pixel.
 * The horizon's elevation comes from the CPU in double (SkyPush.horizon.x: its sine, -sqrt(h (2R + h)) / (R + h)),
 * so no pixel decides sky or ground by a float sphere test at a grazing ray. A pixel's footprint is a unit box; the
 * horizon crosses it as a line (its curvature over one pixel is far below a pixel); the sky's share of the box is
 * the area on the line's upper side, in closed form. */
#ifndef VKSKY_HORIZON_GLSL
#define VKSKY_HORIZON_GLSL

/* The area of the unit box on the positive side of a line at signed distance d (pixels) from its centre with unit
 * normal n: linear while the line crosses two opposite sides, quadratic where it cuts a corner. */
float horizon_box_coverage(float d, vec2 n)
{
    float a = max(abs(n.x), abs(n.y)), b = min(abs(n.x), abs(n.y));   /* a >= 1/sqrt(2) */
    float half_extent = 0.5 * (a + b), s = abs(d), inside;
    if (s >= half_extent) inside = 1.0;
    else if (s <= 0.5 * (a - b)) inside = 0.5 + s / a;
    else inside = 1.0 - (half_extent - s) * (half_extent - s) / (2.0 * a * b);
    return d >= 0.0 ? inside : 1.0 - inside;
}

/* Half the box's extent along n (the distance from its centre to its farthest corner along the normal). */
float horizon_half_extent(vec2 n) { return 0.5 * (abs(n.x) + abs(n.y)); }

/* The sky-view LUT's rows near the horizon are dense (Hillaire's quadratic latitude mapping, the horizon between two
 * rows), yet the sky changes fastest there, and most where the camera is high: from a tenth of the atmosphere's
 * height up (the blend variant), its pixels within this many pixels of the horizon march their own ray instead of
 * reading the LUT (a band of about 2 x this many rows a column). */
#define VKSKY_HORIZON_DIRECT_PX 2.0
/* ... and its sky rays below this elevation's sine (3 degrees; see sky_pixel). */
#define VKSKY_HORIZON_DIRECT_SIN 0.0523

#ifdef VKSKY_PROJECTION_GLSL
/* Signed distance (this image's pixels, positive = sky) from a pixel centre to the horizon, and the unit normal
 * (in pixels, toward the sky). The elevation's sine v.y - sin(horizon) is the level function; its gradient comes
 * from central differences a quarter pixel apart (inside one cube face; the projection is smooth there). */
float horizon_distance(vec2 centre, SkyPush p, out vec2 n)
{
    bool inside;
    float sin_h = p.horizon.x;
    float f = pixel_view_dir(centre, p, inside).y - sin_h;
    const float e = 0.25;
    float gx = pixel_view_dir(centre + vec2(e, 0.0), p, inside).y - pixel_view_dir(centre - vec2(e, 0.0), p, inside).y;
    float gy = pixel_view_dir(centre + vec2(0.0, e), p, inside).y - pixel_view_dir(centre - vec2(0.0, e), p, inside).y;
    vec2 g = vec2(gx, gy) / (2.0 * e);
    float len = length(g);
    n = len > 0.0 ? g / len : vec2(0.0, -1.0);
    /* Where the elevation does not change across the pixel (the fisheye's zenith, a cube face's centre looking
     * straight down) the pixel is wholly on its centre's side. */
    return len > 1e-12 ? clamp(f / len, -1.0e4, 1.0e4) : (f >= 0.0 ? 1.0e4 : -1.0e4);
}

/* One ray's radiance: the variant's (SKY_RADIANCE: march, lookup or fill) or, in the blend variant, a blend of the
 * lookup and the ray's own march (the march alone where `direct`). */
spectrum_t sky_eval(vec3 v, SkyPush p, bool direct)
{
#ifdef SKY_RADIANCE_DIRECT
    /* horizon.z: the march's weight from a quarter of the atmosphere's height up; horizon.w: the weight of the rays
     * near the horizon, from a tenth of it to three tenths (sky_view_march_blend). */
    float march_weight = direct ? p.horizon.w : p.horizon.z;
    spectrum_t c = spectrum_t(0.0);
    if (march_weight < 1.0) c += (1.0 - march_weight) * SKY_RADIANCE(p.forward.w, v, p.sun_dir.xyz, p.march);
    if (march_weight > 0.0) c += march_weight * SKY_RADIANCE_DIRECT(p.forward.w, v, p.sun_dir.xyz, p.march);
    return c;
#else
    return SKY_RADIANCE(p.forward.w, v, p.sun_dir.xyz, p.march);
#endif
}

/* The sky pass's pixel: its class's radiance (sky or ground, never a blend of the two) and, in alpha, the signed
 * distance from its centre to the horizon (pixels of this image). The tone map (hdr_upsample.glsl) resolves each
 * output pixel's coverage of sky and ground from that distance, at every render scale: one evaluation a pixel here,
 * straight-line code (lavapipe runs a branch's body under a lane mask even where no lane takes it: a second
 * evaluation for the pixels the horizon crosses cost every pixel of the lookup variant, measured 4-5x its sky pass). */
vec4 sky_pixel(vec2 centre, SkyPush p)
{
    bool inside;
    vec3 v = pixel_view_dir(centre, p, inside);
#ifdef SPECTRAL4
    /* The four-wide build's alpha is its fourth wavelength: no horizon distance (its tone map reads the texel). */
    if (!inside) return vec4(0.0);
#else
    if (!inside) return vec4(0.0, 0.0, 0.0, 1.0e4);
#endif
    sky_texel_angle = texel_angle(p);
    vec2 n;
    float d = horizon_distance(centre, p, n);
    /* The blend variant (from 10 km up) marches the band at the horizon, and every sky ray below 3 degrees of
     * elevation (from 10 km 6 degrees of sky, from 100 km 13: the horizon sinks). Those rays graze the limb's glow or skim the thin air near the
     * horizontal, where the sky changes by tens of per cent a degree from high up, faster than the LUT's rows
     * (about a degree apart there) can follow; and their edge, a fixed elevation, does not move with the camera's
     * altitude, so no pixel switches from the LUT to the march as the camera climbs (no pop on the way to space). */
    bool direct = abs(d) < VKSKY_HORIZON_DIRECT_PX || (d > 0.0 && v.y < VKSKY_HORIZON_DIRECT_SIN);
    sky_forced_class = d >= 0.0 ? 1 : 0;
    return SPECTRUM_TO_VEC4(sky_eval(v, p, direct), d);
}
#endif
#endif
