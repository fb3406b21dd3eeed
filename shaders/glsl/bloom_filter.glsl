/* The bloom downsample filter, shared by the fragment chain (bloom_downsample.frag) and the compute chain
 * (bloom_spd.comp): Jimenez's 13-tap filter (SIGGRAPH 2014), five 2x2 groups; the first level (from the HDR
 * image) applies a Karis average per group, which tames the sun's fireflies, and a brightness threshold. The
 * taps, in source texels from the destination texel's centre, in the order the groups below use them. */
const vec2 BLOOM_TAPS[13] = vec2[13](vec2(-2, -2), vec2(0, -2), vec2(2, -2), vec2(-1, -1), vec2(1, -1), vec2(-2, 0),
                                     vec2(0, 0), vec2(2, 0), vec2(-1, 1), vec2(1, 1), vec2(-2, 2), vec2(0, 2), vec2(2, 2));

float bloom_luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
/* One 2x2 group: its average and its weight (the filter's weight, times 1/(1 + luma) when Karis-averaging). */
void bloom_add_group(inout vec3 sum, inout float weight_sum, vec3 a, vec3 b, vec3 c, vec3 d, float w, bool karis)
{
    vec3 avg = 0.25 * (a + b + c + d);
    float wk = karis ? w / (1.0 + bloom_luma(avg)) : w;
    sum += wk * avg;
    weight_sum += wk;
}

/* s[i]: the source at BLOOM_TAPS[i]. `first`: Karis average and threshold (the level read from the HDR image). */
vec3 bloom_filter13(vec3 s[13], bool first, float threshold)
{
    vec3 sum = vec3(0.0);
    float weight_sum = 0.0;
    bloom_add_group(sum, weight_sum, s[3], s[4], s[8], s[9], 0.5, first);
    bloom_add_group(sum, weight_sum, s[0], s[1], s[5], s[6], 0.125, first);
    bloom_add_group(sum, weight_sum, s[1], s[2], s[6], s[7], 0.125, first);
    bloom_add_group(sum, weight_sum, s[5], s[6], s[10], s[11], 0.125, first);
    bloom_add_group(sum, weight_sum, s[6], s[7], s[11], s[12], 0.125, first);
    vec3 color = sum / weight_sum;
    if (first) {
        /* Brightness threshold: keep only the part of each pixel above it, hue preserved. */
        float lum = bloom_luma(color);
        color *= max(lum - threshold, 0.0) / max(lum, 1e-4);
    }
    return min(color, vec3(65504.0));
}

/* The upsample filter: a 9-tap tent of the smaller mip, `t` its texel size, at `uv` (weights 4, 2, 1 / 16). */
vec3 bloom_tent9(sampler2D src, vec2 uv, vec2 t)
{
    vec3 c = 4.0 * textureLod(src, uv, 0.0).rgb;
    c += 2.0 * (textureLod(src, uv + vec2(t.x, 0), 0.0).rgb + textureLod(src, uv - vec2(t.x, 0), 0.0).rgb
              + textureLod(src, uv + vec2(0, t.y), 0.0).rgb + textureLod(src, uv - vec2(0, t.y), 0.0).rgb);
    c += textureLod(src, uv + t, 0.0).rgb + textureLod(src, uv - t, 0.0).rgb
       + textureLod(src, uv + vec2(t.x, -t.y), 0.0).rgb + textureLod(src, uv + vec2(-t.x, t.y), 0.0).rgb;
    return c / 16.0;
}
