/* The tone map's read of the sky (HDR) image at an output pixel, shared by the fragment and compute tone maps.
 * At render scale 1 the output pixel is a texel centre and this is that texel. Below 1 it is a bilinear upsample
 * that does not blend across a class boundary (the sky pass's alpha: 0 ground, 1 sky): where the four taps are not
 * all of one class, the output pixel takes its nearest texel, so the horizon stays sharp (moved at most half a sky
 * texel) instead of blending ground into the sky. The bilinear sample's own alpha decides, with no extra fetch:
 * with classes 0 and 1 and positive weights it is within 1e-3 of 0 or 1 only where the taps agree. One fetch, not a weighted four: lavapipe runs a branch's body whenever any pixel
 * of its 8-wide group takes it, so each extra fetch costs every pixel (measured at 1280x720: nearest +4.6 ms of
 * CPU a frame, the class-weighted four +13 ms); within one texel a class varies little. */
vec3 hdr_upsample(sampler2D hdr, vec2 uv)
{
    vec4 bilinear = textureLod(hdr, uv, 0.0);
    if (abs(bilinear.a - round(bilinear.a)) < 1e-3) return bilinear.rgb;
    ivec2 size = textureSize(hdr, 0);
    return texelFetch(hdr, clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1), 0).rgb;
}
