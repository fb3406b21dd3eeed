#include "app/runs/reference_run.h"
#include "app/scene/light.h"
#include "app/runs/exr_header.h"
#include "app/runs/stop.h"
#include "io/atomic_file.h"
#include "io/exr_write.h"
#include "io/half_float.h"
#include "reference/path_tracer.h"
#include "reference/spectral.h"
#include "model/spectrum.h"
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const double DEG = 3.14159265358979323846 / 180.0;

typedef struct ref_job {
    const options *o;
    ref_spectral spec;           /* --spectral: the spectral reference (spec.wavelengths 0: RGB) */
    pt_settings pt;
    double sun[3];
    float *rgba;
    int next_row;                /* shared work counter */
    pthread_mutex_t lock;
} ref_job;

/* The converged model, or (--path-trace) the Monte Carlo path tracer of the same medium with all scattering
 * orders and no horizon fade; err gets the path tracer's standard errors (0 for the model). */
static void radiance(const ref_job *job, const double view[3], const double sun[3], double rgb[3], double err[3])
{
    const options *o = job->o;
    err[0] = err[1] = err[2] = 0.0;
    model_atmosphere a = o->atmosphere;   /* the sun in output units: cd/m2 in photometric units (app/scene/light.h) */
    light_sun(o, a.sun_illuminance);
    if (job->spec.wavelengths) {   /* XYZ -> linear Rec.709; the error of Y only, as the luminance's */
        double xyz[3], se[3];
        ref_spectral_radiance(&job->spec, o->view.altitude_km, view, sun, xyz, se, NULL);
        spectrum_xyz_to_rec709(xyz, rgb);
        err[0] = err[1] = err[2] = se[1];
        return;
    }
    if (o->path_trace) {
        pt_settings s = {.samples = o->path_samples, .seed = 2020, .ground_albedo = o->ground_albedo[1], .threads = 1};
        pt_radiance(&a, o->view.altitude_km, view, sun, &s, rgb, err);
        return;
    }
    ref_quality q = ref_quality_converged();
    q.ms_off = !o->multiple_scattering;   /* --no-multiscatter: single scattering, as the GPU's (no Psi term) */
    ref_sky_radiance(&a, o->view.altitude_km, view, sun, q, rgb);
}

/* The spectral reference of the run: the scene's medium per wavelength or the RGB medium's; the sun the solar
 * spectrum scaled to the luminance of the configured sun in output units (1 for the default photometric sun, the
 * spectrum's own colour at its own illuminance). */
static void spectral_setup(const options *o, ref_spectral *s, pt_settings *pt)
{
    ref_spectral_init(s, &o->atmosphere, o->spectral ? o->spectral : 48);
    if (o->spectral_medium_set) s->medium = o->spectral_medium;
    s->q.ms_off = !o->multiple_scattering;   /* --no-multiscatter: single scattering, as the GPU's (no Psi term) */
    double e[3];   /* the sun in output units (app/scene/light.h): the spectrum itself (scale 1) for the default sun */
    light_sun(o, e);
    s->sun_scale = (0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2]) / spectrum_solar_illuminance_toa();
    if (o->path_trace) {
        *pt = (pt_settings){.samples = o->path_samples, .seed = 2020, .ground_albedo = o->ground_albedo[1],
                            .threads = 2};
        s->pt = pt;
    }
}

/* --irradiance: the beam, the sky and (tilted) the ground at the camera, in W/m^2 over 360-830 nm and in lux, then
 * the spectrum in 10 nm steps of the bins' centres. */
static int irradiance_run(const options *o, ref_job *job)
{
    ref_irradiance *r = malloc(sizeof *r);
    if (!r) return 1;
    double az = o->tilt_azimuth_set ? o->tilt_azimuth_deg : o->view.sun_azimuth_deg;
    if (ref_spectral_irradiance(&job->spec, o->view.altitude_km, job->sun, o->tilt_deg, az, o->ground_albedo, 16, r)) {
        free(r);
        return 1;
    }
    if (stop_requested()) {
        free(r);
        return stop_status(0);
    }
    printf("# irradiance at %g km, sun elevation %g deg; tilted surface: tilt %g deg facing azimuth %g deg (sun at "
           "%.2f deg from its normal); %d wavelengths, %s\n", o->view.altitude_km, o->view.sun_elevation_deg,
           o->tilt_deg, az, acos(fmax(-1.0, fmin(1.0, r->cos_incidence_tilted))) / DEG, r->count,
           o->path_trace ? "path tracer" : "model");
    double up[3] = {0.0, 1.0, 0.0}, xyz[3], sum;
    ref_spectral_radiance(&job->spec, o->view.altitude_km, up, job->sun, xyz, NULL, NULL);
    sum = xyz[0] + xyz[1] + xyz[2];
    printf("zenith luminance %.6g cd/m^2, chromaticity x %.4f y %.4f\n", xyz[1], sum > 0 ? xyz[0] / sum : 0.0,
           sum > 0 ? xyz[1] / sum : 0.0);
    const ref_irradiance_band *b[2] = {&r->watts, &r->lux};
    static const char *const unit[2] = {"W/m^2 (360-830 nm)", "lx"};
    for (int i = 0; i < 2; ++i)
        printf("%-20s direct_normal %.6g diffuse_horizontal %.6g global_horizontal %.6g diffuse_tilted %.6g "
               "global_tilted %.6g\n", unit[i], b[i]->direct_normal, b[i]->diffuse_horizontal,
               b[i]->global_horizontal, b[i]->diffuse_tilted, b[i]->global_tilted);
    printf("# nm direct_normal diffuse_horizontal global_horizontal diffuse_tilted global_tilted (W m^-2 nm^-1)\n");
    for (int k = 0; k < r->count; ++k) {
        const ref_irradiance_band *v = &r->spectral[k];
        printf("%.2f %.6g %.6g %.6g %.6g %.6g\n", r->nm[k], v->direct_normal, v->diffuse_horizontal,
               v->global_horizontal, v->diffuse_tilted, v->global_tilted);
    }
    free(r);
    return 0;
}

static void *render_rows(void *arg)
{
    ref_job *job = arg;
    const options *o = job->o;
    for (;;) {
        pthread_mutex_lock(&job->lock);
        int y = job->next_row++;
        pthread_mutex_unlock(&job->lock);
        if (y >= o->height) return NULL;
        /* The graceful stop, between pixels: a path-traced pixel can take long, a row much longer. */
        for (int x = 0; x < o->width && !stop_requested(); ++x) {
            double dir[3], rgb[3], err[3];
            ref_pixel_dir(x, y, o->width, o->height, o->view.yaw_deg * DEG, o->view.pitch_deg * DEG,
                          o->view.fov_deg * DEG, dir);
            radiance(job, dir, job->sun, rgb, err);
            float *p = job->rgba + 4 * ((size_t)y * o->width + x);
            for (int c = 0; c < 3; ++c) p[c] = (float)rgb[c];
            p[3] = 1.0f;
        }
    }
}

int reference_run(const options *o)
{
    char err[512];
    stop_install();
    for (int i = 0; i < o->output_count; ++i) {
        size_t n = strlen(o->outputs[i]);
        if (n < 4 || strcasecmp(o->outputs[i] + n - 4, ".exr") != 0) {
            fprintf(stderr, "vksky: --render: with --reference only .exr (scene-linear) outputs are accepted\n");
            return 2;
        }
        if (io_check_writable(o->outputs[i], err, sizeof err) != 0) {
            fprintf(stderr, "vksky: --render: %s\n", err);
            return 2;
        }
    }
    ref_job job = {.o = o};
    ref_dir(o->view.sun_azimuth_deg * DEG, o->view.sun_elevation_deg * DEG, job.sun);
    if (o->spectral || o->irradiance) {
        spectral_setup(o, &job.spec, &job.pt);
        if (o->irradiance) return irradiance_run(o, &job);
    }
    if (o->output_count == 0) {
        double view[3], rgb[3], e[3];
        ref_dir(o->view.yaw_deg * DEG, o->view.pitch_deg * DEG, view);
        radiance(&job, view, job.sun, rgb, e);
        if (stop_requested()) return stop_status(0);
        if (o->path_trace) printf("%.9g %.9g %.9g stderr %.3g %.3g %.3g\n", rgb[0], rgb[1], rgb[2], e[0], e[1], e[2]);
        else printf("%.9g %.9g %.9g\n", rgb[0], rgb[1], rgb[2]);
        return 0;
    }
    size_t pixels = (size_t)o->width * o->height;
    job.rgba = malloc(pixels * 4 * sizeof(float));
    pthread_mutex_init(&job.lock, NULL);
    /* The reference's multi-scattering table is built lazily: build it once before the threads share it. A stop
     * during the build leaves no table (ref_set_cancel): then no thread may start (each would build one, and
     * building is not thread-safe); the flag is set whenever the build was cut short. */
    {
        double view[3] = {0, 1, 0}, rgb[3], e[3];
        radiance(&job, view, job.sun, rgb, e);
    }
    if (stop_requested()) {
        free(job.rgba);
        pthread_mutex_destroy(&job.lock);
        return stop_status(0);
    }
    enum { THREADS = 2 };
    pthread_t threads[THREADS];
    for (int i = 0; i < THREADS; ++i) pthread_create(&threads[i], NULL, render_rows, &job);
    for (int i = 0; i < THREADS; ++i) pthread_join(threads[i], NULL);
    pthread_mutex_destroy(&job.lock);
    if (stop_requested()) {   /* rows left unrendered: write nothing */
        free(job.rgba);
        return stop_status(0);
    }
    uint16_t *half = malloc(pixels * 4 * sizeof(uint16_t));
    for (size_t i = 0; i < pixels * 4; ++i) half[i] = io_float_to_half(job.rgba[i]);
    free(job.rgba);
    int status = 0;
    for (int i = 0; i < o->output_count && status == 0; ++i) {
        io_exr_layer layer = {.name = "", .rgba_half = half};
        if (stop_requested()) {   /* the graceful stop: no further output (stop_status says why) */
            status = 1;
            break;
        }
        exr_header h;   /* how it was made (app/runs/exr_header.h): the command line says --reference */
        if (exr_header_build(&h, o, -1) != 0) {
            fprintf(stderr, "vksky: %s: out of memory for the EXR header\n", o->outputs[i]);
            status = 1;
            break;
        }
        if (io_write_exr_meta(o->outputs[i], o->width, o->height, &layer, 1, &h.meta, err, sizeof err) != 0) {
            if (!stop_requested()) fprintf(stderr, "vksky: %s\n", err);   /* else stop_status says why */
            status = 1;
        }
        exr_header_free(&h);
    }
    free(half);
    return stop_status(status);
}
