/* The command-line flag table (see flags.h): one row per flag, in the order --help lists them. */
#include "app/cli/flags.h"
#include <string.h>

const flag flags_table[] = {
    {"--render", ARG_STRING, 0, 0, "FILE   write the frame: .exr (scene-linear RGBA, half or float: --exr-type; ZIP; the header records the scene, camera and command line) or .png (tone-mapped 8-bit sRGB); repeatable; a %d in FILE is the frame number"},
    {"--animate", ARG_STRING, 0, 0, "PARAM=FROM:TO  animate a numeric flag (sun-elevation, yaw, altitude, exposure, mie-g, ...) or time (local clock, decimal hours, with --date) linearly over the frames; repeatable"},
    {"--frame-count", ARG_INT, 1, 1000000, "N  frames of the sequence (default 1); with N > 1 each --render needs one %d (e.g. sky_%04d.exr), the frame number"},
    {"--frame-range", ARG_STRING, 0, 0, "A:B  render only frames A to B (inclusive, from 0) of the sequence: split it across jobs"},
    {"--skip-existing", ARG_NONE, 0, 0, "  render only the frames whose files are missing (an EXR of another frame or scene is rendered again): resume a sequence"},
    {"--width", ARG_INT, 1, 16384, "N      image width in pixels (default 1280)"},
    {"--height", ARG_INT, 1, 16384, "N      image height in pixels (default 720)"},
    {"--projection", ARG_STRING, 0, 0, "P perspective | equirect | cubemap | fisheye: camera view, 2:1 latitude-longitude map, OpenEXR cube (face = --width), all-sky fisheye (default perspective)"},
    {"--quiet", ARG_NONE, 0, 0, "         no progress report and no per-frame lines on stderr, no --max-error pick on stdout"},
    {"--sun-elevation", ARG_DOUBLE, -90, 90, "DEG   sun elevation above the horizon (default 20)"},
    {"--sun-azimuth", ARG_DOUBLE, -360, 360, "DEG   sun azimuth, clockwise seen from above: with --yaw 0 as north, 90 is east (default 0)"},
    {"--date", ARG_STRING, 0, 0, "YYYY-MM-DD  the sun by date and place (NREL SPA): local date; needs --time, --latitude, --longitude; not with --sun-elevation/--sun-azimuth"},
    {"--time", ARG_STRING, 0, 0, "HH:MM[:SS]  local clock time (24 h) for --date"},
    {"--utc-offset", ARG_DOUBLE, -18, 18, "H  local time minus UTC in hours for --date, e.g. -7 for UTC-7 (default 0)"},
    {"--latitude", ARG_DOUBLE, -90, 90, "DEG  observer latitude for --date, north positive"},
    {"--longitude", ARG_DOUBLE, -180, 180, "DEG  observer longitude for --date, east positive"},
    {"--elevation-m", ARG_DOUBLE, -500, 100000, "M  observer height above sea level for --date (default 0)"},
    {"--altitude", ARG_DOUBLE, 0, 1e6, "KM    camera altitude above the ground (default 0.001 = 1 m)"},
    {"--yaw", ARG_DOUBLE, -360, 360, "DEG    view azimuth, same convention as --sun-azimuth (default 0)"},
    {"--pitch", ARG_DOUBLE, -90, 90, "DEG    view elevation, same convention as --sun-elevation (default 10)"},
    {"--fov", ARG_DOUBLE, 1, 170, "DEG    vertical field of view (default 75)"},
    {"--exposure", ARG_DOUBLE, -20, 20, "EV  exposure: EV100 in photometric units (the camera's: scene luminance L shows as L / (1.2 2^EV)), stops before tone mapping in relative units (default: --auto-exposure in photometric units, 0 in relative)"},
    {"--auto-exposure", ARG_NONE, 0, 0, "  exposure from the frame's log-average luminance, EV100 = log2(L_avg 100 / 12.5) (the default in photometric units without --exposure; docs/units.md)"},
    {"--units", ARG_STRING, 0, 0, "U     photometric | relative: pixels in cd/m2 (linear Rec.709, Y = luminance) with the sun from the solar spectrum (1.33e5 lx), or the lesson's scale (the sun 20,20,20) (default photometric; docs/units.md)"},
    {"--exr-type", ARG_STRING, 0, 0, "T  half | float | auto: EXR channel type; auto: float where a value would overflow half (the sun's disc in photometric units), else half (default auto)"},
    {"--tonemap", ARG_STRING, 0, 0, "OP   clamp | reinhard | aces (default aces)"},
    {"--no-bloom", ARG_NONE, 0, 0, "      leave bloom out (no bloom passes, no mip chain)"},
    {"--no-dither", ARG_NONE, 0, 0, "     8-bit output (PNG, the window) without its triangular dither of +-1 LSB"},
    {"--steps", ARG_INT, 1, 4096, "N      view march steps per pixel (default 32)"},
    {"--quality", ARG_STRING, 0, 0, "P   low | medium | high | ultra | lesson | cpu | auto: a preset of the knobs below (later flags override it); auto (the default of --render/--bench): the measured front's point for the scene kind and device kind (a sequence's: the GPU table's, on any device); lesson: the 32-step march of the guide; cpu: a 96x54 sky-view LUT at half size, quarter-size bloom (lavapipe 1280x720: < 1 % daytime error, 35 ms of CPU a frame); auto's colour: a render (.exr or .png still, sequence: one pick for all its frames' kinds; .exr or .png environment map, in one band or several; --composite, --aovs) whose scene's RGB colour is over the default colour budget CIEDE2000 1 from the spectrum's renders the fewest --spectral wavelengths within it (every kind on a GPU: noon 8, afternoon 16; on a CPU device only where RGB is over 3: sunset, twilight, altitude; the window, --bench and sequences stay RGB and say why; --spectral 0 keeps RGB)"},
    {"--bloom-res", ARG_STRING, 0, 0, "R    half | quarter: the bloom chain's first mip at half or a quarter of the sky's size (default: the preset's, half except for --quality cpu; quarter: a quarter of the bloom's cost, for CPU devices)"},
    {"--bloom-downsample", ARG_STRING, 0, 0, "D levels | single-pass: with --post-pass compute, the bloom downsample as one dispatch per level (default: faster on an H100) or all levels in one dispatch (tile counters, the last workgroup continues)"},
    {"--post-pass", ARG_STRING, 0, 0, "K fragment | compute | auto: bloom and the tone map as draws or compute dispatches (one dispatch for the whole bloom downsample); auto: fragment on a CPU device, compute on a GPU (default auto)"},
    {"--max-error", ARG_DOUBLE, 1e-4, 1, "E the cheapest measured configuration whose mean relative luminance error on this kind of scene is <= E"},
    {"--max-color-error", ARG_DOUBLE, 0.01, 100, "DE the fewest wavelengths (--spectral 0, 4, 8, 16, 24 or 32) whose measured worst CIEDE2000 against the 48-wavelength spectral reference on this kind of scene is <= DE; prints what it picked (as --spectral's outputs when spectral)"},
    {"--max-steps", ARG_INT, 1, 4096, "N  variable step count (Hillaire): from --steps up to N as the path grows (default: = --steps)"},
    {"--steps-ramp", ARG_DOUBLE, 0.001, 1e5, "KM path length at which the variable count reaches --max-steps (default 100)"},
    {"--sample-offset", ARG_DOUBLE, 0, 1, "X sample position within a step: 0.5 midpoint (default), 0.3 Hillaire"},
    {"--step-distribution", ARG_DOUBLE, 1, 4, "P steps end at t_max (i/N)^P: 1 uniform, 2 quadratic (default 2; uniform for rays entering from space)"},
    {"--sky-mode", ARG_STRING, 0, 0, "M   march | skyview | auto | fill: per-pixel march, sky-view LUT lookup, the LUT inside the atmosphere, or a constant (the benchmark floor) (default march)"},
    {"--sky-pass", ARG_STRING, 0, 0, "K   fragment | compute | auto: the sky pass as a full-screen draw or a compute dispatch; auto: fragment on a CPU device, compute on a GPU (default auto)"},
    {"--skyview-lut", ARG_STRING, 2, 4096, "WxH sky-view LUT size (default 192x108)"},
    {"--skyview-steps", ARG_INT, 1, 1024, "N march steps per sky-view LUT texel (default 30)"},
    {"--transmittance-lut", ARG_STRING, 2, 4096, "WxH transmittance LUT size (default 256x64)"},
    {"--transmittance-steps", ARG_INT, 1, 4096, "N steps per transmittance texel (default 40)"},
    {"--multiscatter-lut", ARG_INT, 2, 1024, "N multi-scattering LUT size NxN (default 32)"},
    {"--multiscatter-dirs", ARG_INT, 1, 4096, "N sphere directions per texel, a perfect square (default 64)"},
    {"--multiscatter-steps", ARG_INT, 1, 4096, "N steps per direction (default 20)"},
    {"--lut-format", ARG_STRING, 0, 0, "F  f16 | f32: RGBA16F or RGBA32F LUTs (default f16)"},
    {"--bloom-mips", ARG_INT, 1, 8, "N   bloom downsample passes (default 5)"},
    {"--render-scale", ARG_DOUBLE, 0.1, 1, "S sky rendered at S x the output size (full size where the shorter axis would get < 32 pixels), upsampled by the tone map (default 1)"},
    {"--mie-g", ARG_DOUBLE, -0.999, 0.999, "G       Mie Henyey-Greenstein asymmetry (default 0.8)"},
    {"--rayleigh-scale", ARG_DOUBLE, 0, 1000, "S Rayleigh density scale (default 1)"},
    {"--mie-scale", ARG_DOUBLE, 0, 1000, "S      Mie (aerosol) density scale (default 1)"},
    {"--ozone-scale", ARG_DOUBLE, 0, 1000, "S    ozone density scale (default 1)"},
    {"--scene", ARG_STRING, 0, 0, "FILE.json|FILE.exr|NAME  load a scene file, the scene (and units) an EXR made by vksky was rendered from, or a shipped scene by name (--list-scenes), first (schema: scenes/README.md); every other flag overrides it"},
    {"--list-scenes", ARG_NONE, 0, 0, "list the shipped scenes (names for --scene) with a line each, and exit"},
    {"--dump-scene", ARG_NONE, 0, 0, "      print the effective scene (after all overrides) as scene JSON and exit"},
    {"--ground-albedo", ARG_TRIPLE, 0, 1, "R,G,B ground albedo (default 0,0,0)"},
    {"--mie-phase", ARG_STRING, 0, 0, "M    hg | cornette-shanks: the Mie phase function (default hg = Henyey-Greenstein)"},
    {"--sun-illuminance", ARG_TRIPLE, 0, 1e6, "R,G,B sun illuminance at the top of the atmosphere in the lesson's scale, where 20,20,20 is the real sun (photometric units: that fraction of the solar spectrum) (default 20,20,20)"},
    {"--sun-lux", ARG_DOUBLE, 0, 1e7, "LX   the sun's illuminance at the top of the atmosphere in lux: the solar spectrum scaled (default 133177, the spectrum's own)"},
    {"--sun-angular-radius", ARG_DOUBLE, 0.01, 10, "DEG sun disc angular radius (default 0.265)"},
    {"--limb-darkening", ARG_DOUBLE, 0, 1, "U   sun limb darkening coefficient (default 0.6)"},
    {"--no-sun-disc", ARG_NONE, 0, 0, "     leave the sun disc out"},
    {"--sun-visibility", ARG_STRING, 0, 0, "M penumbra | lesson-fade: the sun's visibility at each point, the fraction of its disc above the horizon, or the lesson's fade (default penumbra)"},
    {"--no-multiscatter", ARG_NONE, 0, 0, " single scattering only (no multi-scattering term or LUT)"},
    {"--reference", ARG_NONE, 0, 0, "       CPU reference (double precision, no LUTs): print R G B along the view axis, or with --render write a reference image"},
    {"--path-trace", ARG_NONE, 0, 0, "      with --reference: Monte Carlo path tracer of the same medium, all scattering orders"},
    {"--samples", ARG_INT, 1, 100000000, "N        with --path-trace: paths per estimate (default 4096)"},
    {"--spectral", ARG_INT, 0, 120, "N       colour from N wavelengths over 360-830 nm (radiance -> CIE XYZ -> linear Rec.709; 0: RGB, the default); with --reference 3-120 (>= 40 recommended), on the GPU a multiple of 4 up to 48 (four wavelengths a pass without bloom or the horizon in view, else three), --render only: .exr, .png (tone-mapped on the host), .exr environment maps, --composite and --aovs (three a pass)"},
    {"--irradiance", ARG_NONE, 0, 0, "    with --reference: print the direct normal, diffuse and global irradiance (W/m^2, 360-830 nm) and illuminance (lx) at the camera, spectral (default 48 wavelengths)"},
    {"--tilt", ARG_DOUBLE, 0, 180, "DEG       with --irradiance: the tilted surface's tilt from horizontal (default 0)"},
    {"--tilt-azimuth", ARG_DOUBLE, -360, 360, "DEG with --irradiance: the azimuth the tilted surface faces, as --sun-azimuth (default: the sun's)"},
    {"--bench", ARG_INT, 1, 100000, "N      render N frames after warm-up, print per-pass GPU ms medians"},
    {"--frames", ARG_INT, 1, 100000000, "N     window: quit after N presented frames"},
    {"--screenshot", ARG_STRING, 0, 0, "FILE window: save the last presented frame as PNG before quitting"},
    {"--async-luts", ARG_NONE, 0, 0, "    the LUT passes on a second queue (a compute-only family, else a second queue of the graphics family; refused if the device has neither), ordered by timeline semaphores (docs/synchronization.md section 10)"},
    {"--validate", ARG_NONE, 0, 0, "      Khronos validation + synchronization validation; any message fails the run (also VKSKY_VALIDATION=1)"},
    {"--trace-barriers", ARG_NONE, 0, 0, "print one line per barrier as the frame is recorded"},
    {"--trace-passes", ARG_NONE, 0, 0, "  list the passes the frame records"},
    {"--timings", ARG_NONE, 0, 0, "       where the first image's time went (exec, options, probe, instance, device, pipelines, setup, LUTs, frame, readback, encode, write, teardown: they add up to the total), on stderr; a sequence's, banded render's or composite's stages"},
    {"--no-cache", ARG_NONE, 0, 0, "      no pipeline or LUT cache on disk (default: $XDG_CACHE_HOME/vksky or ~/.cache/vksky, per device and driver)"},
    {"--list-devices", ARG_NONE, 0, 0, "  list Vulkan devices and exit"},
    {"--device", ARG_INT, 0, 63, "N     use device N of --list-devices (default: discrete > integrated > CPU)"},
    {"--threads", ARG_INT, 1, 1024, "N     threads that compress EXR chunks and PNG image data (default: the cores available); EXRs are the same for every N, PNGs for every N > 1 (N = 1: libpng's own bytes)"},
    {"--exr-compression", ARG_STRING, 0, 0, "C zip | zips | piz | pxr24 | b44 | b44a | rle | none: the EXR compression (default zip; zip:1 .. zip:9 a deflate level (libdeflate), default 4 (OpenEXR 3.2's): zip:6 writes 0.95x the bytes in 1.6x the time; pxr24, b44, b44a are lossy; DWAA/DWAB: OpenEXR 3.1's C library cannot write them)"},
    {"--help", ARG_NONE, 0, 0, "          this text"},
    {"--version", ARG_NONE, 0, 0, "       print the version"},
};

const int flags_count = (int)(sizeof flags_table / sizeof flags_table[0]);

const flag *flags_find(const char *name, size_t name_len)
{
    const flag *f = NULL;
    for (int k = 0; k < flags_count; ++k)
        if (strlen(flags_table[k].name) == name_len && !strncmp(flags_table[k].name, name, name_len)) f = &flags_table[k];
    return f;
}

bool flags_range(const char *flag_name, double *min, double *max)
{
    for (int i = 0; i < flags_count; ++i)
        if (!strcmp(flags_table[i].name, flag_name) && flags_table[i].min < flags_table[i].max) {
            *min = flags_table[i].min, *max = flags_table[i].max;
            return true;
        }
    return false;
}
