/* Shared helpers of the libFuzzer targets: crash loudly (abort) on a broken property, so that
 * libFuzzer records the input. */
#ifndef RUGO_FUZZ_COMMON_H
#define RUGO_FUZZ_COMMON_H

#include "rugo/rugo.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define FUZZ_CHECK(cond)                                                                                     \
    do {                                                                                                     \
        if (!(cond)) {                                                                                       \
            fprintf(stderr, "%s:%d: FUZZ_CHECK(%s) failed\n", __FILE__, __LINE__, #cond);                    \
            abort();                                                                                         \
        }                                                                                                    \
    } while (0)

/* Every output of a query must be finite for finite input; states and counts consistent. */
static inline void fuzz_check_contacts(rugo_status st, const rugo_contact* c, int count, int capacity,
                                       rugo_contact_state state) {
    if (st != RUGO_OK) return;
    FUZZ_CHECK(count >= 0 && count <= capacity);
    FUZZ_CHECK(state == RUGO_STATE_APART || state == RUGO_STATE_CONTACT || state == RUGO_STATE_INTERSECTING);
    if (state == RUGO_STATE_APART) FUZZ_CHECK(count == 0);
    for (int i = 0; i < count; ++i) {
        const rugo_contact* k = &c[i];
        FUZZ_CHECK(isfinite(k->point_a.x) && isfinite(k->point_a.y));
        FUZZ_CHECK(isfinite(k->point_b.x) && isfinite(k->point_b.y));
        FUZZ_CHECK(isfinite(k->normal.x) && isfinite(k->normal.y));
        FUZZ_CHECK(fabs(hypot(k->normal.x, k->normal.y) - 1.0) < 1e-6);
        FUZZ_CHECK(isfinite(k->separation));
        FUZZ_CHECK(isfinite(k->t_a) && isfinite(k->t_b));
        FUZZ_CHECK(k->t_a >= 0.0 && k->t_a <= 1.0);
        FUZZ_CHECK(isfinite(k->tolerance_a) && isfinite(k->tolerance_b));
        FUZZ_CHECK(isfinite(k->friction) && isfinite(k->restitution));
    }
}

/* Queries every fuzz target runs on a shape: against itself (moved), a circle, a segment, a box. */
static inline void fuzz_query_shape(const rugo_shape* s, const rugo_shape* other, rugo_transform xa,
                                    rugo_transform xb) {
    rugo_collide_context* ctx = NULL;
    if (rugo_collide_context_create(NULL, &ctx) != RUGO_OK) return;
    rugo_contact c[16];
    rugo_contact_output o = rugo_contact_output_of(c, 16);
    rugo_contact_query q = rugo_default_contact_query();
    const rugo_mass_properties m = rugo_shape_mass(s);
    FUZZ_CHECK(isfinite(m.area) && isfinite(m.inertia) && isfinite(m.centroid.x) && isfinite(m.centroid.y));
    rugo_status st = rugo_collide_shapes(s, xa, other, xb, &q, ctx, &o);
    fuzz_check_contacts(st, c, o.count, 16, o.state);
    q.lod = -1;
    st = rugo_collide_shapes(s, xa, other, xb, &q, ctx, &o);
    fuzz_check_contacts(st, c, o.count, 16, o.state);
    const rugo_obb* root = rugo_mobb_tree_root(rugo_shape_tree(s));
    const rugo_vec2 centre = rugo_transform_point(xa, root->center);
    const rugo_real r = 0.5 * (root->half[0] + root->half[1]);
    const rugo_transform id = rugo_identity_transform();
    const rugo_primitive circle = rugo_make_circle(centre, r);
    st = rugo_collide_primitive(s, xa, &circle, id, NULL, ctx, &o);
    fuzz_check_contacts(st, c, o.count, 16, o.state);
    const rugo_primitive capsule =
        rugo_make_capsule(rugo_v2(centre.x - 2 * r, centre.y), rugo_v2(centre.x + 2 * r, centre.y), 0.01 * r);
    st = rugo_collide_primitive(s, xa, &capsule, id, NULL, ctx, &o);
    fuzz_check_contacts(st, c, o.count, 16, o.state);
    const rugo_vec2 box[4] = {rugo_v2(centre.x - r, centre.y - r), rugo_v2(centre.x + r, centre.y - r),
                              rugo_v2(centre.x + r, centre.y + r), rugo_v2(centre.x - r, centre.y + r)};
    rugo_primitive square;
    st = rugo_make_polygon(box, 4, 0.0, &square);
    if (st == RUGO_OK) st = rugo_collide_primitive(s, xa, &square, id, NULL, ctx, &o);
    if (st == RUGO_OK) fuzz_check_contacts(st, c, o.count, 16, o.state);
    rugo_collide_context_destroy(ctx);
}

#endif
