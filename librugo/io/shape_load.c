/* One call from a shape file to a shape (rugo_shape_load_file): a JSON shape file built with its
 * roughness, or a baked file loaded as it is, with errors worded for whoever made the asset. */
#include "rugo/baked.h"
#include "rugo/shape_file.h"

#include "core/internal.h"

#include <stdio.h>
#include <string.h>

/* 1 if the file starts with the baked magic; 0 otherwise (unreadable files too: the JSON reader then
 * reports them). */
static int file_is_baked(const char* path) {
    unsigned char head[RUGO_BAKED_MAGIC_SIZE];
    FILE* f = fopen(path, "rb");
    if (f == NULL) return 0;
    const size_t n = fread(head, 1, sizeof head, f);
    fclose(f);
    return rugo_is_baked(head, n);
}

/* The message for an outline rugo_shape_create refused: the field, the value and a way out. */
static rugo_status build_failed(rugo_parse_error* e, rugo_status st, const rugo_shape_desc* d,
                                const rugo_contour_problem* pr) {
    switch (st) {
    case RUGO_ERR_NOT_POWER_OF_TWO: {
        int lo = 4;
        while (lo * 2 <= d->count && lo < RUGO_MAX_CONTROL_POINTS / 2)
            lo *= 2;
        return rugo__parse_fail(
            e, st, "control_points",
            "control_points has %d points, not a power of two; refit the outline with %d or %d "
            "(rugo fit / rugo import --control-points %d)",
            d->count, lo, lo * 2, lo * 2);
    }
    case RUGO_ERR_SELF_INTERSECTING:
        return rugo__parse_fail(
            e, st, "control_points",
            "self-intersecting: segments %d and %d cross near (%.6g, %.6g); fix the outline there",
            pr->segment_a, pr->segment_b, pr->where.x, pr->where.y);
    case RUGO_ERR_NOT_FINITE:
        if (pr->index >= 0 && pr->index < d->count)
            return rugo__parse_fail(e, st, "control_points",
                                    "control_points[%d] is (%.17g, %.17g): not finite", pr->index,
                                    d->control_points[pr->index].x, d->control_points[pr->index].y);
        return rugo__parse_fail(
            e, st, "control_points",
            "coordinates so large that the area overflows (keep them below about 1e150); scale "
            "the outline, e.g. to metres");
    case RUGO_ERR_BAD_SIZE: {
        rugo_vec2 lo, hi;
        rugo_contour_bounds((rugo_contour){d->control_points, d->count}, &lo, &hi);
        return rugo__parse_fail(e, st, "control_points",
                                "the outline is %.6g units across; a shape must be %g to %g",
                                hypot(hi.x - lo.x, hi.y - lo.y), RUGO_SHAPE_MIN_SIZE, RUGO_SHAPE_MAX_SIZE);
    }
    default:
        return rugo__parse_fail(e, st, "", "the shape cannot be built: %s", rugo_status_string(st));
    }
}

rugo_status rugo_shape_load_file(const char* path, const rugo_allocator* allocator, rugo_shape** out,
                                 rugo_parse_error* error) {
    if (error != NULL) memset(error, 0, sizeof *error);
    if (out != NULL) *out = NULL;
    if (path == NULL || out == NULL)
        return rugo__parse_fail(error, RUGO_ERR_NULL_ARGUMENT, "", "a required argument is NULL");
    if (file_is_baked(path)) {
        rugo_baked_error be;
        memset(&be, 0, sizeof be);
        const rugo_status st = rugo_shape_read_baked_file(path, allocator, out, &be);
        if (st != RUGO_OK) {
            rugo__parse_fail(error, st, be.field, "byte %lu: %s", (unsigned long)be.offset, be.message);
            return st;
        }
        return RUGO_OK;
    }
    const rugo_allocator al = rugo__allocator_or_default(allocator);
    rugo_text text;
    rugo_status st = rugo_read_file(path, &al, &text);
    if (st != RUGO_OK)
        return rugo__parse_fail(error, st, "", "cannot read the file: %s", rugo_status_string(st));
    rugo_shape_desc d;
    st = rugo_shape_desc_parse(text.data, text.length, &al, &d, error);
    rugo_text_free(&text);
    if (st != RUGO_OK) return st;
    rugo_real* tol = NULL;
    if (d.has_roughness) {
        tol = (rugo_real*)rugo__alloc_array(&al, (size_t)d.count, sizeof *tol);
        if (tol == NULL) {
            rugo_shape_desc_free(&d);
            return rugo__parse_fail(error, RUGO_ERR_OUT_OF_MEMORY, "", "out of memory");
        }
        st = rugo_roughness_tolerances_on_contour(&d.roughness, (rugo_contour){d.control_points, d.count},
                                                  &al, tol);
        if (st != RUGO_OK) {
            rugo__free(&al, tol);
            rugo_shape_desc_free(&d);
            return rugo__parse_fail(error, st, "roughness", "the roughness does not fit this outline: %s",
                                    rugo_status_string(st));
        }
    }
    const rugo_roughness_desc r = d.has_roughness ? d.roughness : rugo_default_roughness_desc();
    rugo_shape_def def = rugo_default_shape_def();
    def.points = d.control_points;
    def.count = d.count;
    def.filter = d.filter;
    def.tolerances = tol;
    def.q = r.q;
    def.estimator = r.estimator;
    def.friction = r.friction;
    def.restitution = r.restitution;
    def.allocator = al;
    rugo_contour_problem pr;
    memset(&pr, 0, sizeof pr);
    st = rugo_shape_create(&def, out, &pr);
    if (st != RUGO_OK) build_failed(error, st, &d, &pr);
    rugo__free(&al, tol);
    rugo_shape_desc_free(&d);
    return st;
}
