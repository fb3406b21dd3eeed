/* Aerial perspective to a point: what the atmosphere does to the light from a surface at distance d along a view
 * ray, L = L_surface T + S (Bruneton's GetSkyRadianceToPoint, computed by the march itself rather than by
 * differences of 4D scattering tables). Expects sky_common.glsl.
 *
 * S comes split as the march splits it (MarchSegment in sky_common.glsl): rayleigh + mie = S exactly.
 *
 * This is the accurate path (--aerial-perspective march): one march per pixel over [0, d]. The froxel volume (the
 * fast path, --aerial-perspective volume) plugs in here: define AERIAL_VOLUME and provide
 * aerial_volume_lookup(v_march_frame, d) returning an Aerial, and composite.comp calls it instead. */

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
