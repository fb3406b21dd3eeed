/* The example host's scene: its camera, its sun and its mesh (a ground plane and boxes standing on it), shared by
 * sky_host.c and its test (tests/example_host_check.c), which checks the picture against vksky's CLI and the CPU
 * reference. World: metres, +Y up, north -Z, east +X, the ground at y = 0 (vksky_camera.origin_altitude_m = 0). */
#ifndef VKSKY_EXAMPLE_SKY_HOST_SCENE_H
#define VKSKY_EXAMPLE_SKY_HOST_SCENE_H

#define SCENE_CAMERA_HEIGHT_M 200.0
#define SCENE_YAW_DEG 0.0          /* looking north */
#define SCENE_PITCH_DEG 5.0
#define SCENE_FOV_DEG 60.0
#define SCENE_NEAR_M 1.0
#define SCENE_SUN_AZIMUTH_DEG 180.0   /* behind the camera: it lights the boxes' faces that look at it */
#define SCENE_SUN_ELEVATION_DEG 25.0
#define SCENE_GROUND_HALF_M 40000.0
#define SCENE_GROUND_ALBEDO 0.1f

/* A box: its front face (facing the camera, +Z) centred on x at distance `distance_m` north, `width_m` wide and
 * deep, `height_m` tall, Lambertian with `albedo`. Pairs at one distance are mirror images (x and -x: the sun is in the
 * vertical plane of the view axis, so their rays see the same air) differing only in albedo: the test reads the
 * transmittance and the in-scattering from their difference. */
typedef struct scene_box {
    double x_m, distance_m, width_m, height_m;
    float albedo;
} scene_box;
#define SCENE_BOX_COUNT 6
static const scene_box SCENE_BOXES[SCENE_BOX_COUNT] = {
    {-150.0, 2000.0, 200.0, 400.0, 0.3f},     {150.0, 2000.0, 200.0, 400.0, 0.05f},     /* the near pair */
    {-3000.0, 12000.0, 1200.0, 1500.0, 0.3f}, {3000.0, 12000.0, 1200.0, 1500.0, 0.05f}, /* the far pair */
    {3500.0, 6000.0, 800.0, 900.0, 0.5f},     {-9000.0, 20000.0, 2500.0, 2500.0, 0.5f},
};
#endif
