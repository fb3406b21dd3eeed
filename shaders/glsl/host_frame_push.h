/* The SCENE_LINEAR pass's push constants (host_frame.comp, src/sky/host_frame.c): one definition for C and GLSL
 * (include shared.h first). 8 vec4 = 128 bytes, the push-constant size every device has. */
#ifndef VKSKY_HOST_FRAME_PUSH_H
#define VKSKY_HOST_FRAME_PUSH_H
#include "shared.h"
#ifndef VULKAN
#define vec4 vksky_vec4   /* shared.h's C spelling, undefined at its end */
#endif

VKSKY_STRUCT(HostFramePush) {
    /* The sky pass's push for the host's camera: its ray matrix is the host's inverse(projection x view) without
     * the translation, in the march frame (forward + x right + y up = the pixel's unnormalised ray, x and y its
     * Vulkan NDC with y up), altitude, sun, march, the horizon (sky_pixel in horizon.glsl reads it unchanged). */
    SkyPush sky;
    /* The host's depth d -> the point: offset from the camera (march-frame km) = (forward + x right + y up) /
     * (x d + y) (the perspective's 1/w, from the same inverse); z: the far plane's depth (0 reversed, 1 standard);
     * w: 1 reversed depth, 0 standard, 2 no depth image (sky in every pixel). */
    vec4 depth;
} VKSKY_END(HostFramePush)
#ifndef VULKAN
#undef vec4
#endif
#endif
