/* Dithering of the 8-bit display output (issue 26): a smooth sky gradient quantised to 8 bits shows bands (a
 * twilight sky: dozens of rows per level). Triangular noise of +-1 LSB added before quantisation turns the bands into
 * fine noise whose mean is the signal's and whose power does not depend on it (a triangular PDF, the sum of two
 * uniforms: the error's first two moments are independent of the value). Deterministic: seeded by the pixel's
 * position in the whole image (a tile's offset included), so the same render gives the same file. Expects
 * srgb_encode (tonemap_ops.glsl). */

/* Jarzynski and Olano's pcg2d (JCGT 2020): two well-mixed 32-bit values from a pixel. */
uvec2 dither_hash(uvec2 v)
{
    v = v * 1664525u + 1013904223u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v ^= v >> 16u;
    return v;
}

/* Triangular noise on (-1, 1): the sum of two uniforms on [0, 1) less 1. */
float dither_triangular(ivec2 pixel)
{
    uvec2 h = dither_hash(uvec2(pixel));
    vec2 u = vec2(h >> 8u) * (1.0 / 16777216.0);
    return u.x + u.y - 1.0;
}

vec3 dither_srgb_decode(vec3 c)
{
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

/* The display value with its dither (dither: TonemapPush's; x 1 = on, yz the frame's offset in the whole image).
 * `encoded`: the value is already sRGB-encoded (a UNORM target); otherwise the target's format encodes it, so the
 * noise is added in the encoded domain and decoded back (the format's encoding then lands on the dithered value).
 * Near 0 and 1 the amplitude shrinks to the distance from the end, so clipping never biases the mean. */
vec3 dither_display(vec3 value, ivec2 pixel, vec4 dither, bool encoded)
{
    if (dither.x < 0.5) return value;
    vec3 c = encoded ? value : srgb_encode(clamp(value, 0.0, 1.0));
    vec3 amplitude = clamp(min(c, 1.0 - c) * 255.0, 0.0, 1.0);
    c = clamp(c + dither_triangular(pixel + ivec2(dither.yz)) * amplitude / 255.0, 0.0, 1.0);
    return encoded ? c : dither_srgb_decode(c);
}
