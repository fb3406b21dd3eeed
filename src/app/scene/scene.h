/* Scene files: a JSON description of what to render (planet, medium, sun, camera, output, quality), parsed with
 * cJSON onto the options struct. `vksky --scene FILE.json` loads one before any flag is applied, so every flag
 * overrides the scene; `vksky --dump-scene` prints the effective scene (after all overrides) in this schema, and
 * loading that dump back reproduces the same options. scenes/README.md documents the shipped scenes.
 *
 * Schema (every field optional; an absent field keeps the default, which is Hillaire 2020 Table 1 and the CLI's
 * defaults; units: km, /km, degrees; [r, g, b] = three numbers for 680, 550, 440 nm):
 *
 * { "description": "free text",
 *   "planet": {"ground_radius_km": 6360, "atmosphere_top_km": 6460, "ground_albedo": [0, 0, 0]},
 *   "species": {
 *     "rayleigh": {"scattering": [5.802e-3, 13.558e-3, 33.1e-3], "absorption": [0, 0, 0],
 *                  "density": {"profile": "exponential", "scale_height_km": 8}},
 *     "mie":      {"scattering": [3.996e-3, ...], "absorption": [0.444e-3, ...],
 *                  "density": {"profile": "exponential", "scale_height_km": 1.2},
 *                  "phase": {"model": "henyey-greenstein" | "cornette-shanks", "g": 0.8}},
 *     "ozone":    {"scattering": [0, 0, 0], "absorption": [0.650e-3, 1.881e-3, 0.085e-3],
 *                  "density": {"profile": "tent", "center_km": 25, "half_width_km": 15}}},
 *   "multiple_scattering": true,
 *   "sun": {"elevation_deg": 20, "azimuth_deg": 0, "illuminance": [20, 20, 20], "angular_radius_deg": 0.265,
 *           "limb_darkening": 0.6, "disc": true},
 *   "camera": {"altitude_km": 0.001, "yaw_deg": 0, "pitch_deg": 10, "fov_deg": 75},
 *   "output": {"width": 1280, "height": 720, "exposure_ev": 0, "tonemap": "clamp" | "reinhard" | "aces",
 *              "bloom": true},
 *   "quality": {"preset": "low" | "medium" | "high" | "ultra", "sky_mode": "march" | "skyview" | "auto" | "fill",
 *               "sky_pass": "fragment" | "compute" | "auto", "steps": 32, "max_steps": 0, "steps_ramp_km": 100,
 *               "step_distribution": 2, "sample_offset": 0.5, "skyview_lut": [192, 108], "skyview_steps": 30,
 *               "transmittance_lut": [256, 64], "transmittance_steps": 40, "multiscatter_lut": 32,
 *               "multiscatter_directions": 64, "multiscatter_steps": 20, "lut_format": "f16" | "f32",
 *               "render_scale": 1, "bloom_mips": 5} }
 *
 * Rules:
 *  - Species: rayleigh, mie and ozone only. Rayleigh absorption and ozone scattering must be 0 (the model has
 *    neither). Density profiles: exponential (rayleigh, mie), tent (ozone).
 *  - A field that has a command-line flag has that flag's range (looked up in the flag table, app/cli/flags.c, not copied):
 *    e.g. camera.fov_deg as --fov, species.mie.phase.g as --mie-g, quality.max_steps as --max-steps (or 0: fixed).
 *    Fields without a flag: radii in [1, 1e6] km with atmosphere_top_km > ground_radius_km, coefficients in
 *    [0, 1000] /km, scale heights and the tent's half width in [0.01, 1000] km, its centre in [0, 1000] km.
 *  - Numbers must be finite (1e400 parses as infinity and is refused); integers must be integral.
 *  - Precedence: defaults < the scene's quality.preset < the scene's other fields < flags. A --quality or
 *    --max-error flag replaces the scene's whole quality section (preset and knobs); later knob flags override it.
 *    Density scale flags (--mie-scale ...) multiply the scene's coefficients.
 *
 * Errors: one line on stderr, status 2: "vksky: FILE: field.path: what; expected ..." for a field (unknown field,
 * wrong type, out of range, unsupported), "vksky: FILE:LINE:COLUMN: syntax error ..." for malformed JSON,
 * "vksky: --scene: cannot read 'FILE': reason" for an unreadable file. */
#ifndef VKSKY_APP_SCENE_H
#define VKSKY_APP_SCENE_H
#include "app/cli/options_struct.h"

/* Load a scene file onto *o (fields present override what *o holds; a quality preset the scene names is applied
 * first, its knob fields after it, and o->quality is set to the preset's name). 0: ok; 2: bad input (one line
 * printed on stderr; *o may be partly changed). */
int scene_load(const char *path, options *o);

/* The "description" of the scene loaded last (NULL: none, or it had none); --dump-scene writes it back. */
const char *scene_loaded_description(void);
#endif
