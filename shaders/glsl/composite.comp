#version 450
/* The composite pass: the atmosphere applied to a rendered image (seed 004's workflow), coverage-correct (issue 28).
 * Per pixel, the covered part (alpha, with a finite world position): beauty T + alpha S along the ray from the
 * camera to that position (aerial.glsl); the uncovered part (1 - alpha): vksky's sky along the pixel's ray when the
 * camera orientation is known, else nothing (the beauty's alpha kept). Writes the composite and the AOV layers
 * (shared.h, VKSKY_AOV_*). */
#extension GL_GOOGLE_include_directive : require
#include "atmosphere.glsl"

layout(set = 0, binding = VKSKY_BINDING_TRANSMITTANCE_LUT) uniform sampler2D transmittance_lut;
layout(set = 0, binding = VKSKY_BINDING_MULTISCATTER_LUT) uniform sampler2D multiscatter_lut;
layout(set = 0, binding = VKSKY_BINDING_GROUND_IRRADIANCE_LUT) uniform sampler2D ground_irradiance_lut;
/* The inputs, one image of 2 bands: rows [0, H) the beauty RGBA, rows [H, 2H) the world position XYZ (H: the rows of
 * the frame's band being composited). */
layout(set = 0, binding = VKSKY_BINDING_COMPOSITE_IN) uniform sampler2D composite_in;
layout(set = 0, binding = VKSKY_BINDING_OUTPUT, rgba32f) uniform writeonly image2D composite_out;
layout(push_constant) uniform Push { CompositePush push; };
#ifdef AERIAL_VOLUME
/* --aerial-perspective volume: the froxel volume (ap_volume.comp), trilinear, clamped. */
layout(set = 0, binding = VKSKY_BINDING_AP_VOLUME) uniform sampler3D ap_volume;
#endif

#include "sky_common.glsl"
#include "aerial.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

bool finite3(vec3 x) { return !any(isnan(x)) && !any(isinf(x)); }

/* Every layer within the finite fp16 range; the composite keeps a negative beauty's sign (filters ring), the
 * atmosphere's layers are never negative. */
void store(ivec2 p, int height, int layer, vec4 value)
{
    vec4 lo = vec4(layer == VKSKY_AOV_COMPOSITE ? -FP16_MAX : 0.0);
    imageStore(composite_out, ivec2(p.x, p.y + layer * height), clamp(value, lo, vec4(FP16_MAX)));
}

void main()
{
    ivec2 size = textureSize(composite_in, 0);
    int height = size.y / 2;
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= size.x || p.y >= height) return;
    vec4 beauty = texelFetch(composite_in, p, 0);
    /* A non-finite beauty value (a renderer's firefly gone to Inf) would make the whole pixel NaN: read as 0. */
    for (int c = 0; c < 4; ++c)
        if (isnan(beauty[c]) || isinf(beauty[c])) beauty[c] = 0.0;
    vec3 position = texelFetch(composite_in, ivec2(p.x, p.y + height), 0).xyz;
    float h = push.forward.w;
    vec3 s = push.sun_dir.xyz;
    /* Alpha is coverage and the beauty premultiplied (what renderers write): the covered part gets the
     * atmosphere to its surface, beauty T + alpha S; the uncovered part (1 - alpha) the sky behind it, also in the
     * sky and sun_disk layers, so that on every pixel
     *     composite.rgb = beauty.rgb * transmittance + alpha (rayleigh + mie) + sky + sun_disk
     * (docs/aerial_perspective.md "The coverage identity"). Without a known orientation there is no sky: the
     * uncovered part stays the beauty's (alpha kept). */
    float alpha = clamp(beauty.a, 0.0, 1.0);
    bool oriented = dot(push.forward.xyz, push.forward.xyz) > 0.0;
    vec3 sky = vec3(0.0), sun = vec3(0.0), transmittance = vec3(1.0), rayleigh = vec3(0.0), mie = vec3(0.0);
    bool covered = finite3(position) && alpha > 0.0;
    if (covered) {
        /* The offset in world units (small numbers: no planet-scale subtraction), then to march-frame km. */
        vec3 dw = position - vec3(push.world_to_march[0].w, push.world_to_march[1].w, push.world_to_march[2].w);
        vec3 d = vec3(dot(push.world_to_march[0].xyz, dw), dot(push.world_to_march[1].xyz, dw),
                      dot(push.world_to_march[2].xyz, dw));
        float dist = length(d);
        vec3 v = dist > 0.0 ? d / dist : vec3(0.0, 1.0, 0.0);
#ifdef AERIAL_VOLUME
        Aerial a;
        if (!aerial_volume_lookup(v, dist, push, a)) a = aerial_march(h, v, s, dist, push.march, push.sun_dir.w);
#else
        Aerial a = aerial_march(h, v, s, dist, push.march, push.sun_dir.w);
#endif
        transmittance = a.transmittance;
        rayleigh = a.rayleigh;
        mie = a.mie;
    }
    if (oriented && alpha < 1.0) {
        /* The sky along this pixel's ray (the sky pass's ray matrix), the sun disc apart. */
        /* The image is one band of the frame: its first row is push.right.w, the frame's height 1 / push.up.w. */
        vec2 ndc = vec2(2.0 * (float(p.x) + 0.5) / float(size.x) - 1.0,
                        1.0 - 2.0 * (float(p.y) + push.right.w + 0.5) * push.up.w);
        vec3 v = normalize(push.forward.xyz + ndc.x * push.right.xyz + ndc.y * push.up.xyz);
        MarchSegment seg = march_segment(h, v, s, push.march, push.sun_dir.w, 3.0e38);
        if (alpha == 0.0) {   /* nothing covered: the layers are the sky's */
            transmittance = seg.throughput;
            rayleigh = seg.rayleigh;
            mie = seg.mie;
        }
        sky = (1.0 - alpha) * (seg.rayleigh + seg.mie + lit_ground(seg));
        sun = (1.0 - alpha) * sun_disc(v, s, seg.throughput, seg.hits_ground);
    }
    vec3 rgb = beauty.rgb * transmittance + alpha * (rayleigh + mie) + sky + sun;
    vec4 composite = vec4(rgb, oriented ? 1.0 : beauty.a);
    store(p, height, VKSKY_AOV_COMPOSITE, composite);
    store(p, height, VKSKY_AOV_SKY, vec4(sky, 1.0));
    store(p, height, VKSKY_AOV_SUN_DISK, vec4(sun, 1.0));
    store(p, height, VKSKY_AOV_TRANSMITTANCE, vec4(transmittance, 1.0));
    store(p, height, VKSKY_AOV_RAYLEIGH, vec4(rayleigh, 1.0));
    store(p, height, VKSKY_AOV_MIE, vec4(mie, 1.0));
}
