#version 450
/* Hillaire's aerial-perspective volume (--aerial-perspective volume): per froxel, camera -> the point at its slice's
 * distance along its column's ray, by aerial.glsl's march (the same march the composite's per-pixel path runs).
 * Layout: aerial.glsl ("The volume"); sizes, range and distribution: src/sky/ap_volume.h. */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"

layout(set = 0, binding = VKSKY_BINDING_TRANSMITTANCE_LUT) uniform sampler2D transmittance_lut;
layout(set = 0, binding = VKSKY_BINDING_MULTISCATTER_LUT) uniform sampler2D multiscatter_lut;
layout(set = 0, binding = VKSKY_BINDING_OUTPUT, rgba16f) uniform writeonly image3D ap_volume_out;
layout(push_constant) uniform Push { CompositePush push; };

/* A segment to a froxel never ends on the lit ground (lit_ground is not called): no ground-irradiance LUT. */
#define GROUND_SKY_IRRADIANCE(mu_s) vec3(0.0)
#include "sky_common.glsl"
#define AP_VOLUME_BUILD
#include "aerial.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

void main()
{
    ivec3 size = imageSize(ap_volume_out);
    int depth = size.z / 3;
    ivec3 f = ivec3(gl_GlobalInvocationID);
    if (f.x >= size.x || f.y >= size.y || f.z >= depth) return;
    /* The column's ray through the froxel's centre on the frustum (the pixel rays' ray matrix). */
    vec2 cell = (vec2(f.xy) + 0.5) / vec2(size.xy);
    vec2 ndc = vec2(2.0 * cell.x - 1.0, 1.0 - 2.0 * cell.y);
    vec3 v = normalize(push.forward.xyz + ndc.x * push.right.xyz + ndc.y * push.up.xyz);
    float d = ap_slice_distance(float(f.z) + 1.0, float(depth));
    /* A froxel below the ground holds the point just above the ground straight above it (Hillaire's volume does
     * the same): the field stays smooth across the columns that meet the ground, so a ground point between two
     * of them interpolates between values to points near it, not between a column clamped at its own ground hit
     * and one that is not. Altitudes without planet-scale differences: r^2 - Rb^2 expanded. */
    float h = push.forward.w, Rb = ground_radius(), rc = Rb + h;
    float r2_minus = h * (2.0 * Rb + h) + 2.0 * rc * d * v.y + d * d;   /* |P|^2 - Rb^2, P = camera + v d */
    float rp = sqrt(Rb * Rb + r2_minus);
    const float lift = 0.001;   /* 1 m above the ground */
    float alt = r2_minus / (rp + Rb);
    if (alt < lift) {
        /* P' = P (Rb + lift) / |P|, so P' - camera = v d + P k with k = (lift - alt) / |P| (small: no cancellation). */
        float k = (lift - alt) / rp;
        vec3 offset = v * d + (vec3(0.0, rc, 0.0) + v * d) * k;
        d = length(offset);
        v = offset / d;
    }
    Aerial a = aerial_march(h, v, push.sun_dir.xyz, d, push.march, push.sun_dir.w);
    /* fp16 storage: clamp to its finite range like every other layer. */
    imageStore(ap_volume_out, ivec3(f.xy, f.z + AP_BAND_TRANSMITTANCE * depth), vec4(a.transmittance, 1.0));
    imageStore(ap_volume_out, ivec3(f.xy, f.z + AP_BAND_RAYLEIGH * depth), vec4(min(a.rayleigh, vec3(FP16_MAX)), 1.0));
    imageStore(ap_volume_out, ivec3(f.xy, f.z + AP_BAND_MIE * depth), vec4(min(a.mie, vec3(FP16_MAX)), 1.0));
}
