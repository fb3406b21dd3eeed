#version 450
/* The SCENE_LINEAR pass (src/sky/host_frame.c): the sky and the aerial perspective in the host's own frame.
 * One thread per pixel of the host's HDR colour image, which already holds its geometry. Where the host's depth is
 * the far plane: the sky along the pixel's ray, as the sky pass computes it (sky_pixel, horizon.glsl). Elsewhere:
 * the point is reconstructed from the depth, and the pixel becomes colour x T + S over the camera -> point segment
 * (aerial_march, aerial.glsl, as the composite pass applies it), alpha kept. Units: the renderer's (the atmosphere's
 * sun: vksky_luts.sun_illuminance). */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"
#include "host_frame_push.h"

layout(set = 0, binding = VKSKY_BINDING_TRANSMITTANCE_LUT) uniform sampler2D transmittance_lut;
layout(set = 0, binding = VKSKY_BINDING_MULTISCATTER_LUT) uniform sampler2D multiscatter_lut;
layout(set = 0, binding = VKSKY_BINDING_GROUND_IRRADIANCE_LUT) uniform sampler2D ground_irradiance_lut;
/* The host's depth (texelFetch only; its stand-in is the transmittance LUT when the host gives none). */
layout(set = 0, binding = VKSKY_BINDING_HOST_DEPTH) uniform sampler2D host_depth;
#ifndef HOST_FORMAT
#define HOST_FORMAT rgba16f
#endif
layout(set = 0, binding = VKSKY_BINDING_OUTPUT, HOST_FORMAT) uniform image2D host_color;
layout(push_constant) uniform Push { HostFramePush push; };

/* The per-pixel march, as the sky pass's march variant (sky_bindings.glsl's SKY_RADIANCE). */
#define SKY_RADIANCE(h, v, s, march) sky_radiance(h, v, s, march, push.sky.sun_dir.w)
#include "sky_common.glsl"
#include "aerial.glsl"
#include "projection.glsl"
#include "horizon.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(host_color);
    if (any(greaterThanEqual(p, size))) return;
    float mode = push.depth.w;
    float d = mode < 1.5 ? texelFetch(host_depth, p, 0).r : push.depth.z;
    bool sky = mode > 0.5 ? d <= push.depth.z : d >= push.depth.z;
    if (sky) {
        /* The pixel's own sky; alpha 0: no geometry covers it (sky_pixel's alpha, the horizon's distance for the
         * CLI's tone map, is not the host's). */
        imageStore(host_color, p, vec4(sky_pixel(vec2(p) + 0.5, push.sky).rgb, 0.0));
        return;
    }
    vec4 color = imageLoad(host_color, p);
    SkyPush s = push.sky;
    /* The pixel's ray as pixel_view_dir builds it, unnormalised, scaled by the perspective's 1/w: the point. */
    vec2 ndc = vec2(2.0 * (float(p.x) + 0.5) * s.right.w - 1.0, 1.0 - 2.0 * (float(p.y) + 0.5) * s.up.w);
    vec3 offset = (s.forward.xyz + ndc.x * s.right.xyz + ndc.y * s.up.xyz) / (push.depth.x * d + push.depth.y);
    float dist = length(offset);
    if (!(dist > 0.0) || isinf(dist)) return;   /* on the camera, or a depth the projection cannot map: untouched */
    Aerial a = aerial_march(s.forward.w, offset / dist, s.sun_dir.xyz, dist, s.march, s.sun_dir.w);
    vec3 rgb = color.rgb * a.transmittance + a.rayleigh + a.mie;
    imageStore(host_color, p, vec4(clamp(rgb, vec3(-FP16_MAX), vec3(FP16_MAX)), color.a));
}
