/* Pixel -> view direction for every projection, one definition for every sky pass (fragment, compute; march and
 * sky-view lookup). The C twin (src/sky/projection.c) holds the same maths for tests and the header's sun
 * placement; docs/readme/envmap.md states the conventions. World axes: +Y up (the zenith), dir(az, el) =
 * (cos el cos az, sin el, cos el sin az): azimuth 0 = +X, 90 = +Z.
 * Pixel centres are at integer + 0.5; u = x / width, v = y / height run over the whole image (a tile adds its
 * offset), so maps are continuous across tile borders and an equirect's or cube's edges are pixel edges. */
#ifndef VKSKY_PROJECTION_GLSL
#define VKSKY_PROJECTION_GLSL
const float PROJ_PI = 3.14159265358979;

/* OpenEXR's cube-map face directions (ImfEnvmap: CubeMap::direction and pixelPosition), with a running left to
 * right and b top to bottom over the face, both in [-1, 1]. */
vec3 projection_cube_dir(int face, float a, float b)
{
    if (face == 0) return vec3(1.0, -b, a);          /* +X */
    if (face == 1) return vec3(-1.0, -b, -a);        /* -X */
    if (face == 2) return vec3(a, 1.0, -b);          /* +Y */
    if (face == 3) return vec3(a, -1.0, b);          /* -Y */
    if (face == 4) return vec3(-a, -b, 1.0);         /* +Z */
    return vec3(a, -b, -1.0);                        /* -Z */
}

/* The view ray of a pixel centre (tile-local pixel coordinates). `inside` is false where the projection has no
 * direction (outside the fisheye's circle): such pixels are written black. Perspective uses the ray matrix (camera
 * basis scaled by fov/aspect), never an inverse view-projection at planet scale. */
vec3 pixel_view_dir(vec2 pixel_centre, SkyPush p, out bool inside)
{
    /* precise: the compiler may not fold the offset into later products (a tile's pixel must get the very
     * direction it gets in the untiled frame, bit for bit). */
    precise vec2 g = pixel_centre + p.projection.yz;
    int kind = int(p.projection.x);
    inside = true;
    if (kind == VKSKY_PROJECTION_EQUIRECT) {
        /* Longitude +pi at the left edge to -pi at the right (OpenEXR LatLongMap); latitude +pi/2 at the top. */
        float lon = PROJ_PI * (1.0 - 2.0 * g.x * p.right.w);
        float lat = PROJ_PI * (0.5 - g.y * p.up.w);
        return vec3(sin(lon) * cos(lat), sin(lat), cos(lon) * cos(lat));
    }
    if (kind == VKSKY_PROJECTION_CUBEMAP) {
        /* right.w = 1 / face size; faces stacked vertically. */
        float face = floor(g.y * p.right.w);
        float a = 2.0 * g.x * p.right.w - 1.0;
        float b = 2.0 * (g.y * p.right.w - face) - 1.0;
        return normalize(projection_cube_dir(int(face), a, b));
    }
    if (kind == VKSKY_PROJECTION_FISHEYE) {
        /* Equidistant: the zenith angle grows linearly with the distance from the centre (the horizon at the
         * inscribed circle); seen from below, north (+X) up and east (+Z) left, as all-sky cameras record. */
        vec2 q = vec2(2.0 * g.x * p.right.w - 1.0, 1.0 - 2.0 * g.y * p.up.w);
        float r = length(q);
        inside = r <= 1.0;
        float theta = min(r, 1.0) * 0.5 * PROJ_PI;
        vec2 h = r > 0.0 ? q / r : vec2(0.0, 1.0);   /* (-sin az, cos az) */
        return vec3(sin(theta) * h.y, cos(theta), -sin(theta) * h.x);
    }
    vec2 ndc = vec2(2.0 * g.x * p.right.w - 1.0, 1.0 - 2.0 * g.y * p.up.w);
    return normalize(p.forward.xyz + ndc.x * p.right.xyz + ndc.y * p.up.xyz);
}
#endif
