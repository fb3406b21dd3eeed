/* Aerial perspective to a point: what the atmosphere does to the light from a surface at distance d along a view
 * ray, L = L_surface T + S (Bruneton's GetSkyRadianceToPoint, computed by the march itself rather than by
 * differences of 4D scattering tables). Expects sky_common.glsl.
 *
 * S comes split as the march splits it (MarchSegment in sky_common.glsl): rayleigh + mie = S exactly.
 *
 * aerial_march is the accurate path (--aerial-perspective march): one march per pixel over [0, d]. Hillaire's
 * froxel volume is the fast path (--aerial-perspective volume): ap_volume.comp (AP_VOLUME_BUILD) calls the same
 * aerial_march once per froxel, the composite pass (AERIAL_VOLUME) then interpolates it per pixel
 * (aerial_volume_lookup). */

struct Aerial {
    vec3 transmittance;     /* camera -> point, per channel */
    vec3 rayleigh, mie;     /* in-scattered radiance camera -> point, by phase function (sum: S) */
};

/* From altitude h_cam along the unit ray v (march frame: up = +Y) to the point d km away; sun toward s. */
Aerial aerial_march(float h_cam, vec3 v, vec3 s, float d, vec4 march, float distribution)
{
    MarchSegment seg = march_segment(h_cam, v, s, march, distribution, d);
    Aerial a;
    a.transmittance = seg.throughput;
    a.rayleigh = seg.rayleigh;
    a.mie = seg.mie;
    return a;
}

#if defined(AERIAL_VOLUME) || defined(AP_VOLUME_BUILD)
/* The volume (src/sky/ap_volume.h): froxel columns over the camera's frustum (the composite's image), `depth`
 * slices along each column's ray; slice k holds camera -> the point ap_slice_distance(k + 1) km along the ray, so
 * distance 0 (T = 1, S = 0) needs no slice. Three bands of `depth` slices in one 3D image: T, rayleigh, mie. */
layout(constant_id = VKSKY_SPEC_AP_RANGE) const float AP_RANGE_KM = 32.0;
layout(constant_id = VKSKY_SPEC_AP_DISTRIBUTION) const float AP_DISTRIBUTION = 2.0;
#define AP_BAND_TRANSMITTANCE 0
#define AP_BAND_RAYLEIGH 1
#define AP_BAND_MIE 2

/* Distance (km) at slice position x in [0, depth]: range (x / depth)^distribution, and its inverse. */
float ap_slice_distance(float x, float depth)
{
    float u = x / depth;
    return AP_RANGE_KM * (AP_DISTRIBUTION == 2.0 ? u * u : AP_DISTRIBUTION == 1.0 ? u : pow(u, AP_DISTRIBUTION));
}
float ap_slice_of_distance(float d, float depth)
{
    float u = clamp(d / AP_RANGE_KM, 0.0, 1.0);
    return depth * (AP_DISTRIBUTION == 2.0 ? sqrt(u) : AP_DISTRIBUTION == 1.0 ? u : pow(u, 1.0 / AP_DISTRIBUTION));
}
#endif

#ifdef AERIAL_VOLUME
/* Camera -> the point d km along the unit march-frame ray v, from the volume (sampler ap_volume): the ray's place
 * on the frustum picks the froxel column (bilinear), d the slices (linear in distance between the two slices
 * around it; below the first slice, linear from T = 1, S = 0). False when the volume does not hold the point
 * (behind the camera, outside the frustum, beyond the range): the caller marches. */
bool aerial_volume_lookup(vec3 v, float d, CompositePush p, out Aerial a)
{
    a.transmittance = vec3(1.0);
    a.rayleigh = a.mie = vec3(0.0);
    float forward = dot(v, p.forward.xyz);
    if (!(forward > 1e-6) || !(d <= AP_RANGE_KM)) return false;
    /* The frustum's screen coordinates of v (the inverse of the ray matrix's forward + x right + y up). */
    vec2 ndc = vec2(dot(v, p.right.xyz) / dot(p.right.xyz, p.right.xyz),
                    dot(v, p.up.xyz) / dot(p.up.xyz, p.up.xyz)) / forward;
    vec2 uv = vec2(0.5 * (ndc.x + 1.0), 0.5 * (1.0 - ndc.y));
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return false;
    float depth = float(textureSize(ap_volume, 0).z / 3);
    float x = ap_slice_of_distance(d, depth);
    float j = min(floor(x), depth - 1.0);
    float d_lo = ap_slice_distance(j, depth), d_hi = ap_slice_distance(j + 1.0, depth);
    float s = j + clamp((d - d_lo) / max(d_hi - d_lo, 1e-12), 0.0, 1.0);   /* slice position, linear in d */
    /* Texel centre k + 0.5 holds slice position k + 1; never closer than half a texel to a band's edge. */
    float z = max(s - 0.5, 0.5);
    float fade = min(s, 1.0);   /* below the first slice: from the identity at d = 0 */
    vec3 t = texture(ap_volume, vec3(uv, (AP_BAND_TRANSMITTANCE * depth + z) / (3.0 * depth))).rgb;
    a.transmittance = mix(vec3(1.0), t, fade);
    a.rayleigh = fade * texture(ap_volume, vec3(uv, (AP_BAND_RAYLEIGH * depth + z) / (3.0 * depth))).rgb;
    a.mie = fade * texture(ap_volume, vec3(uv, (AP_BAND_MIE * depth + z) / (3.0 * depth))).rgb;
    return true;
}
#endif
