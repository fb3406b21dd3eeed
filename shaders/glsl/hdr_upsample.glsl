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

/* One side's taps around pos (texel coordinates): the bilinear weights of the taps of that side (sign of their
 * distance) renormalised; their mean value and mean distance. False if none of the four is of that side. */
bool hdr_side_taps(sampler2D hdr, vec2 pos, float side, out vec3 value, out float dist)
{
    ivec2 size = textureSize(hdr, 0);
    vec2 t = pos - 0.5;
    ivec2 i0 = ivec2(floor(t));
    vec2 f = t - vec2(i0);
    vec4 sum = vec4(0.0);
    float weight = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        vec4 tap = texelFetch(hdr, clamp(i0 + o, ivec2(0), size - 1), 0);
        float w = max((o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y), 1e-4);
        if (tap.a * side >= 0.0) sum += w * tap, weight += w;
    }
    value = weight > 0.0 ? sum.rgb / weight : vec3(0.0);
    dist = weight > 0.0 ? sum.a / weight : 0.0;
    return weight > 0.0;
}

/* One side's value at distance `target` (texels) from the horizon, near pos. The texels of a side nearest the
 * horizon lie up to a texel or two from it, where the sky (and a hazy ground) change fastest: so the value is
 * interpolated, or extrapolated by at most the spacing, along the distance between the side's taps at pos (or a
 * texel further in, where pos has none of them: the horizon is all but straight over a few texels) and those one
 * texel further in. `toward`: a step of about one texel into the side. */
vec3 hdr_side_value(sampler2D hdr, vec2 pos, vec2 toward, float side, float target)
{
    vec3 a = vec3(0.0), b;
    float da = 0.0, db;
    int step = 0;
    while (step < 3 && !hdr_side_taps(hdr, pos + float(step) * toward, side, a, da)) ++step;
    if (!hdr_side_taps(hdr, pos + float(step + 1) * toward, side, b, db) || abs(db - da) < 0.25) return a;
    float t = clamp((target - da) / (db - da), -1.0, 1.0);
    return max(a + (b - a) * t, vec3(0.0));
}

vec3 hdr_upsample(sampler2D hdr, vec2 uv, ivec2 out_size)
{
    ivec2 size = textureSize(hdr, 0);
    vec4 bilinear = textureLod(hdr, uv, 0.0);
    if (abs(bilinear.a) > 2.0) return bilinear.rgb;
    /* The distance's gradient per output pixel from the four taps' distances (texels), its unit normal, and the
     * output pixel's distance in output pixels. */
    vec2 pos = uv * vec2(size), t = pos - 0.5;
    ivec2 i0 = ivec2(floor(t));
    float d00 = texelFetch(hdr, clamp(i0, ivec2(0), size - 1), 0).a;
    float d10 = texelFetch(hdr, clamp(i0 + ivec2(1, 0), ivec2(0), size - 1), 0).a;
    float d01 = texelFetch(hdr, clamp(i0 + ivec2(0, 1), ivec2(0), size - 1), 0).a;
    float d11 = texelFetch(hdr, clamp(i0 + ivec2(1, 1), ivec2(0), size - 1), 0).a;
    vec2 per_texel = vec2(0.5 * (d10 - d00 + d11 - d01), 0.5 * (d01 - d00 + d11 - d10));
    vec2 texels_per_pixel = vec2(size) / vec2(out_size);
    vec2 g = per_texel * texels_per_pixel;   /* change of the distance (texels) per output pixel */
    float len = length(g);
    /* A clamped tap (the image's edge) can leave no gradient: the pixel takes its own side. */
    if (len < 1e-6) return bilinear.rgb;
    vec2 n = g / len;
    float d = bilinear.a / len, half_extent = horizon_half_extent(n);
    float coverage = horizon_box_coverage(d, n);
    /* Each part's centroid along the normal (output pixels, as the sky pass's), in texels of distance. */
    float sky_at = max(0.5 * (max(0.0, d - half_extent) + d + half_extent), 0.0) * len;
    float ground_at = min(0.5 * (d - half_extent + min(0.0, d + half_extent)), 0.0) * len;
    vec2 toward_sky = n * texels_per_pixel / max(texels_per_pixel.x, texels_per_pixel.y);   /* about one texel */
    vec3 sky = coverage > 0.0 ? hdr_side_value(hdr, pos, toward_sky, 1.0, sky_at) : vec3(0.0);
    vec3 ground = coverage < 1.0 ? hdr_side_value(hdr, pos, -toward_sky, -1.0, ground_at) : vec3(0.0);
    return mix(ground, sky, coverage);
}
