/* The window's input handling (window_input.c): GLFW key, mouse button and cursor callbacks, and the held keys
 * read once a frame. */
#ifndef VKSKY_APP_WINDOW_INPUT_H
#define VKSKY_APP_WINDOW_INPUT_H
#include <stdbool.h>

typedef struct app app;   /* the window's state (app/window/window_app.h) */

typedef struct input_state {
    bool captured;             /* cursor disabled: mouse look */
    bool have_cursor;
    double cursor_x, cursor_y;
    double look_dx, look_dy;   /* pixels since the last frame */
    bool auto_sun;
} input_state;

/* Key, mouse button and cursor callbacks on a->window (whose user pointer is a). */
void window_input_install(app *a);
/* F5: the --scene file read again, the command line's flags over it as values; the renderer keeps what did not
 * change. A broken file keeps the current scene (its one line printed). */
void window_input_reload(app *a);
/* Held keys and the mouse since the last frame -> camera and sun (a->view), over dt seconds of wall time. */
void window_input_read(app *a, double dt);
#endif
