/* The window's input: the controls table, key presses (toggles, steps, F5 reload), mouse capture and look, and
 * the held keys polled once a frame into the fly camera and the sun. */
#include "app/window/window_app.h"
#include "app/runs/host_print.h"
#include <math.h>
#include <string.h>

#define SUN_RATE_DEG_S 30.0
#define AUTO_SUN_RATE_DEG_S 15.0
#define LOOK_DEG_PER_PIXEL 0.1

static void print_controls(void)
{
    printf("vksky controls\n"
           "  W A S D        fly forward / left / back / right (0.2 km/s)\n"
           "  Space / C      fly up / down (along the local vertical)\n"
           "  Left Shift     10x speed\n"
           "  mouse          look around (click the window to capture the cursor)\n"
           "  Left / Right   sun azimuth (30 deg/s)\n"
           "  Up / Down      sun elevation (30 deg/s, -90..90)\n"
           "  T              automatic sun rotation (azimuth, 15 deg/s) on/off\n"
           "  1 / 2 / 3      tone map: clamp / Reinhard / ACES\n"
           "  = + / -        exposure +/- 0.5 EV (photometric units: EV100 -/+ 0.5, auto exposure off)\n"
           "  B              bloom on/off\n"
           "  Escape         release the mouse; again: quit\n"
           "  F5             reload the --scene file (recomputes only what changed)\n"
           "  F1 / H         this table\n");
    fflush(stdout);
}

static void set_captured(app *a, bool captured)
{
    a->in.captured = captured;
    a->in.have_cursor = false;   /* the first motion after a mode change is a jump, not a look */
    glfwSetInputMode(a->window, GLFW_CURSOR, captured ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
    if (glfwRawMouseMotionSupported())
        glfwSetInputMode(a->window, GLFW_RAW_MOUSE_MOTION, captured ? GLFW_TRUE : GLFW_FALSE);
}

static const char *tonemap_name(int t)
{
    return t == VKSKY_TONEMAP_CLAMP ? "clamp" : t == VKSKY_TONEMAP_REINHARD ? "reinhard" : "aces";
}

/* Discrete keys (toggles, steps) act on the press; held keys are polled once a frame in window_input_read. */
/* F5: reload the scene file's medium and features through the scene loader, the command line's flags over them again
 * as the values the start-up parse kept (vksky_scene_reload: no second parse of the command line), then
 * vksky_renderer_set_scene. The renderer recomputes only what changed: the LUTs when their inputs' hash changed, the
 * pipelines when the variant changed. The camera and the sun stay where the user put them. A broken file leaves the
 * current scene (its one-line error is printed). */
void window_input_reload(app *a)
{
    if (!a->o->scene_path) {
        printf("F5: no --scene file to reload\n");
        return;
    }
    if (vksky_scene_reload(a->scene, host_print_message, NULL) != VKSKY_SUCCESS) return;
    /* The atmosphere uniform buffer is shared by the frames in flight: wait for them before rewriting it. */
    vkDeviceWaitIdle(a->ctx.device);
    vksky_renderer_stats before, after;
    vksky_renderer_get_stats(a->renderer, &before);
    window_api_check(vksky_renderer_set_scene(a->renderer, a->scene), "vksky_renderer_set_scene");
    vksky_renderer_get_stats(a->renderer, &after);
    double ground_km = vksky_scene_ground_radius_m(a->scene) / 1000.0;
    if (ground_km != a->cam.ground_radius_km) {
        /* Another planet: the camera keeps its altitude, heading and sun over the new ground. */
        camera_to_view(&a->cam, &a->view);
        camera_init(&a->cam, &a->view, ground_km);
    }
    printf("scene reloaded: %s (LUTs %s, pipelines %s)\n", a->o->scene_path,
           vksky_renderer_luts_stale(a->renderer) ? "recomputed" : "kept",
           after.variant_builds != before.variant_builds ? "rebuilt" : "kept");
    fflush(stdout);
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode, (void)mods;
    if (action != GLFW_PRESS) return;
    app *a = glfwGetWindowUserPointer(w);
    sky_view *v = &a->view;
    switch (key) {
    case GLFW_KEY_ESCAPE:
        if (a->in.captured) set_captured(a, false);
        else glfwSetWindowShouldClose(w, GLFW_TRUE);
        return;
    case GLFW_KEY_T: a->in.auto_sun = !a->in.auto_sun; printf("auto sun %s\n", a->in.auto_sun ? "on" : "off"); break;
    case GLFW_KEY_1: v->tonemap = VKSKY_TONEMAP_CLAMP; break;
    case GLFW_KEY_2: v->tonemap = VKSKY_TONEMAP_REINHARD; break;
    case GLFW_KEY_3: v->tonemap = VKSKY_TONEMAP_ACES; break;
    /* + brightens: half a stop more exposure, which is half an EV100 less (photometric units; the keys then take
     * over from auto exposure). */
    case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD:
        v->exposure_ev = v->ev100 ? v->exposure_ev - 0.5 : fmin(20.0, v->exposure_ev + 0.5), a->auto_exposure = false;
        break;
    case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT:
        v->exposure_ev = v->ev100 ? v->exposure_ev + 0.5 : fmax(-20.0, v->exposure_ev - 0.5), a->auto_exposure = false;
        break;
    case GLFW_KEY_B: v->bloom = !v->bloom; printf("bloom %s\n", v->bloom ? "on" : "off"); break;
    case GLFW_KEY_F1: case GLFW_KEY_H: print_controls(); return;
    case GLFW_KEY_F5: window_input_reload(a); return;
    default: return;
    }
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_3) printf("tonemap %s\n", tonemap_name(v->tonemap));
    if (key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD || key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT)
        printf(v->ev100 ? "exposure EV100 %.1f\n" : "exposure %+.1f EV\n", v->exposure_ev);
    fflush(stdout);
}

static void on_mouse_button(GLFWwindow *w, int button, int action, int mods)
{
    (void)mods;
    app *a = glfwGetWindowUserPointer(w);
    if (button == GLFW_MOUSE_BUTTON_LEFT && action == GLFW_PRESS && !a->in.captured) set_captured(a, true);
}

static void on_cursor(GLFWwindow *w, double x, double y)
{
    app *a = glfwGetWindowUserPointer(w);
    if (a->in.captured && a->in.have_cursor) {
        a->in.look_dx += x - a->in.cursor_x;
        a->in.look_dy += y - a->in.cursor_y;
    }
    a->in.cursor_x = x, a->in.cursor_y = y, a->in.have_cursor = true;
}

static double key_axis(GLFWwindow *w, int positive, int negative)
{
    return (glfwGetKey(w, positive) == GLFW_PRESS ? 1.0 : 0.0) - (glfwGetKey(w, negative) == GLFW_PRESS ? 1.0 : 0.0);
}

/* Held keys and the mouse since the last frame -> camera and sun, over dt seconds of wall time. */
void window_input_read(app *a, double dt)
{
    GLFWwindow *w = a->window;
    camera_input in = {
        .forward = key_axis(w, GLFW_KEY_W, GLFW_KEY_S),
        .right = key_axis(w, GLFW_KEY_D, GLFW_KEY_A),
        .up = key_axis(w, GLFW_KEY_SPACE, GLFW_KEY_C),
        .boost = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS,
        .yaw_deg = a->in.look_dx * LOOK_DEG_PER_PIXEL,
        .pitch_deg = -a->in.look_dy * LOOK_DEG_PER_PIXEL,   /* screen y grows downwards */
        .sun_azimuth_deg = (key_axis(w, GLFW_KEY_RIGHT, GLFW_KEY_LEFT) * SUN_RATE_DEG_S +
                            (a->in.auto_sun ? AUTO_SUN_RATE_DEG_S : 0.0)) * dt,
        .sun_elevation_deg = key_axis(w, GLFW_KEY_UP, GLFW_KEY_DOWN) * SUN_RATE_DEG_S * dt,
    };
    a->in.look_dx = a->in.look_dy = 0.0;
    camera_update(&a->cam, &in, dt);
    camera_to_view(&a->cam, &a->view);
}

void window_input_install(app *a)
{
    glfwSetKeyCallback(a->window, on_key);
    glfwSetMouseButtonCallback(a->window, on_mouse_button);
    glfwSetCursorPosCallback(a->window, on_cursor);
}
