/* The process's CPU time: on a CPU device (lavapipe) a frame's work whatever else the machine runs, where wall and
 * timestamp times grow with the machine's load (--bench's and the window's cpu_ms, tools/tradeoff --cost cpu). */
#ifndef VKSKY_APP_CPU_TIME_H
#define VKSKY_APP_CPU_TIME_H
/* User + system CPU time of the whole process so far (every thread: a CPU device's workers too), in ms. */
double process_cpu_ms(void);
#endif
