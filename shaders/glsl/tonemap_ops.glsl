/* The tone map operators and the sRGB encoding, shared by the fragment (tonemap_common.glsl) and compute
 * (tonemap.comp) tone maps. */
vec3 aces_fitted(vec3 x)
{
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
vec3 srgb_encode(vec3 c)
{
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}
/* params: TonemapPush's (x exposure multiplier, y operator, w 1 = encode sRGB). */
vec3 tonemap_apply(vec3 color, vec4 params)
{
    vec3 x = color * params.x;
    int op = int(params.y);
    vec3 mapped = op == VKSKY_TONEMAP_ACES ? aces_fitted(x)
                : op == VKSKY_TONEMAP_REINHARD ? x / (1.0 + x)
                : clamp(x, 0.0, 1.0);
    return params.w > 0.5 ? srgb_encode(mapped) : mapped;
}
/* Auto exposure (issue 32): the GPU meter's result for this frame (meter.comp wrote it earlier in the same frame;
 * the spine's meter.result_to_tonemap barrier orders it). meter: TonemapPush's (x 1 = on, y the slot). */
layout(std430, set = 0, binding = VKSKY_BINDING_METER) readonly buffer MeterResults {
    vec4 result[VKSKY_METER_SLOTS];
} meter_results;
vec4 tonemap_exposed(vec4 params, vec4 meter)
{
    if (meter.x > 0.5) params.x *= meter_results.result[int(meter.y)].z;
    return params;
}
