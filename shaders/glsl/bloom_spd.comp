#version 450
#pragma use_vulkan_memory_model
#extension GL_KHR_memory_scope_semantics : require
/* Bloom downsample, compute chain: every level of the mip chain in ONE dispatch, in the style of AMD FidelityFX
 * SPD (single-pass downsampler): workgroup shared memory, and a global atomic counter per tile so that the
 * workgroup that finishes the last input of a tile goes on to compute it ("the last one continues").
 *
 * Work: a task is one 16x16 tile of one level. The dispatch has one workgroup per tile of level 0 (read from the
 * HDR image through the sampler, exactly as the fragment chain does). Level k >= 1 tile T reads a region of level
 * k-1 (the 13-tap filter reaches 2.5 texels beyond the tile, so the region spans up to 3x3 tiles of level k-1):
 * its counter counts those input tiles. A workgroup that has written a tile increments the counters of the
 * tiles that read it; the one whose increment completes a counter pushes that tile onto its own task stack.
 * No workgroup ever waits for another (Vulkan promises no forward progress between workgroups, so a spin-wait
 * could hang): work only moves on to whoever arrives last.
 *
 * In-dispatch synchronization, in the Vulkan memory model (docs/synchronization.md, "Inside the single-pass
 * downsampler"): message passing between workgroups through the counters.
 *  - release: every thread's imageStore of the tile, then a control barrier at workgroup execution scope and
 *    device memory scope with MakeAvailable on image (and shared) storage: all 256 threads' stores happen-before
 *    what any of them does next, and are made available to other workgroups;
 *  - the counters: imageAtomicAdd with acquire-release semantics at device scope: one total order per counter,
 *    so exactly one workgroup sees the value count - 1, and its increment synchronizes with every earlier one;
 *  - acquire: a control barrier with MakeVisible hands that to all threads before they imageLoad the inputs.
 *  The images are nonprivate (they take part in availability and visibility operations); no access is
 *  coherent: the barriers' semantics do what `coherent` + memoryBarrierImage() did in the legacy idiom.
  * Synchronization validation checks barriers between commands; it cannot see any of this (it treats a dispatch
 * as one access). The tests (post_compare) compare the result with the fragment chain's instead. */
#extension GL_GOOGLE_include_directive : require
#include "shared.h"
#include "bloom_filter.glsl"

#define TILE 16
#define REGION 44            /* the largest level k-1 region a tile reads: 16 x 2.0625 + 5 + 2 margin < 44 */
#define STACK 256

layout(local_size_x = TILE, local_size_y = TILE) in;
layout(set = 0, binding = VKSKY_BINDING_POST_SOURCE) uniform sampler2D hdr;
layout(set = 0, binding = VKSKY_BINDING_POST_MIP + 0, rgba16f) uniform nonprivate image2D mip0;
layout(set = 0, binding = VKSKY_BINDING_POST_MIP + 1, rgba16f) uniform nonprivate image2D mip1;
layout(set = 0, binding = VKSKY_BINDING_POST_MIP + 2, rgba16f) uniform nonprivate image2D mip2;
layout(set = 0, binding = VKSKY_BINDING_POST_MIP + 3, rgba16f) uniform nonprivate image2D mip3;
layout(set = 0, binding = VKSKY_BINDING_POST_MIP + 4, rgba16f) uniform nonprivate image2D mip4;
layout(set = 0, binding = VKSKY_BINDING_POST_MIP + 5, rgba16f) uniform nonprivate image2D mip5;
layout(set = 0, binding = VKSKY_BINDING_POST_MIP + 6, rgba16f) uniform nonprivate image2D mip6;
layout(set = 0, binding = VKSKY_BINDING_POST_MIP + 7, rgba16f) uniform nonprivate image2D mip7;
layout(set = 0, binding = VKSKY_BINDING_SPD_COUNTERS, r32ui) uniform nonprivate uimage2D counters;
layout(push_constant) uniform Push { PostPush push; };   /* params: x mip count, y threshold */

/* Workgroup shared memory, touched only through relaxed atomics at workgroup scope (ordered by the control
 * barriers below). A plain access would do under the memory model too, but glslang 12 makes every plain shared
 * access workgroup-coherent, with a make-visible/available operation at workgroup scope on each one, which Mesa
 * 22.3's lavapipe turns into a workgroup execution barrier: inside divergent control flow that breaks the
 * workgroup (docs/synchronization.md §7, "Status"). */
shared uint region[REGION * REGION * 3];
shared uint stack[STACK];
shared uint stack_size;

/* Shared-memory ordering between this workgroup's threads: every thread's accesses before, everyone's after. */
#define WORKGROUP_BARRIER() controlBarrier(gl_ScopeWorkgroup, gl_ScopeWorkgroup, gl_StorageSemanticsShared, \
                                           gl_SemanticsAcquireRelease)
uint shared_get(uint i) { return atomicLoad(region[i], gl_ScopeWorkgroup, 0, gl_SemanticsRelaxed); }
void region_put(int i, vec3 c)
{
    for (int j = 0; j < 3; ++j)
        atomicStore(region[3 * i + j], floatBitsToUint(c[j]), gl_ScopeWorkgroup, 0, gl_SemanticsRelaxed);
}
vec3 region_get(int i)
{
    return uintBitsToFloat(uvec3(shared_get(3 * i), shared_get(3 * i + 1), shared_get(3 * i + 2)));
}

/* Constant indices only: no descriptor-array dynamic indexing feature needed. */
ivec2 mip_size(int k)
{
    switch (k) {
    case 0: return imageSize(mip0); case 1: return imageSize(mip1); case 2: return imageSize(mip2);
    case 3: return imageSize(mip3); case 4: return imageSize(mip4); case 5: return imageSize(mip5);
    case 6: return imageSize(mip6); default: return imageSize(mip7);
    }
}
vec3 mip_load(int k, ivec2 p)
{
    switch (k) {
    case 0: return imageLoad(mip0, p).rgb; case 1: return imageLoad(mip1, p).rgb; case 2: return imageLoad(mip2, p).rgb;
    case 3: return imageLoad(mip3, p).rgb; case 4: return imageLoad(mip4, p).rgb; case 5: return imageLoad(mip5, p).rgb;
    case 6: return imageLoad(mip6, p).rgb; default: return imageLoad(mip7, p).rgb;
    }
}
void mip_store(int k, ivec2 p, vec3 c)
{
    vec4 v = vec4(c, 1.0);
    switch (k) {
    case 0: imageStore(mip0, p, v); break; case 1: imageStore(mip1, p, v); break;
    case 2: imageStore(mip2, p, v); break; case 3: imageStore(mip3, p, v); break;
    case 4: imageStore(mip4, p, v); break; case 5: imageStore(mip5, p, v); break;
    case 6: imageStore(mip6, p, v); break; default: imageStore(mip7, p, v); break;
    }
}

ivec2 tiles_of(int k) { return (mip_size(k) + TILE - 1) / TILE; }

/* The texels of level k-1 that tile t of level k reads: [lo, hi], clamped to the image. The same formula as
 * the sampling below (bilinear taps at (x + 0.5) * Ws / Wd + offset, offsets up to 2), one texel of margin. */
void source_range(int k, ivec2 t, out ivec2 lo, out ivec2 hi)
{
    ivec2 wd = mip_size(k), ws = mip_size(k - 1);
    vec2 r = vec2(ws) / vec2(wd);
    ivec2 x0 = t * TILE, x1 = min(t * TILE + TILE - 1, wd - 1);
    lo = ivec2(floor((vec2(x0) + 0.5) * r - 2.5)) - 1;
    hi = ivec2(floor((vec2(x1) + 0.5) * r + 1.5)) + 2;
    lo = clamp(lo, ivec2(0), ws - 1);
    hi = clamp(hi, ivec2(0), ws - 1);
}

/* Counter index of tile t of level k >= 1: levels 1.. laid end to end, 1024 counters a row. */
ivec2 counter_coord(int k, ivec2 t)
{
    int base = 0;
    for (int j = 1; j < k; ++j) { ivec2 n = tiles_of(j); base += n.x * n.y; }
    int idx = base + t.y * tiles_of(k).x + t.x;
    return ivec2(idx % 1024, idx / 1024);
}

uint pack_task(int k, ivec2 t) { return uint(k) << 20 | uint(t.y) << 10 | uint(t.x); }

void level0(ivec2 t)
{
    ivec2 p = t * TILE + ivec2(gl_LocalInvocationID.xy);
    ivec2 size = mip_size(0);
    if (any(greaterThanEqual(p, size))) return;
    vec2 uv = (vec2(p) + 0.5) / vec2(size), tex = 1.0 / vec2(textureSize(hdr, 0));
    vec3 s[13];
    for (int i = 0; i < 13; ++i) s[i] = textureLod(hdr, uv + tex * BLOOM_TAPS[i], 0.0).rgb;
    mip_store(0, p, bloom_filter13(s, true, push.params.y));
}

/* Bilinear fetch from the region as the sampler does it (clamp to edge, texel centres at i + 0.5). */
vec3 region_bilinear(vec2 pos, ivec2 lo, ivec2 hi, ivec2 rsize)
{
    vec2 q = pos - 0.5, f = q - floor(q);
    ivec2 i0 = ivec2(floor(q));
    ivec2 a = clamp(i0, lo, hi) - lo, b = clamp(i0 + 1, lo, hi) - lo;
    vec3 c00 = region_get(a.y * rsize.x + a.x), c10 = region_get(a.y * rsize.x + b.x);
    vec3 c01 = region_get(b.y * rsize.x + a.x), c11 = region_get(b.y * rsize.x + b.x);
    return mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
}

void level_k(int k, ivec2 t)
{
    ivec2 lo, hi;
    source_range(k, t, lo, hi);
    ivec2 rsize = hi - lo + 1;
    uint lid = gl_LocalInvocationIndex;
    for (int i = int(lid); i < rsize.x * rsize.y; i += TILE * TILE)
        region_put(i, mip_load(k - 1, lo + ivec2(i % rsize.x, i / rsize.x)));
    WORKGROUP_BARRIER();   /* shared memory: the region is complete */
    ivec2 p = t * TILE + ivec2(gl_LocalInvocationID.xy);
    ivec2 wd = mip_size(k), ws = mip_size(k - 1);
    if (all(lessThan(p, wd))) {
        vec2 centre = (vec2(p) + 0.5) * vec2(ws) / vec2(wd);
        vec3 s[13];
        for (int i = 0; i < 13; ++i) s[i] = region_bilinear(centre + BLOOM_TAPS[i], lo, hi, rsize);
        mip_store(k, p, bloom_filter13(s, false, 0.0));
    }
    WORKGROUP_BARRIER();   /* shared memory: everyone is done reading the region before the next task overwrites it */
}

/* Tile t of level k is written: count it in every level k+1 tile that reads it; push those it completes. */
void finish(int k, ivec2 t)
{
    int levels = int(push.params.x);
    if (k + 1 >= levels) return;
    /* Release: all 256 threads' image stores of the tile happen-before what any of them does next, made
     * available at device scope (other workgroups may run on other units with their own caches). */
    controlBarrier(gl_ScopeWorkgroup, gl_ScopeDevice, gl_StorageSemanticsImage | gl_StorageSemanticsShared,
                   gl_SemanticsAcquireRelease | gl_SemanticsMakeAvailable);
    /* Candidates: a level k+1 tile reads level k tiles [2s - 2, 2s + 2] at most; 7 x 7 around t / 2 is ample. */
    uint lid = gl_LocalInvocationIndex;
    if (lid < 49) {
        ivec2 s = t / 2 + ivec2(int(lid % 7) - 3, int(lid / 7) - 3);
        ivec2 n = tiles_of(k + 1);
        if (all(greaterThanEqual(s, ivec2(0))) && all(lessThan(s, n))) {
            ivec2 lo, hi;
            source_range(k + 1, s, lo, hi);
            ivec2 tlo = lo / TILE, thi = hi / TILE;
            if (all(greaterThanEqual(t, tlo)) && all(lessThanEqual(t, thi))) {
                uint inputs = uint((thi.x - tlo.x + 1) * (thi.y - tlo.y + 1));
                /* The hand-off: release publishes this tile; the increment that completes the counter
                 * acquires every earlier one (read-modify-writes continue a release sequence). */
                uint before = imageAtomicAdd(counters, counter_coord(k + 1, s), 1u, gl_ScopeDevice,
                                             gl_StorageSemanticsImage, gl_SemanticsAcquireRelease |
                                             gl_SemanticsMakeAvailable | gl_SemanticsMakeVisible);
                if (before == inputs - 1u) {
                    uint slot = atomicAdd(stack_size, 1u, gl_ScopeWorkgroup, 0, gl_SemanticsRelaxed);
                    atomicStore(stack[slot], pack_task(k + 1, s), gl_ScopeWorkgroup, 0, gl_SemanticsRelaxed);
                }
            }
        }
    }
    /* Acquire: hand the completed tiles to all threads, their inputs made visible to the imageLoads that follow. */
    controlBarrier(gl_ScopeWorkgroup, gl_ScopeDevice, gl_StorageSemanticsImage | gl_StorageSemanticsShared,
                   gl_SemanticsAcquireRelease | gl_SemanticsMakeVisible);
}

void main()
{
    if (gl_LocalInvocationIndex == 0) atomicStore(stack_size, 0u, gl_ScopeWorkgroup, 0, gl_SemanticsRelaxed);
    WORKGROUP_BARRIER();
    ivec2 t = ivec2(gl_WorkGroupID.xy);
    level0(t);
    finish(0, t);
    while (true) {
        /* uniform: read after a barrier, written only between barriers */
        uint n = atomicLoad(stack_size, gl_ScopeWorkgroup, 0, gl_SemanticsRelaxed);
        if (n == 0u) break;
        uint task = atomicLoad(stack[n - 1u], gl_ScopeWorkgroup, 0, gl_SemanticsRelaxed);
        WORKGROUP_BARRIER();
        if (gl_LocalInvocationIndex == 0) atomicStore(stack_size, n - 1u, gl_ScopeWorkgroup, 0, gl_SemanticsRelaxed);
        WORKGROUP_BARRIER();
        int k = int(task >> 20);
        ivec2 tile = ivec2(int(task & 1023u), int((task >> 10) & 1023u));
        level_k(k, tile);
        finish(k, tile);
    }
}
