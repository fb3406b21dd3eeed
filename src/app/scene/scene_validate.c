/* Scene files: reading one field of the JSON: its type, its range (the flag's, from the flag table, or the
 * scene-only ranges), unknown and repeated fields, and the one-line message when it is wrong. See scene_validate.h. */
#include "app/scene/scene_validate.h"
#include "app/cli/bad_value.h"
#include "app/cli/flags.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A printable, bounded copy (control characters -> '?'): messages stay one line whatever the file holds. */
void scene_printable(char *dst, size_t n, const char *src)
{
    size_t k = 0;
    for (; src && *src && k + 1 < n; ++src) dst[k++] = (unsigned char)*src < 0x20 || *src == 0x7f ? '?' : *src;
    dst[k] = '\0';
}

void scene_join(char *out, const char *parent, const char *key)
{
    char k[64];
    scene_printable(k, sizeof k, key);
    /* Long paths are cut; the return value is checked only to say so to the compiler. */
    if (snprintf(out, PATH_LEN, "%s%s%s", parent, parent[0] ? "." : "", k) >= PATH_LEN) out[PATH_LEN - 1] = '\0';
}

int scene_fail(const scene_ctx *c, const char *path, const char *fmt, ...)
{
    char msg[640];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fprintf(options_report_stream(), "vksky: %s: %s: %s\n", c->file, path, msg);
    return 2;
}

const char *scene_type_of(const cJSON *j)
{
    if (cJSON_IsNumber(j)) return "a number";
    if (cJSON_IsString(j)) return "a string";
    if (cJSON_IsBool(j)) return "a boolean";
    if (cJSON_IsNull(j)) return "null";
    if (cJSON_IsArray(j)) return "an array";
    if (cJSON_IsObject(j)) return "an object";
    return "an invalid value";
}

void scene_word_list(char *out, size_t n, const char *const *words, int count, const char *last_sep)
{
    size_t k = 0;
    out[0] = '\0';
    for (int i = 0; i < count && k < n; ++i)
        k += (size_t)snprintf(out + k, n - k, "%s%s", words[i], i + 2 < count ? ", " : i + 1 < count ? last_sep : "");
}

scene_range scene_flag_range(const char *flag, bool integer)
{
    scene_range r = {0, 0, integer, flag};
    if (!flags_range(flag, &r.min, &r.max)) {
        fprintf(options_report_stream(), "vksky: internal error: no range for %s in the flag table\n", flag);
        abort();
    }
    return r;
}

scene_range scene_only_range(double min, double max)
{
    return (scene_range){min, max, false, NULL};
}

/* Unknown and repeated fields of an object. */
int scene_check_fields(const scene_ctx *c, const cJSON *obj, const char *path, const char *const *names, int count)
{
    for (const cJSON *it = obj->child; it; it = it->next) {
        char p[PATH_LEN];
        scene_join(p, path, it->string);
        bool known = false;
        for (int i = 0; i < count; ++i) known = known || !strcmp(it->string, names[i]);
        if (!known) {
            char list[512];
            scene_word_list(list, sizeof list, names, count, ", ");
            return scene_fail(c, p, "unknown field; accepted: %s", list);
        }
        for (const cJSON *prev = obj->child; prev != it; prev = prev->next)
            if (!strcmp(prev->string, it->string)) return scene_fail(c, p, "given twice; give each field once");
    }
    return 0;
}

/* Field `key` of `obj` (NULL if absent); its path in *path. */
const cJSON *scene_field(const cJSON *obj, const char *key, const char *parent, char *path)
{
    scene_join(path, parent, key);
    return obj ? cJSON_GetObjectItemCaseSensitive(obj, key) : NULL;
}

int scene_get_object(const scene_ctx *c, const cJSON *obj, const char *key, const char *parent, const cJSON **out)
{
    char p[PATH_LEN];
    const cJSON *j = scene_field(obj, key, parent, p);
    *out = NULL;
    if (!j) return 0;
    if (!cJSON_IsObject(j)) return scene_fail(c, p, "expected an object, got %s", scene_type_of(j));
    *out = j;
    return 0;
}

int scene_check_number(const scene_ctx *c, const cJSON *j, const char *path, scene_range r, double *out)
{
    const char *what = r.integer ? "an integer" : "a number";
    char as[48] = "";
    if (r.flag) snprintf(as, sizeof as, " (as %s)", r.flag);
    if (!cJSON_IsNumber(j)) return scene_fail(c, path, "expected %s, got %s", what, scene_type_of(j));
    double v = j->valuedouble;
    if (!isfinite(v)) return scene_fail(c, path, "not a finite number; expected %s in [%g, %g]%s", what, r.min, r.max, as);
    if (r.integer && v != floor(v))
        return scene_fail(c, path, "%.10g is not an integer; expected an integer in [%g, %g]%s", v, r.min, r.max, as);
    if (v < r.min || v > r.max)
        return scene_fail(c, path, "%.10g is out of range; expected %s in [%g, %g]%s", v, what, r.min, r.max, as);
    *out = v;
    return 0;
}

int scene_get_number(const scene_ctx *c, const cJSON *obj, const char *key, const char *parent, scene_range r, double *out)
{
    char p[PATH_LEN];
    const cJSON *j = scene_field(obj, key, parent, p);
    return j ? scene_check_number(c, j, p, r, out) : 0;
}

int scene_get_int(const scene_ctx *c, const cJSON *obj, const char *key, const char *parent, scene_range r, int *out)
{
    double v = *out;
    r.integer = true;
    if (scene_get_number(c, obj, key, parent, r, &v)) return 2;
    *out = (int)v;
    return 0;
}

/* An array of exactly n numbers in r; *given tells whether the field was there. */
int scene_get_array(const scene_ctx *c, const cJSON *obj, const char *key, const char *parent, scene_range r, int n, double *out,
                     bool *given)
{
    char p[PATH_LEN];
    const cJSON *j = scene_field(obj, key, parent, p);
    if (given) *given = j != NULL;
    if (!j) return 0;
    const char *what = r.integer ? "integers" : "numbers";
    if (!cJSON_IsArray(j)) return scene_fail(c, p, "expected an array of %d %s, got %s", n, what, scene_type_of(j));
    if (cJSON_GetArraySize(j) != n)
        return scene_fail(c, p, "expected %d %s, got %d", n, what, cJSON_GetArraySize(j));
    double v[4];
    int i = 0;
    for (const cJSON *e = j->child; e; e = e->next, ++i) {
        char pe[PATH_LEN + 16];
        snprintf(pe, sizeof pe, "%s[%d]", p, i);
        if (scene_check_number(c, e, pe, r, &v[i])) return 2;
    }
    memcpy(out, v, (size_t)n * sizeof *out);
    return 0;
}

int scene_get_bool(const scene_ctx *c, const cJSON *obj, const char *key, const char *parent, bool *out)
{
    char p[PATH_LEN];
    const cJSON *j = scene_field(obj, key, parent, p);
    if (!j) return 0;
    if (!cJSON_IsBool(j)) return scene_fail(c, p, "expected true or false, got %s", scene_type_of(j));
    *out = cJSON_IsTrue(j);
    return 0;
}

int scene_get_word(const scene_ctx *c, const cJSON *obj, const char *key, const char *parent, const char *const *words,
                    int count, int *out)
{
    char p[PATH_LEN], list[256], value[64];
    const cJSON *j = scene_field(obj, key, parent, p);
    if (!j) return 0;
    scene_word_list(list, sizeof list, words, count, " or ");
    if (!cJSON_IsString(j)) return scene_fail(c, p, "expected a string (%s), got %s", list, scene_type_of(j));
    for (int i = 0; i < count; ++i)
        if (!strcmp(j->valuestring, words[i])) {
            *out = i;
            return 0;
        }
    scene_printable(value, sizeof value, j->valuestring);
    return scene_fail(c, p, "unknown value '%s'; expected %s", value, list);
}

