/* Fitting an imported outline (fit.h: rugo_fit_outline): rugo_fit_contour at a given or searched
 * control count, counter-clockwise orientation, and errors measured to the closest point of the
 * fitted curve. Part of the Eigen shim target only because rugo_fit_contour is; nothing here uses
 * Eigen directly. No exception can come from this file's own code (no C++ containers); the C
 * functions it calls do not throw. */
#include "rugo/contour.h"
#include "rugo/fit.h"

#include <cfloat>
#include <cmath>
#include <cstring>

#include "core/internal.h"

namespace {

/* "ROFt" — marks a def that came from rugo_default_outline_fit_def. */
constexpr int kOutlineFitCookie = 0x524f4674;

/* Largest power of two <= n (n >= 1). */
int floor_power_of_two(int n) {
    int p = 1;
    while (p <= n / 2)
        p *= 2;
    return p;
}

/* Distances from every sample to the closest point of the curve: their maximum and root mean square
 * (the sum taken relative to the maximum so that it cannot overflow). */
void closest_point_errors(const rugo_vec2* ctrl, int n, const rugo_vec2* samples, int m, double* max_error,
                          double* rms_error, double* scratch) {
    rugo_contour c;
    c.points = ctrl;
    c.count = n;
    double mx = 0.0;
    for (int k = 0; k < m; ++k) {
        scratch[k] = rugo_contour_closest_point(c, samples[k]).distance;
        mx = std::fmax(mx, scratch[k]);
    }
    double sum = 0.0;
    if (mx > 0.0)
        for (int k = 0; k < m; ++k) {
            const double r = scratch[k] / mx;
            sum += r * r;
        }
    *max_error = mx;
    *rms_error = mx > 0.0 ? mx * std::sqrt(sum / m) : 0.0;
}

/* One fit at control count n into a new array (through al), oriented counter-clockwise; the
 * closest-point errors are left to the caller. rugo_fit_contour validates everything about the
 * samples and the count. */
rugo_status fit_once(const rugo_outline_fit_def& def, const rugo_allocator& al, int n,
                     rugo_outline_fit* out) {
    rugo_vec2* ctrl =
        static_cast<rugo_vec2*>(rugo__alloc_array(&al, static_cast<std::size_t>(n), sizeof(rugo_vec2)));
    if (ctrl == nullptr) return RUGO_ERR_OUT_OF_MEMORY;
    rugo_fit_def fd = rugo_default_fit_def();
    fd.samples = def.samples;
    fd.sample_count = def.sample_count;
    fd.control_count = n;
    fd.parameterization = def.parameterization;
    fd.allocator = al;
    rugo_fit_result res;
    const rugo_status st = rugo_fit_contour(&fd, ctrl, &res);
    if (st != RUGO_OK) {
        rugo__free(&al, ctrl);
        return st;
    }
    std::memset(out, 0, sizeof *out);
    out->reversed = rugo_contour_orient_ccw(ctrl, n);
    out->control_points = ctrl;
    out->control_count = n;
    out->max_error_at_parameter = res.max_error;
    out->allocator = al;
    return RUGO_OK;
}

/* The power of two 2^k that brings the samples' largest coordinate into [1/2, 1), or 0 when no scaling is
 * needed: within [2^-200, 2^200] squared distances neither underflow nor overflow. Beyond, e.g. a circle
 * of radius 1e-300, every squared distance underflows to 0 and the fit reported an error of 0 (or
 * failed); scaling by a power of two is exact for normal numbers, so the fit of the scaled samples is
 * the scaled fit. Non-finite samples: 0 (rugo_fit_contour reports them). */
int sample_scale_exponent(const rugo_vec2* samples, int count) {
    double mx = 0.0;
    for (int k = 0; k < count; ++k) {
        if (!std::isfinite(samples[k].x) || !std::isfinite(samples[k].y)) return 0;
        mx = std::fmax(mx, std::fmax(std::fabs(samples[k].x), std::fabs(samples[k].y)));
    }
    if (!(mx > 0.0) || (mx >= std::ldexp(1.0, -200) && mx <= std::ldexp(1.0, 200))) return 0;
    int e = 0;
    (void)std::frexp(mx, &e);
    return -e;
}

rugo_status fit_outline_scaled(const rugo_outline_fit_def* def, rugo_outline_fit* out);

} // namespace

extern "C" {

rugo_outline_fit_def rugo_default_outline_fit_def(void) {
    rugo_outline_fit_def d;
    std::memset(&d, 0, sizeof d);
    d.samples = nullptr;
    d.sample_count = 0;
    d.control_count = 0;
    d.tolerance = 0.0;
    d.max_control_count = RUGO_DEFAULT_MAX_FIT_CONTROL_POINTS;
    d.parameterization = RUGO_PARAM_CHORD_LENGTH;
    d.allocator.alloc = nullptr;
    d.allocator.free = nullptr;
    d.allocator.ctx = nullptr;
    d.cookie = kOutlineFitCookie;
    return d;
}

rugo_status rugo_fit_outline(const rugo_outline_fit_def* def, rugo_outline_fit* out) {
    if (out != nullptr) std::memset(out, 0, sizeof *out);
    if (def == nullptr || out == nullptr) return RUGO_ERR_NULL_ARGUMENT;
    if (def->cookie != kOutlineFitCookie) return RUGO_ERR_BAD_ARGUMENT;
    if (def->samples == nullptr) return RUGO_ERR_NULL_ARGUMENT;
    if (def->sample_count > 0 && def->sample_count <= RUGO_MAX_CONTROL_POINTS &&
        sample_scale_exponent(def->samples, def->sample_count) != 0)
        return fit_outline_scaled(def, out);
    const int automatic = def->control_count == 0;
    int lo = def->control_count, hi = def->control_count;
    if (automatic) {
        if (!(std::isfinite(def->tolerance) && def->tolerance > 0.0)) return RUGO_ERR_BAD_ARGUMENT;
        if (def->max_control_count > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
        if (def->max_control_count < 4) return RUGO_ERR_BAD_ARGUMENT;
        if (!rugo__is_power_of_two(def->max_control_count)) return RUGO_ERR_NOT_POWER_OF_TWO;
        if (def->sample_count < 16) return RUGO_ERR_TOO_FEW_POINTS;
        if (def->sample_count > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
        lo = 4;
        hi = floor_power_of_two(def->sample_count / 4);
        if (hi > def->max_control_count) hi = def->max_control_count;
    } else {
        /* As rugo_fit_contour would say, before a control-point array of that size is allocated. */
        if (lo < 4) return RUGO_ERR_TOO_FEW_POINTS;
        if (lo > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
        if (!rugo__is_power_of_two(lo)) return RUGO_ERR_NOT_POWER_OF_TWO;
    }
    /* Everything else (counts, finiteness, repeated samples) is rugo_fit_contour's to validate; the
     * scratch for the distances is allocated after the first fit has accepted the samples. */
    const rugo_allocator al = rugo__allocator_or_default(&def->allocator);
    double* scratch = nullptr;
    rugo_outline_fit best;
    std::memset(&best, 0, sizeof best);
    rugo_status st = RUGO_OK;
    for (int n = lo;; n *= 2) {
        rugo_outline_fit trial;
        st = fit_once(*def, al, n, &trial);
        if (st != RUGO_OK) break;
        rugo_outline_fit_free(&best);
        best = trial;
        if (scratch == nullptr) {
            scratch = static_cast<double*>(
                rugo__alloc_array(&al, static_cast<std::size_t>(def->sample_count), sizeof(double)));
            if (scratch == nullptr) {
                st = RUGO_ERR_OUT_OF_MEMORY;
                break;
            }
        }
        closest_point_errors(best.control_points, n, def->samples, def->sample_count, &best.max_error,
                             &best.rms_error, scratch);
        if (!automatic || best.max_error <= def->tolerance) break;
        if (n > hi / 2) break; /* the largest count allowed has been tried (and n *= 2 cannot overflow) */
    }
    rugo__free(&al, scratch);
    if (st != RUGO_OK) {
        rugo_outline_fit_free(&best);
        return st;
    }
    best.tolerance_met = !(def->tolerance > 0.0) || best.max_error <= def->tolerance;
    *out = best;
    return RUGO_OK;
}

void rugo_outline_fit_free(rugo_outline_fit* fit) {
    if (fit == nullptr) return;
    rugo__free(&fit->allocator, fit->control_points);
    std::memset(fit, 0, sizeof *fit);
}

} // extern "C"

namespace {

/* rugo_fit_outline on the samples scaled by 2^k (sample_scale_exponent), the result scaled back. */
rugo_status fit_outline_scaled(const rugo_outline_fit_def* def, rugo_outline_fit* out) {
    const int k = sample_scale_exponent(def->samples, def->sample_count);
    const rugo_allocator al = rugo__allocator_or_default(&def->allocator);
    rugo_vec2* scaled = static_cast<rugo_vec2*>(
        rugo__alloc_array(&al, static_cast<std::size_t>(def->sample_count), sizeof(rugo_vec2)));
    if (scaled == nullptr) return RUGO_ERR_OUT_OF_MEMORY;
    for (int i = 0; i < def->sample_count; ++i)
        scaled[i] = rugo_v2(std::ldexp(def->samples[i].x, k), std::ldexp(def->samples[i].y, k));
    rugo_outline_fit_def d = *def;
    d.samples = scaled;
    d.tolerance = std::ldexp(def->tolerance, k);
    /* A tolerance the scaling pushes out of range is clamped (the validation stays the unscaled one's). */
    const int clamped = std::isfinite(def->tolerance) && def->tolerance > 0.0 &&
                        (!std::isfinite(d.tolerance) || !(d.tolerance > 0.0));
    if (clamped) d.tolerance = std::isfinite(d.tolerance) ? DBL_TRUE_MIN : DBL_MAX;
    const rugo_status st = rugo_fit_outline(&d, out);
    rugo__free(&al, scaled);
    if (st != RUGO_OK) return st;
    for (int i = 0; i < out->control_count; ++i)
        out->control_points[i] =
            rugo_v2(std::ldexp(out->control_points[i].x, -k), std::ldexp(out->control_points[i].y, -k));
    out->max_error = std::ldexp(out->max_error, -k);
    out->rms_error = std::ldexp(out->rms_error, -k);
    out->max_error_at_parameter = std::ldexp(out->max_error_at_parameter, -k);
    /* Judged in the scaled problem, where the errors are exact, unless the tolerance was clamped. */
    if (clamped) out->tolerance_met = !(def->tolerance > 0.0) || out->max_error <= def->tolerance;
    return RUGO_OK;
}

} // namespace
