/* Shape description files written (rugo_shape_desc_write): the desc checked as the reader would check
 * it, then written so that it reads back to the same bits. */
#include "rugo/shape_file.h"

#include "core/internal.h"
#include "io/json.h"
#include "rough/internal.h" /* rugo__roughness_arc_source_check */

static const char* estimator_name(rugo_tolerance_estimator est) {
    switch (est) {
    case RUGO_ESTIMATOR_COEFFICIENTS:
        return "coefficients";
    case RUGO_ESTIMATOR_DETAIL:
        return "detail";
    }
    return NULL;
}

static const char* method_name(rugo_roughen_method m) {
    switch (m) {
    case RUGO_ROUGHEN_WAVELET:
        return "wavelet";
    case RUGO_ROUGHEN_LOCAL:
        return "local";
    }
    return NULL;
}

/* Checks a roughness desc for a shape of n control points, as the reader would. */
static rugo_status check_roughness(const rugo_roughness_desc* r, int n) {
    rugo_status s = RUGO_OK;
    switch (r->kind) {
    case RUGO_ROUGHNESS_PRESET:
        if ((int)r->preset < 0 || r->preset >= RUGO_PRESET_COUNT || rugo_preset_name(r->preset) == NULL)
            return RUGO_ERR_BAD_ARGUMENT;
        break;
    case RUGO_ROUGHNESS_CONSTANT:
        s = rugo_tolerances_check(&r->constant, 1, NULL);
        break;
    case RUGO_ROUGHNESS_TOLERANCES:
        if (r->tolerance_count != n) return RUGO_ERR_BAD_ARGUMENT;
        if (n > 0 && r->tolerances == NULL) return RUGO_ERR_NULL_ARGUMENT;
        if (n > 0) s = rugo_tolerances_check(r->tolerances, n, NULL);
        break;
    case RUGO_ROUGHNESS_RANGES:
    case RUGO_ROUGHNESS_PROFILE:
        s = rugo__roughness_arc_source_check(r);
        break;
    default:
        return RUGO_ERR_BAD_ARGUMENT;
    }
    if (s != RUGO_OK) return s;
    if (r->seed > RUGO_MAX_FILE_SEED) return RUGO_ERR_BAD_ARGUMENT;
    if (!(r->q > 0.0 && isfinite(r->q))) return RUGO_ERR_BAD_QUANTILE;
    if (estimator_name(r->estimator) == NULL) return RUGO_ERR_BAD_ARGUMENT;
    if ((s = rugo_friction_map_check(&r->friction)) != RUGO_OK) return s;
    if ((s = rugo_restitution_check(&r->restitution)) != RUGO_OK) return s;
    if (r->has_perturbation) {
        if (method_name(r->perturbation_method) == NULL) return RUGO_ERR_BAD_ARGUMENT;
        if (r->perturbation_levels < 1 || r->perturbation_levels > RUGO_MAX_PERTURBATION_LEVELS)
            return RUGO_ERR_BAD_ARGUMENT;
        if ((long long)r->perturbation_count != (long long)n << r->perturbation_levels)
            return RUGO_ERR_BAD_ARGUMENT;
        if (r->perturbation_count > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
        if (r->perturbation_count > 0 && r->perturbation_points == NULL) return RUGO_ERR_NULL_ARGUMENT;
        for (int i = 0; i < r->perturbation_count; ++i)
            if (!rugo__v2_finite(r->perturbation_points[i])) return RUGO_ERR_NOT_FINITE;
    }
    return RUGO_OK;
}

static void write_roughness(rugo__json_writer* w, const rugo_roughness_desc* r) {
    rugo__json_key(w, "roughness");
    rugo__json_begin_object(w, 0);
    switch (r->kind) {
    case RUGO_ROUGHNESS_PRESET:
        rugo__json_key(w, "preset");
        rugo__json_string(w, rugo_preset_name(r->preset));
        break;
    case RUGO_ROUGHNESS_CONSTANT:
        rugo__json_key(w, "constant");
        rugo__json_number(w, r->constant);
        break;
    case RUGO_ROUGHNESS_RANGES:
        rugo__json_key(w, "ranges");
        rugo__json_begin_array(w, 0);
        for (int i = 0; i < r->range_count; ++i) {
            rugo__json_begin_object(w, RUGO__JSON_INLINE);
            rugo__json_key(w, "from");
            rugo__json_number(w, r->ranges[i].from);
            rugo__json_key(w, "to");
            rugo__json_number(w, r->ranges[i].to);
            rugo__json_key(w, "tolerance");
            rugo__json_number(w, r->ranges[i].tolerance);
            rugo__json_end_object(w);
        }
        rugo__json_end_array(w);
        rugo__json_key(w, "background");
        rugo__json_number(w, r->background);
        break;
    case RUGO_ROUGHNESS_PROFILE:
        rugo__json_key(w, "profile");
        rugo__json_begin_array(w, 0);
        for (int i = 0; i < r->profile_count; ++i) {
            rugo__json_begin_array(w, RUGO__JSON_INLINE);
            rugo__json_number(w, r->profile[i].s);
            rugo__json_number(w, r->profile[i].tolerance);
            rugo__json_end_array(w);
        }
        rugo__json_end_array(w);
        break;
    default:
        rugo__json_key(w, "tolerances");
        rugo__json_begin_array(w, 0);
        for (int i = 0; i < r->tolerance_count; ++i)
            rugo__json_number(w, r->tolerances[i]);
        rugo__json_end_array(w);
        break;
    }
    rugo__json_key(w, "seed");
    rugo__json_integer(w, (long long)r->seed);
    rugo__json_key(w, "q");
    rugo__json_number(w, r->q);
    rugo__json_key(w, "estimator");
    rugo__json_string(w, estimator_name(r->estimator));
    rugo__json_key(w, "friction");
    rugo__json_begin_object(w, RUGO__JSON_INLINE);
    rugo__json_key(w, "alpha");
    rugo__json_number(w, r->friction.alpha);
    rugo__json_key(w, "lambda_min");
    rugo__json_number(w, r->friction.lambda_min);
    rugo__json_key(w, "base");
    rugo__json_number(w, r->friction.base);
    rugo__json_end_object(w);
    rugo__json_key(w, "restitution");
    rugo__json_begin_object(w, RUGO__JSON_INLINE);
    rugo__json_key(w, "epsilon");
    rugo__json_number(w, r->restitution.epsilon);
    rugo__json_key(w, "epsilon_max");
    rugo__json_number(w, r->restitution.epsilon_max);
    rugo__json_end_object(w);
    if (r->has_perturbation) {
        rugo__json_key(w, "perturbation");
        rugo__json_begin_object(w, 0);
        rugo__json_key(w, "method");
        rugo__json_string(w, method_name(r->perturbation_method));
        rugo__json_key(w, "levels");
        rugo__json_integer(w, r->perturbation_levels);
        rugo__json_key(w, "control_points");
        rugo__json_begin_array(w, 0);
        for (int i = 0; i < r->perturbation_count; ++i) {
            rugo__json_begin_array(w, RUGO__JSON_INLINE);
            rugo__json_number(w, r->perturbation_points[i].x);
            rugo__json_number(w, r->perturbation_points[i].y);
            rugo__json_end_array(w);
        }
        rugo__json_end_array(w);
        rugo__json_end_object(w);
    }
    rugo__json_end_object(w);
}

rugo_status rugo_shape_desc_write(const rugo_shape_desc* desc, const rugo_allocator* allocator,
                                  rugo_text* out) {
    if (out != NULL) memset(out, 0, sizeof *out);
    if (desc == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (desc->count < 0) return RUGO_ERR_BAD_ARGUMENT;
    if (desc->count > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
    if (desc->count > 0 && desc->control_points == NULL) return RUGO_ERR_NULL_ARGUMENT;
    const char* filter = rugo_filter_name(desc->filter);
    if (filter == NULL) return RUGO_ERR_BAD_FILTER;
    for (int i = 0; i < desc->count; ++i)
        if (!rugo__v2_finite(desc->control_points[i])) return RUGO_ERR_NOT_FINITE;
    if (desc->has_roughness) {
        rugo_status s = check_roughness(&desc->roughness, desc->count);
        if (s != RUGO_OK) return s;
    }

    /* One point per line: diffs stay readable and parse errors name a useful line. The longest
     * "%.17g" is 24 characters, so a file of RUGO_MAX_CONTROL_POINTS points stays below
     * RUGO_MAX_JSON_BYTES (at most 58 bytes a point) and can be read back. */
    rugo__json_writer w;
    rugo__json_writer_init(&w, allocator, 2);
    rugo__json_begin_object(&w, 0);
    rugo__json_key(&w, "control_points");
    rugo__json_begin_array(&w, 0);
    for (int i = 0; i < desc->count; ++i) {
        rugo__json_begin_array(&w, RUGO__JSON_INLINE);
        rugo__json_number(&w, desc->control_points[i].x);
        rugo__json_number(&w, desc->control_points[i].y);
        rugo__json_end_array(&w);
    }
    rugo__json_end_array(&w);
    rugo__json_key(&w, "filter");
    rugo__json_string(&w, filter);
    if (desc->has_roughness) write_roughness(&w, &desc->roughness);
    rugo__json_end_object(&w);
    rugo__json_raw(&w, "\n", 1);
    rugo_status s = rugo__json_writer_finish(&w, &out->data, &out->length);
    if (s == RUGO_OK) out->allocator = rugo__allocator_or_default(allocator);
    if (s == RUGO_OK && out->length > RUGO_MAX_JSON_BYTES) {
        /* Only a large roughness object gets here: the reader would refuse the text. */
        rugo_text_free(out);
        s = RUGO_ERR_TOO_MANY_POINTS;
    }
    return s;
}
