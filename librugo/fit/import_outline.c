/* Importing an outline at game scale in one call (fit.h: rugo_import_outline): units (a scale, the
 * root viewBox when asked), the fit with its tolerance and error in output units, a crossing check
 * reported in the drawing's coordinates, and recentring on the centroid. Everything else is the
 * public import and fit API; this file only composes it and words the errors for an artist. */
#include "rugo/contour.h"
#include "rugo/fit.h"
#include "rugo/import.h"

#include "core/internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* "RImp" — marks a def that came from rugo_default_import_def. */
#define IMPORT_DEF_COOKIE 0x52496d70

rugo_import_def rugo_default_import_def(void) {
    rugo_import_def d;
    memset(&d, 0, sizeof d);
    d.scale = 1.0;
    d.max_size = RUGO_DEFAULT_IMPORT_MAX_SIZE;
    d.allocator = rugo_default_allocator();
    d.cookie = IMPORT_DEF_COOKIE;
    return d;
}

void rugo_import_result_free(rugo_import_result* result) {
    if (result == NULL) return;
    rugo_outline_fit_free(&result->fit);
    memset(result, 0, sizeof *result);
}

/* rugo__parse_fail's twin: librugo_fit links librugo's public API only (a shared librugo exports no
 * internal function; test shared_build), so it cannot call the core's. */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static rugo_status
import_fail(rugo_parse_error* e, rugo_status st, const char* field, const char* fmt, ...) {
    if (e == NULL) return st;
    memset(e, 0, sizeof *e);
    snprintf(e->path, sizeof e->path, "%s", field);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->message, sizeof e->message, fmt, ap);
    va_end(ap);
    return st;
}

/* 1 if the text's first non-blank character (after a UTF-8 byte order mark) is '<'. */
static int looks_like_xml(const char* text, size_t len) {
    size_t i = 0;
    if (len >= 3 && (unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB &&
        (unsigned char)text[2] == 0xBF)
        i = 3;
    while (i < len && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n'))
        ++i;
    return i < len && text[i] == '<';
}

static rugo_affine scale_map(double s) { return (rugo_affine){s, 0.0, 0.0, s, 0.0, 0.0}; }

/* Inverse of an invertible affine map (the import's maps are scales, flips and translations). */
static rugo_affine affine_inverse(rugo_affine m) {
    const double det = m.a * m.d - m.b * m.c;
    rugo_affine r;
    r.a = m.d / det;
    r.b = -m.b / det;
    r.c = -m.c / det;
    r.d = m.a / det;
    r.e = -(r.a * m.e + r.c * m.f);
    r.f = -(r.b * m.e + r.d * m.f);
    return r;
}

static int is_power_of_two(int n) { return n >= 4 && (n & (n - 1)) == 0; }

/* The samples of the outline in output units (before recentring) and the map from the drawing. */
static rugo_status sample_outline(const rugo_import_def* def, int svg, rugo_outline_samples* s,
                                  rugo_affine* drawing_to_output, rugo_parse_error* error) {
    const rugo_affine flip = {1.0, 0.0, 0.0, -1.0, 0.0, 0.0};
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    sd.allocator = def->allocator;
    rugo_status st;
    if (svg) {
        rugo_affine to_px = rugo_affine_identity();
        if (def->use_viewbox) {
            rugo_svg_viewport vp;
            st = rugo_svg_read_viewport(def->text, def->length, &vp, error);
            if (st != RUGO_OK) return st;
            to_px = vp.user_to_px;
        }
        /* rugo_svg_import_outline maps by sd.transform * flip * (element's transform); the drawing's
         * user units u go to scale * flip * to_px * u, so sd.transform = scale * flip * to_px * flip. */
        *drawing_to_output = rugo_affine_multiply(scale_map(def->scale), rugo_affine_multiply(flip, to_px));
        sd.transform = rugo_affine_multiply(*drawing_to_output, flip);
        sd.sample_count = def->sample_count;
        return rugo_svg_import_outline(def->text, def->length, def->path_id, &sd, s, error);
    }
    rugo_point_list list;
    st = rugo_points_text_parse(def->text, def->length, &def->allocator, &list, error);
    if (st != RUGO_OK) return st;
    const int count = list.count;
    rugo_path poly;
    memset(&poly, 0, sizeof poly);
    st = rugo_path_from_points(list.points, count, &def->allocator, &poly);
    rugo_point_list_free(&list);
    if (st != RUGO_OK)
        return import_fail(error, st, "points",
                           "%d points do not make an outline: %s; give at least 3 distinct points", count,
                           rugo_status_string(st));
    *drawing_to_output = scale_map(def->scale);
    sd.path = &poly;
    sd.transform = *drawing_to_output;
    sd.sample_count = def->sample_count ? def->sample_count : count;
    st = rugo_outline_sample(&sd, s, error);
    rugo_vec2 where;
    if (st == RUGO_ERR_ZERO_AREA && rugo_path_find_crossing(&poly, -1, rugo_affine_identity(), &where))
        st = import_fail(error, RUGO_ERR_SELF_INTERSECTING, "points",
                         "self-intersecting: crosses itself near (%.6g, %.6g) (the points' own units); "
                         "reorder the points into one loop that does not cross",
                         where.x, where.y);
    rugo_path_free(&poly);
    return st;
}

rugo_status rugo_import_outline(const rugo_import_def* def, rugo_import_result* out,
                                rugo_parse_error* error) {
    if (error != NULL) memset(error, 0, sizeof *error);
    if (out != NULL) memset(out, 0, sizeof *out);
    if (def == NULL || out == NULL || def->text == NULL)
        return import_fail(error, RUGO_ERR_NULL_ARGUMENT, "", "a required argument is NULL");
    if (def->cookie != IMPORT_DEF_COOKIE)
        return import_fail(error, RUGO_ERR_BAD_ARGUMENT, "", "def not from rugo_default_import_def");
    if (!(isfinite(def->scale) && def->scale > 0.0))
        return import_fail(error, RUGO_ERR_BAD_ARGUMENT, "scale",
                           "scale is %.17g; it must be a number > 0 (output units per drawing unit, e.g. "
                           "0.01 for 100 px per metre)",
                           def->scale);
    if (!(isfinite(def->max_size) && def->max_size > 0.0))
        return import_fail(error, RUGO_ERR_BAD_ARGUMENT, "max_size",
                           "max_size is %.17g; it must be a number > 0", def->max_size);
    if (!(def->tolerance >= 0.0) || !isfinite(def->tolerance))
        return import_fail(error, RUGO_ERR_BAD_ARGUMENT, "tolerance",
                           "tolerance is %.17g; give a number > 0 in output units, or 0 for 1e-3 of the size",
                           def->tolerance);
    if (def->sample_count < 0)
        return import_fail(error, RUGO_ERR_BAD_ARGUMENT, "sample_count",
                           "sample_count is %d; give 0 or a count >= 3", def->sample_count);
    if (def->control_count != 0 && !is_power_of_two(def->control_count)) {
        int lo = 4;
        while (lo * 2 <= def->control_count && lo < RUGO_MAX_CONTROL_POINTS / 2)
            lo *= 2;
        return import_fail(error, RUGO_ERR_NOT_POWER_OF_TWO, "control_count",
                           "control_count is %d, not a power of two >= 4; use %d or %d (or 0 to search by "
                           "tolerance)",
                           def->control_count, lo, lo < def->control_count ? lo * 2 : 8);
    }
    const int svg = looks_like_xml(def->text, def->length);
    if (!svg && (def->path_id != NULL || def->use_viewbox))
        return import_fail(error, RUGO_ERR_BAD_ARGUMENT, def->path_id != NULL ? "path_id" : "use_viewbox",
                           "%s applies to SVG documents; this text is a point list",
                           def->path_id != NULL ? "path_id" : "use_viewbox");
    rugo_outline_samples s;
    memset(&s, 0, sizeof s);
    rugo_affine to_out = rugo_affine_identity();
    rugo_status st = sample_outline(def, svg, &s, &to_out, error);
    if (st != RUGO_OK) return st;
    rugo_vec2 lo = s.points[0], hi = s.points[0];
    for (int i = 1; i < s.count; ++i) {
        lo.x = fmin(lo.x, s.points[i].x);
        lo.y = fmin(lo.y, s.points[i].y);
        hi.x = fmax(hi.x, s.points[i].x);
        hi.y = fmax(hi.y, s.points[i].y);
    }
    const double size = hypot(hi.x - lo.x, hi.y - lo.y);
    if (!(size <= def->max_size)) {
        rugo_outline_samples_free(&s);
        return import_fail(error, RUGO_ERR_BAD_SIZE, "scale",
                           "the outline is %.6g units across at scale %.6g, more than max_size %.6g: give a "
                           "scale (px per metre) that makes it game-sized, e.g. scale %.3g for 1 unit",
                           size, def->scale, def->max_size, def->scale / size);
    }
    const double tol = def->control_count ? 0.0 : (def->tolerance > 0.0 ? def->tolerance : 1e-3 * size);
    rugo_outline_fit_def fd = rugo_default_outline_fit_def();
    fd.samples = s.points;
    fd.sample_count = s.count;
    fd.control_count = def->control_count;
    fd.tolerance = tol;
    fd.allocator = def->allocator;
    st = rugo_fit_outline(&fd, &out->fit);
    if (st != RUGO_OK) {
        rugo_outline_samples_free(&s);
        return import_fail(error, st, "control_count",
                           "the fit failed: %s; try another control count or more samples",
                           rugo_status_string(st));
    }
    out->from_svg = svg;
    out->sample_count = s.count;
    out->perimeter = s.perimeter;
    out->tolerance = tol;
    out->size = size;
    rugo_outline_samples_free(&s);
    rugo_contour_problem pr;
    st = rugo_contour_check(out->fit.control_points, out->fit.control_count, RUGO_CHECK_ALL, &pr,
                            &def->allocator);
    if (st != RUGO_OK) {
        const rugo_vec2 at = rugo_affine_apply(affine_inverse(to_out), pr.where);
        rugo_import_result_free(out);
        if (st == RUGO_ERR_SELF_INTERSECTING)
            return import_fail(error, st, "control_count",
                               "self-intersecting fit: crosses itself near (%.6g, %.6g) in the drawing's "
                               "coordinates; widen a narrow neck there or give more control points",
                               at.x, at.y);
        return import_fail(error, st, "control_count", "the fitted outline is invalid: %s",
                           rugo_status_string(st));
    }
    if (def->recentre) {
        rugo_contour c = {out->fit.control_points, out->fit.control_count};
        const rugo_vec2 centroid = rugo_contour_mass_properties(c).centroid;
        /* A B-spline moves with its control points: the curve's centroid lands on the origin. */
        for (int i = 0; i < out->fit.control_count; ++i)
            out->fit.control_points[i] = rugo_v2_sub(out->fit.control_points[i], centroid);
        out->offset = rugo_v2(-centroid.x, -centroid.y);
        to_out.e -= centroid.x;
        to_out.f -= centroid.y;
    }
    out->drawing_to_output = to_out;
    out->output_to_drawing = affine_inverse(to_out);
    return RUGO_OK;
}
