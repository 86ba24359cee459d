/* The rough curved shape: pyramid + tolerances + MOBBtree + mass properties + surface, built once.
 *
 * Besides what shape.h exposes, a shape keeps for the contact queries (query/collide_*.c) an upper bound of
 * the tolerance λ(t) over every segment of every level (rugo_tolerance_bound_on_segment), and per level the
 * largest amount by which that bound exceeds the segment's own λ^j_k. The boxes of level j hold the coarse
 * segment thickened by λ^j_k (mobb.h), but λ(t) interpolates between neighbours (SPEC 6.3) and can exceed
 * λ^j_k inside the segment; queries stopped at a coarse level grow the boxes by that excess so that they
 * never miss a contact within the band. At the finest level the boxes hold β^J >= max λ(t): no excess. */
#include "rugo/shape.h"

#include "core/internal.h"
#include "curve/internal.h" /* rugo__pyramid_from_levels */
#include "shape/internal.h"

#include <string.h>

/* "RUGS": catches defs that did not come from rugo_default_shape_def. */
#define SHAPE_DEF_COOKIE 0x52554753

struct rugo_shape {
    rugo_allocator allocator;
    rugo_pyramid* pyramid;
    rugo_tolerances* tolerances;
    rugo_mobb_tree* tree;
    rugo_mass_properties mass;
    rugo_friction_map friction;
    rugo_restitution restitution;
    int finest, coarsest;
    bool rough;
    bool reversed;
    rugo_real* band_bound; /* level j at offset 2^j - 2^J_min, 2^j values */
    rugo_real band_excess[31];
    rugo_real level_error[31]; /* rugo_shape_level_error's bound per level (+inf where it fails) */
    uint64_t fingerprint;      /* of what a query answers from (rugo__shape_fingerprint) */
    /* A shape loaded from parts (baked.c) keeps λ and β here instead of in a rugo_tolerances, whose
     * constructor would recompute them: own, total, bound, each laid out like band_bound, then the
     * band bounds themselves (band_bound points there: one allocation). */
    rugo_real* tol_block;
};

rugo_shape_def rugo_default_shape_def(void) {
    rugo_shape_def d;
    memset(&d, 0, sizeof d);
    d.points = NULL;
    d.count = 0;
    d.filter = RUGO_FILTER_DEFAULT;
    d.coarsest_level = 0;
    d.tolerances = NULL;
    d.q = RUGO_DEFAULT_Q;
    d.estimator = RUGO_ESTIMATOR_DETAIL;
    d.friction = rugo_default_friction_map();
    d.restitution = rugo_default_restitution();
    d.box_method = RUGO_BOXES_MULTIRES;
    d.check_self_intersection = true;
    d.cookie = SHAPE_DEF_COOKIE;
    return d;
}

static rugo_status check_surface(const rugo_shape_def* def) {
    rugo_status st = rugo_friction_map_check(&def->friction);
    if (st != RUGO_OK) return st;
    return rugo_restitution_check(&def->restitution);
}

void rugo_shape_destroy(rugo_shape* s) {
    if (s == NULL) return;
    rugo_allocator al = s->allocator;
    rugo_mobb_tree_destroy(s->tree);
    rugo_tolerances_destroy(s->tolerances);
    rugo_pyramid_destroy(s->pyramid);
    if (s->tol_block == NULL)
        rugo__free(&al, s->band_bound);
    else
        rugo__free(&al, s->tol_block); /* holds band_bound too */
    rugo__free(&al, s);
}

/* The finest curve's size (diagonal of its bounds) must lie in [RUGO_SHAPE_MIN_SIZE,
 * RUGO_SHAPE_MAX_SIZE]: the polar inertia (at most size^4) then stays within the baked format's value
 * limit, and squared distances (tree queries, narrow phase) stay normal doubles. */
static rugo_status check_size(const rugo_pyramid* p, int finest) {
    rugo_contour fine;
    rugo_pyramid_level(p, finest, &fine);
    rugo_vec2 lo, hi;
    rugo_contour_bounds(fine, &lo, &hi);
    const rugo_real size = hypot(hi.x - lo.x, hi.y - lo.y);
    return size >= RUGO_SHAPE_MIN_SIZE && size <= RUGO_SHAPE_MAX_SIZE ? RUGO_OK : RUGO_ERR_BAD_SIZE;
}

/* The coarsest level from which every level up to the finest is a simple closed curve (rugo_contour_check
 * with the crossing test). Coarse levels of outlines with sharp corners can loop (a corner of four
 * coincident control points curls back at the next level): such a curve has no inside, and queries at
 * it would report overlaps of nearly the body's size between bodies that are apart. The finest level
 * was checked when the pyramid was built. */
static rugo_status simple_coarsest(const rugo_pyramid* p, const rugo_allocator* al, int* out) {
    const int J = rugo_pyramid_finest_level(p), Jmin = rugo_pyramid_coarsest_level(p);
    *out = Jmin;
    for (int j = J - 1; j >= Jmin; --j) {
        rugo_contour c;
        rugo_pyramid_level(p, j, &c);
        const rugo_status st = rugo_contour_check(c.points, c.count, RUGO_CHECK_SELF_INTERSECTION, NULL, al);
        if (st == RUGO_ERR_OUT_OF_MEMORY) return st;
        if (st != RUGO_OK) {
            *out = j + 1;
            break;
        }
    }
    return RUGO_OK;
}

/* FNV-1a over n bytes. */
static uint64_t hash_bytes(uint64_t h, const void* v, size_t n) {
    const unsigned char* b = (const unsigned char*)v;
    for (size_t i = 0; i < n; ++i)
        h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

/* What is derived once the parts are in place: the certified level-of-detail error of every level
 * (queries at RUGO_LOD_AUTO choose by it), and the fingerprint of everything a contact query reads
 * (every level's points and bands, the surface), by which a contact cache knows its shapes. */
static void store_derived(rugo_shape* s) {
    for (int j = s->coarsest; j <= s->finest; ++j) {
        rugo_real e = HUGE_VAL;
        if (rugo_shape_level_error(s, j, NULL, &e) != RUGO_OK || !(e >= 0.0)) e = HUGE_VAL;
        s->level_error[j] = e;
    }
    uint64_t h = 14695981039346656037ull;
    const rugo_real head[] = {(rugo_real)s->coarsest, (rugo_real)s->finest,      (rugo_real)s->reversed,
                              s->friction.alpha,      s->friction.lambda_min,    s->friction.base,
                              s->restitution.epsilon, s->restitution.epsilon_max};
    h = hash_bytes(h, head, sizeof head);
    for (int j = s->coarsest; j <= s->finest; ++j) {
        rugo_contour c;
        rugo_tolerance_level tl;
        rugo_pyramid_level(s->pyramid, j, &c);
        rugo_shape_tolerance_level(s, j, &tl);
        h = hash_bytes(h, c.points, (size_t)c.count * sizeof *c.points);
        h = hash_bytes(h, tl.total, (size_t)tl.count * sizeof *tl.total);
    }
    s->fingerprint = h;
}

uint64_t rugo__shape_fingerprint(const rugo_shape* s) { return s != NULL ? s->fingerprint : 0; }

rugo_status rugo_shape_create(const rugo_shape_def* def, rugo_shape** out, rugo_contour_problem* problem) {
    if (out != NULL) *out = NULL;
    if (def == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (def->cookie != SHAPE_DEF_COOKIE) return RUGO_ERR_BAD_ARGUMENT;
    rugo_status st = check_surface(def);
    if (st != RUGO_OK) return st;

    rugo_allocator al = rugo__allocator_or_default(&def->allocator);
    rugo_shape* s = (rugo_shape*)rugo__alloc_array(&al, 1, sizeof(rugo_shape));
    if (s == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    memset(s, 0, sizeof *s);
    s->allocator = al;
    s->friction = def->friction;
    s->restitution = def->restitution;

    rugo_pyramid_def pd = rugo_default_pyramid_def();
    pd.points = def->points;
    pd.count = def->count;
    pd.filter = def->filter;
    pd.coarsest_level = def->coarsest_level;
    pd.check_self_intersection = def->check_self_intersection;
    pd.allocator = al;
    st = rugo_pyramid_create(&pd, &s->pyramid, problem);
    if (st == RUGO_OK) st = check_size(s->pyramid, rugo_pyramid_finest_level(s->pyramid));
    if (st == RUGO_OK && def->check_self_intersection) {
        /* Levels coarser than the coarsest simple one are dropped: the pyramid is built again down to
         * it (the levels it keeps are the same bits, computed from the finest down). */
        int simple = 0;
        st = simple_coarsest(s->pyramid, &al, &simple);
        if (st == RUGO_OK && simple > rugo_pyramid_coarsest_level(s->pyramid)) {
            rugo_pyramid_destroy(s->pyramid);
            s->pyramid = NULL;
            pd.coarsest_level = simple;
            st = rugo_pyramid_create(&pd, &s->pyramid, problem);
        }
    }
    if (st != RUGO_OK) {
        rugo_shape_destroy(s);
        return st;
    }
    s->finest = rugo_pyramid_finest_level(s->pyramid);
    s->coarsest = rugo_pyramid_coarsest_level(s->pyramid);
    s->reversed = rugo_pyramid_was_reversed(s->pyramid);
    const int n = 1 << s->finest;

    /* λ per finest segment in the pyramid's (counter-clockwise) order: a reversed input maps its
     * segment j to segment n-2-j. Zeros for a smooth shape. */
    rugo_real* lambda = (rugo_real*)rugo__alloc_array(&al, (size_t)n, sizeof(rugo_real));
    if (lambda == NULL) {
        rugo_shape_destroy(s);
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    for (int j = 0; j < n; ++j) {
        const rugo_real v = def->tolerances != NULL ? def->tolerances[j] : 0.0;
        /* A band wider than the largest shape: the boxes and bands would leave the baked format's value
         * range (non-finite and negative values are rugo_tolerances_create's errors). */
        if (v > RUGO_SHAPE_MAX_SIZE) {
            rugo__free(&al, lambda);
            rugo_shape_destroy(s);
            return RUGO_ERR_BAD_SIZE;
        }
        lambda[s->reversed ? rugo__wrap(n - 2 - j, n) : j] = v;
    }
    rugo_tolerance_def td = rugo_default_tolerance_def();
    td.pyramid = s->pyramid;
    td.finest = lambda;
    td.count = n;
    td.q = def->q;
    td.estimator = def->estimator;
    td.allocator = al;
    st = rugo_tolerances_create(&td, &s->tolerances);
    if (st == RUGO_OK)
        for (int j = 0; j < n; ++j)
            s->rough |= lambda[j] > 0.0;
    rugo__free(&al, lambda);
    if (st != RUGO_OK) {
        rugo_shape_destroy(s);
        return st;
    }

    rugo_mobb_tree_def md = rugo_default_mobb_tree_def();
    md.pyramid = s->pyramid;
    md.tolerances = s->tolerances;
    md.method = def->box_method;
    md.allocator = al;
    st = rugo_mobb_tree_create(&md, &s->tree);
    if (st != RUGO_OK) {
        rugo_shape_destroy(s);
        return st;
    }

    rugo_contour fine;
    rugo_pyramid_level(s->pyramid, s->finest, &fine);
    s->mass = rugo_contour_mass_properties(fine);

    const size_t per = ((size_t)1 << (s->finest + 1)) - ((size_t)1 << s->coarsest);
    s->band_bound = (rugo_real*)rugo__alloc_array(&al, per, sizeof(rugo_real));
    if (s->band_bound == NULL) {
        rugo_shape_destroy(s);
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    for (int j = s->coarsest; j <= s->finest; ++j) {
        rugo_tolerance_level tl;
        rugo_tolerances_level(s->tolerances, j, &tl);
        rugo_real* bb = s->band_bound + (((size_t)1 << j) - ((size_t)1 << s->coarsest));
        rugo_real excess = 0.0;
        for (int k = 0; k < tl.count; ++k) {
            bb[k] = rugo_tolerance_bound_on_segment(tl.total, tl.count, k, 0.0);
            if (bb[k] - tl.total[k] > excess) excess = bb[k] - tl.total[k];
        }
        s->band_excess[j] = j == s->finest ? 0.0 : excess;
    }
    store_derived(s);
    *out = s;
    return RUGO_OK;
}

int rugo_shape_finest_level(const rugo_shape* s) { return s ? s->finest : -1; }
int rugo_shape_coarsest_level(const rugo_shape* s) { return s ? s->coarsest : -1; }

rugo_status rugo_shape_level(const rugo_shape* s, int level, rugo_contour* out) {
    if (s == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    return rugo_pyramid_level(s->pyramid, level, out);
}

rugo_status rugo_shape_tolerance_level(const rugo_shape* s, int level, rugo_tolerance_level* out) {
    if (s == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (s->tol_block == NULL) return rugo_tolerances_level(s->tolerances, level, out);
    if (level < s->coarsest || level > s->finest) return RUGO_ERR_BAD_LEVEL;
    const size_t per = ((size_t)1 << (s->finest + 1)) - ((size_t)1 << s->coarsest);
    const size_t o = ((size_t)1 << level) - ((size_t)1 << s->coarsest);
    out->level = level;
    out->count = 1 << level;
    out->own = s->tol_block + o;
    out->total = s->tol_block + per + o;
    out->bound = s->tol_block + 2 * per + o;
    return RUGO_OK;
}

const rugo_mobb_tree* rugo_shape_tree(const rugo_shape* s) { return s ? s->tree : NULL; }
rugo_status rugo_shape_level_error(const rugo_shape* s, int level, rugo_real* per_segment,
                                   rugo_real* max_error) {
    if (max_error != NULL) *max_error = NAN;
    if (s == NULL || max_error == NULL) return RUGO_ERR_NULL_ARGUMENT;
    rugo_contour coarse, finest;
    rugo_tolerance_level tc, tf;
    rugo_status st = rugo_shape_level(s, level, &coarse);
    if (st == RUGO_OK) st = rugo_shape_level(s, s->finest, &finest);
    if (st == RUGO_OK) st = rugo_shape_tolerance_level(s, level, &tc);
    if (st == RUGO_OK) st = rugo_shape_tolerance_level(s, s->finest, &tf);
    if (st != RUGO_OK) return st;
    if (level == s->finest) { /* the same curve and band */
        if (per_segment != NULL)
            for (int k = 0; k < coarse.count; ++k)
                per_segment[k] = 0.0;
        *max_error = 0.0;
        return RUGO_OK;
    }
    return rugo_tolerance_level_error(coarse, tc.total, finest, tf.total, per_segment, max_error);
}

rugo_real rugo__shape_level_error(const rugo_shape* s, int level) {
    if (s == NULL || level < s->coarsest || level > s->finest) return HUGE_VAL;
    return s->level_error[level];
}

int rugo_shape_level_for_error(const rugo_shape* s, rugo_real budget) {
    if (s == NULL) return -1;
    int level = s->finest;
    if (!(budget >= 0.0)) return level;
    while (level > s->coarsest && s->level_error[level - 1] <= budget)
        --level;
    return level;
}

const rugo_pyramid* rugo_shape_pyramid(const rugo_shape* s) { return s ? s->pyramid : NULL; }

rugo_mass_properties rugo_shape_mass(const rugo_shape* s) {
    if (s == NULL) {
        rugo_mass_properties m;
        m.area = NAN;
        m.centroid = rugo_v2(NAN, NAN);
        m.inertia = NAN;
        return m;
    }
    return s->mass;
}

rugo_friction_map rugo_shape_friction_map(const rugo_shape* s) {
    if (s == NULL) {
        rugo_friction_map m;
        m.alpha = NAN;
        m.lambda_min = NAN;
        m.base = NAN;
        return m;
    }
    return s->friction;
}

rugo_restitution rugo_shape_restitution(const rugo_shape* s) {
    if (s == NULL) {
        rugo_restitution r;
        r.epsilon = NAN;
        r.epsilon_max = NAN;
        return r;
    }
    return s->restitution;
}

bool rugo_shape_is_rough(const rugo_shape* s) { return s != NULL && s->rough; }
bool rugo_shape_was_reversed(const rugo_shape* s) { return s != NULL && s->reversed; }

const rugo_real* rugo__shape_band_bounds(const rugo_shape* s, int level) {
    if (s == NULL || level < s->coarsest || level > s->finest) return NULL;
    return s->band_bound + (((size_t)1 << level) - ((size_t)1 << s->coarsest));
}

rugo_real rugo__shape_band_excess(const rugo_shape* s, int level) {
    if (s == NULL || level < s->coarsest || level > s->finest) return 0.0;
    return s->band_excess[level];
}

/* ---- from parts (baked shapes) ------------------------------------------------------------------
 * The pyramid and the tree come from their internal constructors from stored data (multires.c,
 * mobb.c: copies, no analysis, no build); λ and β need no object: they live in tol_block. Every
 * array is decoded once, from the file's bytes into its final place, and the stored values make the
 * loaded shape bit-identical to the baked one on any host. The caller (baked.c) has validated every
 * value; the pyramid's constructor checks the outline. */

rugo_status rugo__shape_create_from_parts(const rugo__shape_parts* parts, rugo_shape** out) {
    if (out != NULL) *out = NULL;
    if (parts == NULL || out == NULL || parts->points == NULL || parts->tolerances == NULL ||
        parts->band_bound == NULL || parts->band_excess == NULL || parts->nodes == NULL ||
        (parts->finest > parts->coarsest && (parts->world == NULL || parts->local == NULL)))
        return RUGO_ERR_NULL_ARGUMENT;
    const int J = parts->finest, Jmin = parts->coarsest;
    if (Jmin < 2 || J < Jmin || J > 30 || (1 << J) > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_BAD_LEVEL;
    rugo_status st = rugo_friction_map_check(&parts->friction);
    if (st == RUGO_OK) st = rugo_restitution_check(&parts->restitution);
    if (st != RUGO_OK) return st;

    rugo_allocator al = rugo__allocator_or_default(&parts->allocator);
    rugo_shape* s = (rugo_shape*)rugo__alloc_array(&al, 1, sizeof(rugo_shape));
    if (s == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    memset(s, 0, sizeof *s);
    s->allocator = al;
    s->friction = parts->friction;
    s->restitution = parts->restitution;
    s->mass = parts->mass;
    s->finest = J;
    s->coarsest = Jmin;
    s->rough = parts->rough;
    s->reversed = parts->reversed;

    const size_t per = ((size_t)1 << (J + 1)) - ((size_t)1 << Jmin); /* entries of levels Jmin..J */
    st = rugo__pyramid_from_levels(parts->filter, J, Jmin, parts->reversed, parts->points, parts->world,
                                   parts->local, &al, &s->pyramid);
    if (st == RUGO_OK) st = check_size(s->pyramid, J);
    if (st == RUGO_OK)
        st =
            rugo__mobb_tree_from_nodes(J, Jmin, parts->box_method, parts->nodes, &parts->root, &al, &s->tree);
    if (st == RUGO_OK) {
        /* own, total, bound and the band bounds: one block of 4 per, freed through tol_block. */
        s->tol_block = (rugo_real*)rugo__alloc_array(&al, 4 * per, sizeof(rugo_real));
        if (s->tol_block == NULL) st = RUGO_ERR_OUT_OF_MEMORY;
    }
    if (st != RUGO_OK) {
        rugo_shape_destroy(s);
        return st;
    }
    rugo__decode_f64_le(s->tol_block, parts->tolerances, 3 * per);
    s->band_bound = s->tol_block + 3 * per;
    rugo__decode_f64_le(s->band_bound, parts->band_bound, per);
    rugo_real excess[31];
    rugo__decode_f64_le(excess, parts->band_excess, (size_t)(J - Jmin + 1));
    for (int j = Jmin; j <= J; ++j)
        s->band_excess[j] = excess[j - Jmin];
    store_derived(s);
    *out = s;
    return RUGO_OK;
}
