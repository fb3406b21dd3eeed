#version 450
/* The exposure meter (issue 32): the log-average (geometric mean) luminance of the HDR image, the key of auto
 * exposure, in two dispatches of this shader (MeterPush.pass.x):
 *   pass 0  one workgroup per VKSKY_METER_TILE^2 texels: each thread adds ln max(Y / scale, floor) over 4 x 4 texels
 *           (Y: Rec.709 luminance, scale: the HDR image's units per cd/m2) of rows pass.y .. pass.w - 1 (a band's
 *           own rows; every row for a whole frame), the group sums its threads in shared memory and writes
 *           (sum, count) into partial[group];
 *   pass 1  one workgroup adds every partial and writes result[slot]: the log-average L in cd/m2, EV100 =
 *           log2(L 100 / 12.5) (the reflected-light meter's key, ISO 2720) and the tone map's multiplier
 *           1 / (scale 1.2 2^EV100) (docs/units.md). With temporal adaptation (the window) the EV100 moves
 *           only part of the way from the last frame's (`adapted`, written by the previous frame's pass 1 in submission
 *           order: the spine's meter.to_write and meter.partials_to_average chain after it) toward the metered one.
 * A fixed order of additions (no atomics): the same image gives the same bits every time, so a sequence through the
 * readback ring writes the serial loop's files. With a black ground only sky texels count (HDR alpha, the signed
 * distance to the horizon, >= 0: horizon.glsl). */
#extension GL_GOOGLE_include_directive : require
#include "shared.h"

layout(local_size_x = 16, local_size_y = 16) in;
layout(set = 0, binding = VKSKY_BINDING_POST_SOURCE) uniform sampler2D hdr;
layout(std430, set = 0, binding = VKSKY_BINDING_METER) buffer Meter {
    vec4 result[VKSKY_METER_SLOTS];
    vec4 adapted;              /* x: the last frame's EV100, w: 1 once written (temporal adaptation) */
    vec2 partial[];
} meter;
layout(push_constant) uniform Push { MeterPush push; };

shared vec2 sums[256];

void main()
{
    uint li = gl_LocalInvocationIndex;
    vec2 s = vec2(0.0);
    if (push.pass.x < 0.5) {
        ivec2 size = textureSize(hdr, 0);
        ivec2 base = ivec2(gl_WorkGroupID.xy) * VKSKY_METER_TILE + ivec2(gl_LocalInvocationID.xy);
        for (int j = 0; j < VKSKY_METER_TILE / 16; ++j)
            for (int i = 0; i < VKSKY_METER_TILE / 16; ++i) {
                ivec2 p = base + 16 * ivec2(i, j);
                if (any(greaterThanEqual(p, size))) continue;
                if (p.y < int(push.pass.y) || p.y >= int(push.pass.w)) continue;   /* a band's shared rows: not its own */
                if (push.params.w > 0.5) {
                    /* A fisheye (W x W; pass.z: the whole image's row of this image's row 0): the texels outside its
                     * circle have no direction (written black), no part of the scene; projection.glsl's test. */
                    precise vec2 g = vec2(p) + vec2(0.5, 0.5 + push.pass.z);
                    float inv = 1.0 / float(size.x);
                    if (length(vec2(2.0 * g.x * inv - 1.0, 1.0 - 2.0 * g.y * inv)) > 1.0) continue;
                }
                vec4 t = texelFetch(hdr, p, 0);
                if (push.params.z < 0.5 && t.a < 0.0) continue;   /* the void below the horizon */
                float y = dot(t.rgb, vec3(0.2126, 0.7152, 0.0722)) / push.params.x;
                s += vec2(log(max(y, push.params.y)), 1.0);
            }
    } else {
        for (uint k = li; k < uint(push.pass.y); k += 256u) s += meter.partial[k];
    }
    sums[li] = s;
    barrier();
    for (uint n = 128u; n > 0u; n >>= 1) {
        if (li < n) sums[li] += sums[li + n];
        barrier();
    }
    if (li != 0u) return;
    if (push.pass.x < 0.5) {
        meter.partial[gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x] = sums[0];
        return;
    }
    /* No pixel counted (all ground): the floor (docs/units.md). */
    float l = sums[0].y > 0.0 ? exp(sums[0].x / sums[0].y) : push.params.y;
    float ev100 = log2(l * 100.0 / 12.5);
    if (push.pass.z < 1.0 && meter.adapted.w > 0.5) ev100 = mix(meter.adapted.x, ev100, push.pass.z);
    meter.adapted = vec4(ev100, 0.0, 0.0, 1.0);
    meter.result[int(push.params.w)] = vec4(l, ev100, 1.0 / (push.params.x * 1.2 * exp2(ev100)), sums[0].y);
}
