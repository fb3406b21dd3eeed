/* The tone map's read of the sky (HDR) image at an output pixel, shared by the fragment and compute tone maps.
 * Each sky texel holds its centre's class only (sky or ground, never a blend: horizon.glsl) and, in alpha, the signed
 * distance from its centre to the horizon in texels (positive: sky). The distance is smooth, so its bilinear sample
 * is the output pixel's own distance: away from the horizon (more than two texels, beyond every tap) the output
 * pixel is the plain bilinear sample, one fetch (at render scale 1, the texel itself). Near it the output pixel takes
 * its analytic coverage of the sky (the box coverage of horizon.glsl, in output pixels) and mixes a sky value,
 * interpolated from the sky taps alone, with a ground value from the ground taps alone: the horizon sits where the
 * geometry puts it, per output pixel and anti-aliased, at every render scale, and no ground is blended into the sky
 * nor sky into the ground. Only pixels near the horizon pay for the taps. */
#include "horizon.glsl"

/* One side's value at distance `target` (texels) from the horizon: a = the mean of that side's taps among the four
 * around the pixel (bilinear weights, renormalised; weight 0: none of them is of that side) at mean distance da, and
 * b = the texel one step further into the side, at distance db. The side's texels nearest the horizon lie up to a
 * texel or two from it, where the sky (and a hazy ground) change fastest: so the value is interpolated, or
 * extrapolated by at most the spacing, along the distance from a to b; b alone where the four have none. */
vec3 hdr_side_value(vec4 a_sum, float a_weight, vec4 b, float target)
{
    if (a_weight <= 0.0) return b.rgb;
    vec3 a = a_sum.rgb / a_weight;
    float da = a_sum.a / a_weight;
    float t = abs(b.a - da) < 0.25 ? 0.0 : clamp((target - da) / (b.a - da), -1.0, 1.0);
    return max(a + (b.rgb - a) * t, vec3(0.0));
}

/* Straight-line code, a fixed seven fetches near the horizon: lavapipe runs a branch's body for every pixel whether
 * or not any takes it, so every fetch and loop here costs the whole frame there. */
/* The rows the taps may read: the image's own, or in a tiled render (one band with a row of its neighbours above and
 * below: app/runs/tiles.c) those inside the whole image, so a band's edge pixels see what they see in one whole image.
 * dither: TonemapPush's (yz the frame's offset in the whole image, w the whole height or 0). Render scale 1 there. */
ivec2 hdr_rows(ivec2 size, vec4 dither)
{
    int top = int(dither.z);
    return dither.w > 0.0 ? ivec2(max(0, -top), min(size.y - 1, int(dither.w) - 1 - top)) : ivec2(0, size.y - 1);
}

/* The far-only variants: the tiles of the output that sky/tonemap_regions.c finds out of the horizon path's reach
 * (lavapipe pays for the path's body on every pixel of a shader that has it, taken or not). Each of their pixels
 * would take the far path anyway: the image is the same. 0: the full shader; 1: far only, the sky image smaller
 * than the output (filtered); 2: far only, the sky image the output's size (fetched). */
layout(constant_id = VKSKY_SPEC_TONEMAP_FAR) const int HDR_FAR = 0;

vec3 hdr_upsample(sampler2D hdr, vec2 uv, ivec2 out_size, ivec2 rows)
{
    ivec2 size = textureSize(hdr, 0);
    ivec2 lo = ivec2(0, rows.x), hi = ivec2(size.x - 1, rows.y);
    /* At render scale 1 an output pixel is its texel, fetched (issue 26: the 64x32 map's row 27). A bilinear sample
     * at the pixel's centre, (x + 0.5) / size, lands on the texel's centre only where that is exact in float (a
     * power-of-two size); elsewhere the filter mixes a neighbour in at a rounding-sized weight, and where the value
     * is a half subnormal (a dark ground under a photometric frame's disc scale, 2^-24 a step: 1/256 cd/m2) the
     * rounding of the result moves it by a whole step: a band, whose image height is not the whole image's, then
     * differed from the whole image on the rows that sat at a step's edge. */
    bool fetch = HDR_FAR == 0 ? size == out_size : HDR_FAR == 2;   /* (a variant's: no second fetch on lavapipe) */
    /* The same holds for the taps below: at render scale 1 the pixel's position is its texel's centre, exactly. The
     * interpolated uv times the size lands a rounding away from it, on either side depending on the image's size
     * (a fragment's uv comes from the full-screen triangle's setup), so floor(pos - 0.5) took the quad one texel up
     * or left on some rows and columns of one image and not of another: a band's quad and the whole image's then
     * differed, and at a fisheye's rim, where a tap outside the circle carries the clamped distance 1e4, the
     * gradient and the coverage with it moved by up to 18/255 (docs/horizon.md "Bands equal the whole image"). */
    vec2 pos = fetch ? floor(uv * vec2(size)) + 0.5 : uv * vec2(size);
    vec4 bilinear = fetch ? texelFetch(hdr, ivec2(pos), 0) : textureLod(hdr, uv, 0.0);
    if (HDR_FAR != 0 || abs(bilinear.a) > 2.0) return bilinear.rgb;
    /* The four taps, the distance's gradient per output pixel, its unit normal, the pixel's distance in output
     * pixels and its coverage of the sky. */
    vec2 t = pos - 0.5;
    ivec2 i0 = ivec2(floor(t));
    vec2 f = t - vec2(i0);
    vec4 taps[4];
    vec4 sky_sum = vec4(0.0), ground_sum = vec4(0.0);
    float sky_weight = 0.0, ground_weight = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        taps[k] = texelFetch(hdr, clamp(i0 + o, lo, hi), 0);
        float w = max((o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y), 1e-4);
        bool sky = taps[k].a >= 0.0;
        sky_sum += sky ? w * taps[k] : vec4(0.0), sky_weight += sky ? w : 0.0;
        ground_sum += sky ? vec4(0.0) : w * taps[k], ground_weight += sky ? 0.0 : w;
    }
    vec2 per_texel = vec2(0.5 * (taps[1].a - taps[0].a + taps[3].a - taps[2].a),
                          0.5 * (taps[2].a - taps[0].a + taps[3].a - taps[1].a));
    vec2 texels_per_pixel = vec2(size) / vec2(out_size);
    vec2 g = per_texel * texels_per_pixel;   /* change of the distance (texels) per output pixel */
    float len = max(length(g), 1e-6);
    vec2 n = g / len;
    float d = bilinear.a / len, half_extent = horizon_half_extent(n);
    float coverage = horizon_box_coverage(d, n);
    /* At render scale 1 a pixel the horizon does not cross is its own texel, whatever its neighbours (a banded
     * render's taps clamp at the band's edge). */
    bool whole = coverage <= 0.0 || coverage >= 1.0;
    if (size == out_size && whole) return bilinear.rgb;
    /* Each part's centroid along the normal (output pixels, as a box's), in texels of distance. */
    float sky_at = max(0.5 * (max(0.0, d - half_extent) + d + half_extent), 0.0) * len;
    float ground_at = min(0.5 * (d - half_extent + min(0.0, d + half_extent)), 0.0) * len;
    /* One texel further into each side along the normal (in texels). */
    vec2 step_texels = n * texels_per_pixel / max(texels_per_pixel.x, texels_per_pixel.y);
    vec4 sky_b = texelFetch(hdr, clamp(ivec2(floor(pos + step_texels)), lo, hi), 0);
    vec4 ground_b = texelFetch(hdr, clamp(ivec2(floor(pos - step_texels)), lo, hi), 0);
    vec3 sky = hdr_side_value(sky_sum, sky_weight, sky_b, sky_at);
    vec3 ground = hdr_side_value(ground_sum, ground_weight, ground_b, ground_at);
    return mix(ground, sky, coverage);
}
