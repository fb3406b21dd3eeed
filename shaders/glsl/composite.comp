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

/* The fast defaults (docs/aerial_perspective.md "Cost"; push.march.w < 0, composite_push_fast() in composite.c: no
 * --max-steps given). Off (march.w >= 0), every pixel marches the given count along its own ray, as before.
 *  - A segment camera -> surface marches Hillaire's count growing with its length: POINT_MIN_STEPS at 0 km to the
 *    given count at -march.w km (a short segment changes little along it: measured against a dense march, the same
 *    answer to fp16).
 *  - The sky along the pixels' rays is marched at the corners and the centre of each 8x8 tile and interpolated
 *    bilinearly where the centre's march agrees with the corners' mean within SKY_TILE_TOLERANCE (relative, every
 *    channel of rayleigh, mie, the lit ground and the transmittance), all five rays and the pixel's own are of one
 *    class (ground or sky), and the tile spans at most SKY_TILE_MAX_RAD; elsewhere every pixel marches its own. */
const float POINT_MIN_STEPS = 4.0;
const int TILE = VKSKY_COMPOSITE_TILE;
const float SKY_TILE_TOLERANCE = 5e-4;
const float SKY_TILE_MAX_RAD = 0.0087;   /* 0.5 degree */

bool finite3(vec3 x) { return !any(isnan(x)) && !any(isinf(x)); }

/* Every layer within the finite fp16 range; the composite keeps a negative beauty's sign (filters ring), the
 * atmosphere's layers are never negative. */
void store(ivec2 p, int height, int layer, vec4 value)
{
    vec4 lo = vec4(layer == VKSKY_AOV_COMPOSITE ? -FP16_MAX : 0.0);
    imageStore(composite_out, ivec2(p.x, p.y + layer * height), clamp(value, lo, vec4(FP16_MAX)));
}

/* This band's pixel (x, y) (any integer, also beyond the image: a direction) as a unit march-frame ray (the sky
 * pass's ray matrix). The image is one band of the frame: its first row is push.right.w, the frame's height
 * 1 / push.up.w. */
vec3 pixel_ray(ivec2 p, int width)
{
    vec2 ndc = vec2(2.0 * (float(p.x) + 0.5) / float(width) - 1.0,
                    1.0 - 2.0 * (float(p.y) + push.right.w + 0.5) * push.up.w);
    return normalize(push.forward.xyz + ndc.x * push.right.xyz + ndc.y * push.up.xyz);
}

/* The sky along one ray, what a pixel takes from it (its sun disc apart). */
struct SkyRay {
    vec3 rayleigh, mie, ground, throughput;
    bool hits_ground;
};

SkyRay sky_ray(vec3 v)
{
    MarchSegment seg = march_segment(push.forward.w, v, push.sun_dir.xyz, push.march, push.sun_dir.w, 3.0e38);
    return SkyRay(seg.rayleigh, seg.mie, lit_ground(seg), seg.throughput, seg.hits_ground);
}

/* The tile's five rays: corners (0, 0), (8, 0), (0, 8), (8, 8) and the centre (4, 4), pixel offsets. */
shared vec3 tile_rayleigh[5], tile_mie[5], tile_ground[5], tile_throughput[5];
shared bool tile_hits_ground[5];
shared bool tile_needs_sky;

bool close_to(vec3 exact, vec3 approx)
{
    return all(lessThanEqual(abs(approx - exact), SKY_TILE_TOLERANCE * abs(exact) + 1e-7));
}

void main()
{
    ivec2 size = textureSize(composite_in, 0);
    int height = size.y / 2;
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    /* No early return: the tile's invocations meet at barriers below. */
    bool inside = p.x < size.x && p.y < height;
    ivec2 q = min(p, ivec2(size.x - 1, height - 1));
    vec4 beauty = texelFetch(composite_in, q, 0);
    /* A non-finite beauty value (a renderer's firefly gone to Inf) would make the whole pixel NaN: read as 0. */
    for (int c = 0; c < 4; ++c)
        if (isnan(beauty[c]) || isinf(beauty[c])) beauty[c] = 0.0;
    vec3 position = texelFetch(composite_in, ivec2(q.x, q.y + height), 0).xyz;
    float h = push.forward.w;
    vec3 s = push.sun_dir.xyz;
    bool fast = push.march.w < 0.0;
    /* Alpha is coverage and the beauty premultiplied (what renderers write): the covered part gets the
     * atmosphere to its surface, beauty T + alpha S; the uncovered part (1 - alpha) the sky behind it, also in the
     * sky and sun_disk layers, so that on every pixel
     *     composite.rgb = beauty.rgb * transmittance + alpha (rayleigh + mie) + sky + sun_disk
     * (docs/aerial_perspective.md "The coverage identity"). Without a known orientation there is no sky: the
     * uncovered part stays the beauty's (alpha kept). */
    float alpha = clamp(beauty.a, 0.0, 1.0);
    bool oriented = dot(push.forward.xyz, push.forward.xyz) > 0.0;
    /* The sun disc drawn as the sky pass draws it (sky_common.glsl: at least a texel wide, its power kept), so that the
     * sun_disk layer of an uncovered pixel is the plain render's disc: a pixel's angular size at the view axis, as
     * texel_angle gives it for a perspective image (right.w is the band's first row here, the width the band's). */
    if (oriented)
        sky_texel_angle = 2.0 * max(length(push.right.xyz) / float(size.x), length(push.up.xyz) * push.up.w);
    vec3 sky = vec3(0.0), sun = vec3(0.0), transmittance = vec3(1.0), rayleigh = vec3(0.0), mie = vec3(0.0);
    bool covered = inside && finite3(position) && alpha > 0.0;
    if (covered) {
        /* The offset in world units (small numbers: no planet-scale subtraction), then to march-frame km. */
        vec3 dw = position - vec3(push.world_to_march[0].w, push.world_to_march[1].w, push.world_to_march[2].w);
        vec3 d = vec3(dot(push.world_to_march[0].xyz, dw), dot(push.world_to_march[1].xyz, dw),
                      dot(push.world_to_march[2].xyz, dw));
        float dist = length(d);
        vec3 v = dist > 0.0 ? d / dist : vec3(0.0, 1.0, 0.0);
        vec4 march = fast ? vec4(min(push.march.x, POINT_MIN_STEPS), push.march.x, push.march.z, -push.march.w)
                          : push.march;
#ifdef AERIAL_VOLUME
        Aerial a;
        if (!aerial_volume_lookup(v, dist, push, a)) a = aerial_march(h, v, s, dist, march, push.sun_dir.w);
#else
        Aerial a = aerial_march(h, v, s, dist, march, push.sun_dir.w);
#endif
        transmittance = a.transmittance;
        rayleigh = a.rayleigh;
        mie = a.mie;
    }
    bool needs_sky = inside && oriented && alpha < 1.0;
    /* The tile's rays, when the tile is small enough on the sky and some pixel of it shows sky (uniform over the
     * workgroup: every invocation reaches the barrier). */
    bool tiles = fast && oriented && float(TILE) * 2.0 * length(push.up.xyz) * push.up.w <= SKY_TILE_MAX_RAD;
    bool smooth_tile = false;
    ivec2 corner = ivec2(gl_WorkGroupID.xy) * TILE;
    if (tiles) {
        /* Invocations 0..4 (one SIMD row on a CPU device) march the five rays, if some pixel of the tile shows sky
         * (its alpha below 1, as the host marked it); the others wait at the one barrier. */
        uint k = gl_LocalInvocationIndex;
        if (k < 5) {
            /* The host's mark (shared.h, band_reader_upload): one fetch instead of the tile's 64 alphas, which
             * cost a CPU device a fifth of the pass (issue 28 item 6). */
            bool any_sky = texelFetch(composite_in, ivec2(corner.x, corner.y + height), 0).w !=
                           float(VKSKY_COMPOSITE_TILE_NO_SKY);
            if (k == 0) tile_needs_sky = any_sky;
            if (any_sky) {
                ivec2 o = k == 4 ? ivec2(TILE / 2) : ivec2(int(k & 1u), int(k >> 1)) * TILE;
                SkyRay r = sky_ray(pixel_ray(corner + o, size.x));
                tile_rayleigh[k] = r.rayleigh, tile_mie[k] = r.mie, tile_ground[k] = r.ground;
                tile_throughput[k] = r.throughput, tile_hits_ground[k] = r.hits_ground;
            }
        }
        barrier();
        if (tile_needs_sky) {
            bool one_class = tile_hits_ground[0] == tile_hits_ground[1] && tile_hits_ground[0] == tile_hits_ground[2] &&
                             tile_hits_ground[0] == tile_hits_ground[3] && tile_hits_ground[0] == tile_hits_ground[4];
            smooth_tile = one_class &&
                close_to(tile_rayleigh[4], 0.25 * (tile_rayleigh[0] + tile_rayleigh[1] + tile_rayleigh[2] + tile_rayleigh[3])) &&
                close_to(tile_mie[4], 0.25 * (tile_mie[0] + tile_mie[1] + tile_mie[2] + tile_mie[3])) &&
                close_to(tile_ground[4], 0.25 * (tile_ground[0] + tile_ground[1] + tile_ground[2] + tile_ground[3])) &&
                close_to(tile_throughput[4], 0.25 * (tile_throughput[0] + tile_throughput[1] + tile_throughput[2] +
                                                     tile_throughput[3]));
        }
    }
    if (needs_sky) {
        /* The sky along this pixel's ray, the sun disc apart. */
        vec3 v = pixel_ray(p, size.x);
        SkyRay r;
        vec2 f = vec2(p - corner) / float(TILE);
        if (smooth_tile && ray_hits_ground(h, v.y) == tile_hits_ground[0]) {
            vec4 w = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
            r.rayleigh = w.x * tile_rayleigh[0] + w.y * tile_rayleigh[1] + w.z * tile_rayleigh[2] + w.w * tile_rayleigh[3];
            r.mie = w.x * tile_mie[0] + w.y * tile_mie[1] + w.z * tile_mie[2] + w.w * tile_mie[3];
            r.ground = w.x * tile_ground[0] + w.y * tile_ground[1] + w.z * tile_ground[2] + w.w * tile_ground[3];
            r.throughput = w.x * tile_throughput[0] + w.y * tile_throughput[1] + w.z * tile_throughput[2] +
                           w.w * tile_throughput[3];
            r.hits_ground = tile_hits_ground[0];
        } else {
            r = sky_ray(v);
        }
        if (alpha == 0.0) {   /* nothing covered: the layers are the sky's */
            transmittance = r.throughput;
            rayleigh = r.rayleigh;
            mie = r.mie;
        }
        sky = (1.0 - alpha) * (r.rayleigh + r.mie + r.ground);
        sun = (1.0 - alpha) * sun_disc(v, s, r.throughput, r.hits_ground);
    }
    if (!inside) return;
    vec3 rgb = beauty.rgb * transmittance + alpha * (rayleigh + mie) + sky + sun;
    vec4 composite = vec4(rgb, oriented ? 1.0 : beauty.a);
    store(p, height, VKSKY_AOV_COMPOSITE, composite);
    store(p, height, VKSKY_AOV_SKY, vec4(sky, 1.0));
    store(p, height, VKSKY_AOV_SUN_DISK, vec4(sun, 1.0));
    store(p, height, VKSKY_AOV_TRANSMITTANCE, vec4(transmittance, 1.0));
    store(p, height, VKSKY_AOV_RAYLEIGH, vec4(rayleigh, 1.0));
    store(p, height, VKSKY_AOV_MIE, vec4(mie, 1.0));
}
