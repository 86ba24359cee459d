/* The broad phase of a query (SPEC 7): the two MOBBtrees descended together, B's boxes moved into
 * A's frame and both grown by the band the query may use, down to the query's levels, keeping the
 * node pairs whose boxes overlap. Also the public rugo_tree_pairs. Separate because it is the one
 * part of a query that sees boxes, not curves. */
#include "query/collide_internal.h"

#include <float.h>
#include <string.h>

/* How many levels node level l of side s is above its stop level (the root, l < 0, one more than the
 * coarsest level); 0 for a fixed box, which never descends. */
static int levels_to_stop(const tree_side* s, int l) {
    if (s->tree == NULL) return 0;
    return l < 0 ? s->stop - s->jmin + 1 : s->stop - l;
}

/* The children of node (l, k): level *cl, indices k0 .. k0 + nk - 1 (the root's are the whole coarsest
 * level). */
static void child_range(const tree_side* s, int l, int k, int* cl, int* k0, int* nk) {
    if (l < 0) {
        *cl = s->jmin;
        *k0 = 0;
        *nk = 1 << s->jmin;
    } else {
        *cl = l + 1;
        *k0 = 2 * k;
        *nk = 2;
    }
}

/* fmax as the C library defines it (a NaN argument gives the other one), without the library call. */
static rugo_real fmax_no_libcall(rugo_real a, rugo_real b) {
    if (a != a) return b;
    if (b != b) return a;
    return a > b ? a : b;
}

/* The box of node (l, k) of side s as tested (tree == NULL: the side's fixed box), into t: B's moved
 * by rel (rugo_obb_transform's operations), grown by the side's slack, with its own terms of the
 * test: projected_radius(b, l) = half[0] |axis[0]·l| + half[1] |axis[1]·l| (mobb.c), same operations. */
static inline void tested_box_make(tested_box* t, const tree_side* s, const rugo_obb* const* base, int l,
                                   int k, int moved, rugo_transform rel) {
    rugo_obb* b = &t->b;
    if (s->tree == NULL) {
        *b = s->box;
    } else {
        const rugo_obb* src = l < 0 ? rugo_mobb_tree_root(s->tree) : base[l] + k;
        if (moved) {
            b->center = rugo_transform_point(rel, src->center);
            b->axis[0] = rugo_rotate(rel.q, src->axis[0]);
            b->axis[1] = rugo_rotate(rel.q, src->axis[1]);
            b->half[0] = src->half[0];
            b->half[1] = src->half[1];
        } else {
            *b = *src;
        }
        if (s->slack > 0.0) {
            b->half[0] += s->slack;
            b->half[1] += s->slack;
        }
    }
    const rugo_real d00 = rugo_v2_dot(b->axis[0], b->axis[0]), d10 = rugo_v2_dot(b->axis[1], b->axis[0]);
    const rugo_real d01 = rugo_v2_dot(b->axis[0], b->axis[1]), d11 = rugo_v2_dot(b->axis[1], b->axis[1]);
    t->self0 = b->half[0] * fabs(d00) + b->half[1] * fabs(d10);
    t->self1 = b->half[0] * fabs(d01) + b->half[1] * fabs(d11);
    t->pos = fmax_no_libcall(fabs(b->center.x), fabs(b->center.y));
}

#define SAT_SLACK (16.0 * DBL_EPSILON) /* mobb.c's SAT_SLACK */

/* rugo_obb_overlap(&a->b, &b->b), the same decision bit for bit: every axis's distance and reach are
 * computed with the same operations (a dot product is the same either way round: its products are
 * exact to swap), the box-only terms come precomputed, and the four axes' cross terms are shared. */
static int tested_boxes_overlap(const tested_box* a, const tested_box* b) {
    const rugo_vec2 t = rugo_v2_sub(b->b.center, a->b.center);
    const rugo_real position = fmax_no_libcall(a->pos, b->pos);
    const rugo_vec2 a0 = a->b.axis[0], a1 = a->b.axis[1], b0 = b->b.axis[0], b1 = b->b.axis[1];
    const rugo_real c00 = fabs(rugo_v2_dot(b0, a0)), c10 = fabs(rugo_v2_dot(b1, a0));
    const rugo_real c01 = fabs(rugo_v2_dot(b0, a1)), c11 = fabs(rugo_v2_dot(b1, a1));
    const rugo_real dist0 = fabs(rugo_v2_dot(t, a0)), dist1 = fabs(rugo_v2_dot(t, a1));
    const rugo_real dist2 = fabs(rugo_v2_dot(t, b0)), dist3 = fabs(rugo_v2_dot(t, b1));
    const rugo_real reach0 = a->self0 + (b->b.half[0] * c00 + b->b.half[1] * c10);
    const rugo_real reach1 = a->self1 + (b->b.half[0] * c01 + b->b.half[1] * c11);
    const rugo_real reach2 = (a->b.half[0] * c00 + a->b.half[1] * c01) + b->self0;
    const rugo_real reach3 = (a->b.half[0] * c10 + a->b.half[1] * c11) + b->self1;
    /* all four axes, one branch (the answer is unpredictable) */
    const int sep = (dist0 - reach0 > SAT_SLACK * (dist0 + reach0 + position)) |
                    (dist1 - reach1 > SAT_SLACK * (dist1 + reach1 + position)) |
                    (dist2 - reach2 > SAT_SLACK * (dist2 + reach2 + position)) |
                    (dist3 - reach3 > SAT_SLACK * (dist3 + reach3 + position));
    return !sep;
}

/* Node pairs at the stop levels whose boxes overlap, into ctx->pairs; B's boxes are moved by rel.
 * Each box is computed (moved, grown, its own terms of the test) once, when its node is pushed, into
 * a pool (ctx->box_pool) that the stack's entries index: an expansion that descends both trees tests
 * 2 x 2 pairs from 2 + 2 boxes. The pool holds the boxes of the open expansions only (a few per tree
 * level), not every box of the query. */
rugo_status rugo__traverse(rugo_collide_context* ctx, const tree_side* A, const tree_side* B,
                           rugo_transform rel, long* tests, size_t* count) {
    size_t top = 0, found = 0, nbox = 0;
    long n_tests = 0;
    /* per-level node arrays (a level's nodes are contiguous: rugo_mobb_tree_node(l, k) = base[l] + k;
     * levels stay below 21, as RUGO_MAX_CONTROL_POINTS is 2^20) */
    const rugo_obb* base_a[32];
    const rugo_obb* base_b[32];
    if (A->tree != NULL)
        for (int l = A->jmin; l <= A->stop && l < 32; ++l)
            base_a[l] = rugo_mobb_tree_node(A->tree, l, 0);
    if (B->tree != NULL)
        for (int l = B->jmin; l <= B->stop && l < 32; ++l)
            base_b[l] = rugo_mobb_tree_node(B->tree, l, 0);
    if (!rugo__scratch_reserve(ctx, &ctx->stack, 64, sizeof(traversal_node)) ||
        !rugo__scratch_reserve(ctx, &ctx->box_pool, 64, sizeof(tested_box)))
        return RUGO_ERR_OUT_OF_MEMORY;
    traversal_node* st = (traversal_node*)ctx->stack.data;
    tested_box* pool = (tested_box*)ctx->box_pool.data;
    st[top].la = -1;
    st[top].ka = 0;
    st[top].lb = -1;
    st[top].kb = 0;
    tested_box_make(&pool[nbox], A, base_a, -1, 0, 0, rel);
    st[top].ia = (int)nbox++;
    tested_box_make(&pool[nbox], B, base_b, -1, 0, 1, rel);
    st[top].ib = (int)nbox++;
    st[top].mark = (int)nbox;
    /* Each pair is tested when its parent is expanded, and only overlapping pairs are pushed: the
     * same tests, and the same pairs in the same order, as testing each when it is popped; the tests
     * of one expansion are independent of each other and the push needs no branch. */
    ++n_tests;
    top += (size_t)tested_boxes_overlap(&pool[st[0].ia], &pool[st[0].ib]);
    while (top > 0) {
        const traversal_node t = st[--top];
        /* The pool is a stack too: the boxes made after t was pushed belong to the expansions of its
         * siblings popped before it, and no node left on the stack refers to them. */
        nbox = (size_t)t.mark;
        const int ha = levels_to_stop(A, t.la), hb = levels_to_stop(B, t.lb);
        if (ha == 0 && hb == 0) {
            if (!rugo__scratch_reserve(ctx, &ctx->pairs, found + 1, sizeof(rugo_node_pair)))
                return RUGO_ERR_OUT_OF_MEMORY;
            rugo_node_pair* p = (rugo_node_pair*)ctx->pairs.data;
            p[found].k_a = t.ka;
            p[found].k_b = t.kb;
            ++found;
            continue;
        }
        int cla = t.la, ka0 = t.ka, nka = 1, clb = t.lb, kb0 = t.kb, nkb = 1;
        if (ha >= hb) child_range(A, t.la, t.ka, &cla, &ka0, &nka);
        if (hb >= ha) child_range(B, t.lb, t.kb, &clb, &kb0, &nkb);
        if (!rugo__scratch_reserve(ctx, &ctx->stack, top + (size_t)(nka * nkb), sizeof(traversal_node)) ||
            !rugo__scratch_reserve(ctx, &ctx->box_pool, nbox + (size_t)nka + (size_t)nkb, sizeof(tested_box)))
            return RUGO_ERR_OUT_OF_MEMORY;
        st = (traversal_node*)ctx->stack.data;
        pool = (tested_box*)ctx->box_pool.data;
        /* children's boxes: B's at ib0 + j, A's at ia0 + i (or the parent's box where a side stays) */
        const size_t ib0 = nbox;
        if (hb >= ha) {
            for (int j = 0; j < nkb; ++j)
                tested_box_make(&pool[nbox++], B, base_b, clb, kb0 + j, 1, rel);
        }
        const size_t ia0 = nbox;
        if (ha >= hb) {
            for (int i = 0; i < nka; ++i)
                tested_box_make(&pool[nbox++], A, base_a, cla, ka0 + i, 0, rel);
        }
        /* Pushed in reverse so that pairs come out in increasing order. */
        for (int i = nka - 1; i >= 0; --i) {
            const int ia = ha >= hb ? (int)ia0 + i : t.ia;
            for (int j = nkb - 1; j >= 0; --j) {
                st[top].la = cla;
                st[top].ka = ka0 + i;
                st[top].lb = clb;
                st[top].kb = kb0 + j;
                st[top].ia = ia;
                st[top].ib = hb >= ha ? (int)ib0 + j : t.ib;
                st[top].mark = (int)nbox;
                top += (size_t)tested_boxes_overlap(&pool[ia], &pool[st[top].ib]);
            }
        }
        n_tests += (long)nka * (long)nkb;
    }
    *tests += n_tests;
    *count = found;
    return RUGO_OK;
}

rugo_status rugo_tree_pairs(const rugo_mobb_tree* a, rugo_transform xa, int level_a, const rugo_mobb_tree* b,
                            rugo_transform xb, int level_b, rugo_collide_context* ctx, rugo_node_pair* pairs,
                            int capacity, int* count, long* box_tests) {
    if (count != NULL) *count = 0;
    if (box_tests != NULL) *box_tests = 0;
    if (ctx == NULL || a == NULL || b == NULL || count == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (capacity < 0) return RUGO_ERR_BAD_ARGUMENT;
    if (capacity > 0 && pairs == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (!rugo__transform_finite(xa) || !rugo__transform_finite(xb)) return RUGO_ERR_NOT_FINITE;
    tree_side A, B;
    memset(&A, 0, sizeof A);
    memset(&B, 0, sizeof B);
    A.tree = a;
    A.jmin = rugo_mobb_tree_coarsest_level(a);
    A.stop = level_a < A.jmin
                 ? A.jmin
                 : (level_a > rugo_mobb_tree_finest_level(a) ? rugo_mobb_tree_finest_level(a) : level_a);
    B.tree = b;
    B.jmin = rugo_mobb_tree_coarsest_level(b);
    B.stop = level_b < B.jmin
                 ? B.jmin
                 : (level_b > rugo_mobb_tree_finest_level(b) ? rugo_mobb_tree_finest_level(b) : level_b);
    long tests = 0;
    size_t n = 0;
    rugo_status st = rugo__traverse(ctx, &A, &B, rugo__relative_transform(xa, xb), &tests, &n);
    if (st != RUGO_OK) return st;
    const rugo_node_pair* p = (const rugo_node_pair*)ctx->pairs.data;
    for (size_t i = 0; i < n && i < (size_t)capacity; ++i)
        pairs[i] = p[i];
    *count = n > (size_t)INT32_MAX ? INT32_MAX : (int)n;
    if (box_tests != NULL) *box_tests = tests;
    return RUGO_OK;
}
