/* Private to the contact queries (the collide_*.c files of librugo/query): the types their stages share,
 * the layout of the scratch context, and the small geometry every stage uses. Not installed.
 * docs/contacts.md states the semantics of a query; this comment says how they are computed.
 *
 * Frame. Everything is computed in A's local frame: B's boxes and pieces are moved there by the
 * relative transform xa^-1 xb (exact up to one rounding per coordinate even when both poses are far
 * from the origin), and every narrow-phase call gets its two pieces shifted so that A's piece starts
 * at the origin. Separations and normals are computed there and only the final points and normals
 * are moved to world coordinates.
 *
 * Shape against shape (collide_shapes.c):
 *  1. Tree traversal (SPEC 7) from the two roots down to the query's levels, B's boxes moved into A's
 *     frame. Boxes are grown by the band the query can use beyond what the boxes hold (an override
 *     tolerance, or the excess of λ(t) over λ^j_k at coarse levels, see shape.c), so that no pair of
 *     segments within the band is pruned.
 *  2. First narrow pass on every surviving segment pair, cutoff = the bounds of λ(t) on both segments
 *     (or twice the override): all crossings, and all stationary pairs within the band.
 *  3. Results in global parameters; a point found by two segment pairs (a joint: t = 1 belongs to the
 *     next segment; or a point-like segment) is kept once.
 *  4. Crossings (kind != 0) => INTERSECTING. Overlap regions are traced as the boundary of A ∩ B:
 *     sorted along A and along B, each crossing starts an arc of A inside B or an arc of B inside A
 *     (from the crossing's orientation; if those are inconsistent, e.g. an odd count after a
 *     near-tangent crossing, from containment tests of arc midpoints), and following those arcs from
 *     crossing to crossing closes each region. A second narrow pass over the segments of each region,
 *     cutoff = the region's size, finds the stationary pairs (pa on an A-arc of the region, pb on a
 *     B-arc of it) whose connecting vector is normal to both curves and points out of A at pa and into
 *     B at pb — penetration pairs, typically saddles of the distance; the one with the largest
 *     distance is the region's contact. Pairs of segments whose tangent cones cannot be anti-parallel
 *     are skipped (a penetration pair has anti-parallel tangents). If a region has no such pair
 *     (tiny or degenerate overlaps), the point of its arcs farthest from the other curve (samples +
 *     closest point) is used instead. Local minima within the band outside every region are reported
 *     too, as their own regions.
 *  5. No crossing, but one curve inside the other (a point of one inside the other, decided through
 *     the tree: "Containment through the tree" in collide_levels.c): INTERSECTING, one contact: the
 *     closest pair of the two curves gives the way out (the outer curve's outward normal there); the
 *     inner body's support point against that normal gives the depth.
 *  6. Otherwise each local minimum of the distance within λ_A(t_A) + λ_B(t_B), with the two curves
 *     facing each other, is a contact (CONTACT), or none (APART).
 *
 * Primitives (collide_primitive.c; B = a convex core K — a point, a segment or a polygon — grown by a
 * radius R) follow the same plan with B's boundary made of straight edges (offset by R) and vertex arcs
 * (radius R); the narrow phase runs the piece against each edge (rugo__narrow_line) and each vertex
 * (rugo__narrow_point), crossings with vertex arcs are bracketed between the stationary points of the
 * distance to the vertex. An edge (a segment with R = 0) has no inside: each piece of it inside A gets
 * one contact at its point deepest inside A (sampled, refined by golden section).
 *
 * The files, in the order a query uses them:
 *   collide_context.c           the scratch buffers a context keeps between queries
 *   collide_output.c            the query's defaults and checks; contacts: ids, filling, ordering
 *   collide_levels.c            a shape as one side of a query: its level, bands, containment
 *   collide_geometry.c          normals, corners and tangent cones of the curves
 *   collide_traverse.c          the simultaneous descent of the two MOBBtrees (SPEC 7)
 *   collide_hits.c              the narrow phase's results in global parameters, without duplicates
 *   collide_regions.c           overlap regions traced through the crossings
 *   collide_pieces.c            B's Bezier pieces in A's frame, computed once per query
 *   collide_shapes.c            shape against shape: the plan above, stage by stage
 *   collide_primitive.c         shape against a primitive: the same stages
 *   collide_primitive_boundary.c, collide_primitive_narrow.c
 *                               a primitive's boundary; a piece against its edges and vertex arcs
 *   collide_below_resolution.c  overlaps too shallow for the crossings to resolve
 *   collide_manifold.c          a query's contacts reduced to a few per region */
#ifndef RUGO_QUERY_COLLIDE_INTERNAL_H
#define RUGO_QUERY_COLLIDE_INTERNAL_H

#include "rugo/collide.h"

#include "core/array.h"
#include "core/internal.h"
#include "query/narrow.h"

#include <stdint.h>

/* Relative tolerances (times the larger shape's size). */
#define SAME_POINT 1e-9         /* two results closer than this are the same point */
#define NORMAL_FROM_POINTS 1e-7 /* below this distance the normal comes from A's curve, not pb - pa */
#define OVERLAP_NEAR 1e-6       /* points this close belong to one overlap below the resolution */
#define CUTOFF_PAD 1e-12        /* pad of narrow-phase cutoffs: round-off must not hide a contact */
#define FALLBACK_SAMPLES 16     /* samples per segment of a region's arcs when no penetration pair exists */

#define PI_VALUE 3.14159265358979323846

/* ---------------------------------------------------------------------------------------------------
 * Small geometry (inline here; the rest in collide_geometry.c). */

static inline rugo_vec2 rugo__lerp2(rugo_vec2 a, rugo_vec2 b, rugo_real t) {
    return rugo_v2(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
}

static inline rugo_vec2 rugo__bezier_point(const rugo_vec2 b[4], rugo_real t) {
    const rugo_real s = 1.0 - t;
    const rugo_real w0 = s * s * s, w1 = 3.0 * s * s * t, w2 = 3.0 * s * t * t, w3 = t * t * t;
    return rugo_v2(w0 * b[0].x + w1 * b[1].x + w2 * b[2].x + w3 * b[3].x,
                   w0 * b[0].y + w1 * b[1].y + w2 * b[2].y + w3 * b[3].y);
}

/* v / l for l = rugo__v2_length(v) computed by the caller (0 for l = 0). */
static inline rugo_vec2 rugo__v2_unit_len(rugo_vec2 v, rugo_real l) {
    return l > 0.0 ? rugo_v2(v.x / l, v.y / l) : rugo_v2(0.0, 0.0);
}

static inline rugo_vec2 rugo__v2_unit(rugo_vec2 v) { return rugo__v2_unit_len(v, rugo__v2_length(v)); }

/* xa^-1 xb: B's frame into A's. */
static inline rugo_transform rugo__relative_transform(rugo_transform xa, rugo_transform xb) {
    rugo_transform r;
    r.q.c = xa.q.c * xb.q.c + xa.q.s * xb.q.s;
    r.q.s = xa.q.c * xb.q.s - xa.q.s * xb.q.c;
    r.p = rugo_inv_rotate(xa.q, rugo_v2_sub(xb.p, xa.p));
    return r;
}

static inline int rugo__transform_finite(rugo_transform t) {
    return isfinite(t.p.x) && isfinite(t.p.y) && isfinite(t.q.c) && isfinite(t.q.s);
}

/* The diagonal of a box: the size that the relative tolerances scale. */
static inline rugo_real rugo__box_size(const rugo_obb* b) {
    return b ? 2.0 * hypot(b->half[0], b->half[1]) : 0.0;
}

static inline void rugo__bezier_bounds(const rugo_vec2 b[4], rugo_vec2* lo, rugo_vec2* hi) {
    *lo = *hi = b[0];
    for (int i = 1; i < 4; ++i) {
        lo->x = fmin(lo->x, b[i].x);
        lo->y = fmin(lo->y, b[i].y);
        hi->x = fmax(hi->x, b[i].x);
        hi->y = fmax(hi->y, b[i].y);
    }
}

/* First derivative of a segment at t from rugo_contour_derivative_coefficients' v, w, r. */
static inline rugo_vec2 rugo__first_derivative(rugo_vec2 v, rugo_vec2 w, rugo_vec2 r, rugo_real t) {
    return rugo_v2(0.5 * ((v.x * t + w.x) * t + r.x), 0.5 * ((v.y * t + w.y) * t + r.y));
}

/* The cone of tangent directions of a Bezier piece: unit centre and half-angle (> pi: unknown). */
void rugo__tangent_cone(const rugo_vec2 b[4], rugo_vec2* centre, rugo_real* half);
/* Outward normal of a counter-clockwise curve at (seg, t); at a zero-speed point, a chord's. */
rugo_vec2 rugo__curve_normal(rugo_contour c, int seg, rugo_real t);
/* At a zero-speed point (a sharp corner), 1 and the normals just before and after it; 0 elsewhere. */
int rugo__corner_normals(rugo_contour c, int seg, rugo_real t, rugo_vec2* n_in, rugo_vec2* n_out);
/* Does direction d leave the curve at (seg, t) on its outward side (at a corner: in its normal cone)?
 * rot turns the curve's frame into the query's. */
int rugo__faces_outward(rugo_contour c, int seg, rugo_real t, rugo_vec2 d, rugo_rot rot);
/* A sharp corner of c at one of segment seg's joints within `near` of x: 1 and its chord normal. */
int rugo__corner_near(rugo_contour c, int seg, rugo_vec2 x, rugo_real near, rugo_vec2* n);

/* ---------------------------------------------------------------------------------------------------
 * Hits (collide_hits.c). */

/* A crossing or a stationary pair found by the narrow phase, in global parameters. */
typedef struct hit {
    int sa, sb;       /* segment of A, segment of B (primitives: feature of B's boundary) */
    rugo_real ta, tb; /* in [0, 1) */
    rugo_real ua, ub; /* sa + ta, sb + tb */
    rugo_vec2 pa, pb; /* A's frame */
    rugo_vec2 nb;     /* primitives: B's outward normal at pb (zero: a corner, use its cone) */
    rugo_real distance;
    int kind;
    int src;        /* the narrow call that found it */
    int vertex;     /* primitives: the vertex of a corner candidate, else -1 */
    int dead;       /* removed as a duplicate */
    int coincident; /* found by a narrow call whose pieces coincide (infinitely many roots) */
    int flat;       /* a minimum on a stretch flat to the query's resolution (rugo__pair_point.flat) */
} hit;

/* Appends *h to the hit buffer b (*n used); 0 if out of memory. */
int rugo__push_hit(rugo_collide_context* ctx, rugo__array* b, size_t* n, const hit* h);
/* Segment and parameter with t = 1 moved to the next segment (t below 0 or NaN: 0), seg wrapped to n. */
void rugo__normalise_segment_param(int* seg, rugo_real* t, int n);
/* qsort order of hits: along A, then along B, then by narrow call and kind. */
int rugo__hit_cmp(const void* pa, const void* pb);
/* A stationary pair that may be the closest pair of two curves (RUGO__MINIMUM or RUGO__END_MINIMUM). */
int rugo__is_minimum_candidate(int kind);
/* Sorts the n hits along A and marks as dead the repeats of points found by other narrow calls
 * (within eps; stationary: the stationary pairs' rules of kinds). */
void rugo__dedupe_hits(hit* h, size_t n, rugo_real period_a, rugo_real eps, int stationary);

/* ---------------------------------------------------------------------------------------------------
 * The scratch context (collide_context.c) and what its buffers hold. */

/* A node pair on the traversal's stack. */
typedef struct traversal_node {
    int la, ka, lb, kb; /* level -1: the root */
    int ia, ib;         /* their boxes as tested, in the box pool (see rugo__traverse) */
    int mark;           /* the pool's size when this node was pushed */
} traversal_node;

/* A box as tested, with the parts of rugo_obb_overlap's separating-axis test that depend on it alone

 * (mobb.c): its projected radius on its own two axes and its largest centre coordinate. */
typedef struct tested_box {
    rugo_obb b;
    rugo_real self0, self1; /* projected_radius(b, axis[0]), projected_radius(b, axis[1]) */
    rugo_real pos;          /* fmax(|centre.x|, |centre.y|) */
} tested_box;

/* A segment of an overlap region with what its second narrow pass needs. */
typedef struct seginfo {
    int k;
    rugo_vec2 b[4];   /* Bezier points in A's frame */
    rugo_vec2 lo, hi; /* their bounds */
    rugo_vec2 cone;   /* unit centre of the tangent directions */
    rugo_real half;   /* half-angle of the tangent cone (>= pi: unknown) */
} seginfo;

struct rugo_collide_context {
    rugo_allocator al;
    rugo__array stack;    /* traversal_node */
    rugo__array box_pool; /* tested_box: the box pool of a traversal */
    rugo__array pairs;    /* rugo_node_pair */
    rugo__array xs;       /* hit: crossings */
    rugo__array ss;       /* hit: stationary pairs of the first pass */
    rugo__array ss2;      /* hit: stationary pairs of later passes */
    rugo__array ints;     /* int: region bookkeeping, 8 per crossing */
    rugo__array marks;    /* unsigned char: segment marks of A then B */
    rugo__array segs;     /* seginfo: segments of one region */
    rugo__array out;      /* rugo_contact: contacts before truncation */
    rugo__array ptab;     /* rugo_vec2[4]: Bezier pieces of a query's segments, A's then B's (shape_pair) */
    rugo__array pstamp;   /* uint32_t: the query (epoch) whose piece a ptab entry holds */
    size_t pstamp_zeroed; /* pstamp entries initialised */
    uint32_t epoch;
};

/* Room for `need` elements of `elem` bytes in one of the context's buffers; 0 if out of memory. Every
 * buffer starts at 64 elements and doubles, so that a context reserved once never allocates again. */
static inline int rugo__scratch_reserve(rugo_collide_context* c, rugo__array* b, size_t need, size_t elem) {
    return rugo__array_reserve(b, &c->al, need, elem, 64) == RUGO_OK;
}

/* ---------------------------------------------------------------------------------------------------
 * A shape at the query's level (collide_levels.c). */

typedef struct query_side {
    const rugo_shape* shape;
    const rugo_mobb_tree* tree;
    rugo_contour curve; /* level curve, local frame */
    int level, n, jmin;
    const rugo_real* lambda; /* total λ of the level */
    const rugo_real* band;   /* upper bounds of λ(t) per segment */
    rugo_real slack;         /* growth of the boxes */
} query_side;

/* The absolute level the query's level of detail gives the shape (rugo_contact_query.lod, checked),
 * or a coarser one whose certified error, added to that level's, is at most level_budget (a share of
 * the query's resolution; 0: none). */
int rugo__query_level(const rugo_shape* shape, const rugo_contact_query* q, rugo_real level_budget);
/* s for shape at absolute `level` (J_min..J); override >= 0: the query's tolerance instead of the
 * shape's. */
void rugo__query_side_init(query_side* s, const rugo_shape* shape, int level, rugo_real override);
/* λ at (seg, t) of the side's level, or the override. */
rugo_real rugo__query_side_tolerance(const query_side* s, int seg, rugo_real t, rugo_real override);
/* rugo_contour_contains on the side's curve, through the tree. */
int rugo__query_side_contains(const query_side* s, rugo_vec2 p);
/* rugo_contour_closest_point on the side's curve, through the tree. */
rugo_curve_point rugo__query_side_closest(const query_side* s, rugo_vec2 p);

/* ---------------------------------------------------------------------------------------------------
 * Tree traversal (collide_traverse.c). */

typedef struct tree_side {
    const rugo_mobb_tree* tree; /* NULL: a single fixed box (a primitive) */
    int jmin, stop;
    rugo_real slack;
    rugo_obb box;
} tree_side;

/* Node pairs at the stop levels of A and B whose boxes (B's moved by rel) overlap, in increasing
 * order, into ctx->pairs (*count of them); *tests grows by the box tests made. */
rugo_status rugo__traverse(rugo_collide_context* ctx, const tree_side* A, const tree_side* B,
                           rugo_transform rel, long* tests, size_t* count);

/* ---------------------------------------------------------------------------------------------------
 * Overlap regions (collide_regions.c). */

/* The geometry a region needs of the two boundaries, for shapes and primitives alike. */
typedef struct region_io {
    void* user;
    rugo_real period_a, period_b;
    rugo_vec2 (*point_a)(void* user, rugo_real u); /* A's frame */
    rugo_vec2 (*point_b)(void* user, rugo_real w);
    int (*inside_b)(void* user, rugo_vec2 p);
    int (*inside_a)(void* user, rugo_vec2 p);
} region_io;

typedef struct regions {
    int m;        /* crossings */
    const hit* x; /* sorted by ua */
    int* order_b; /* crossing indices sorted by ub */
    int* pos_b;   /* rank of each crossing in order_b */
    int* a_in;    /* A's arc from crossing i to the next along A lies inside B */
    int* b_in;    /* B's arc from crossing i to the next along B lies inside A */
    int* reg_a;   /* region of A's arc i, or -1 */
    int* reg_b;   /* region of B's arc i, or -1 */
    int count;    /* regions */
    rugo_real period_a, period_b;
} regions;

/* The crossing after crossing i along A, and along B. */
static inline int rugo__next_along_a(const regions* r, int i) { return (i + 1) % r->m; }
static inline int rugo__next_along_b(const regions* r, int i) { return r->order_b[(r->pos_b[i] + 1) % r->m]; }

/* Parameter span of the arc from `from` to `to` along a curve of the given period (a single crossing:
 * the whole curve). */
static inline rugo_real rugo__param_arc(rugo_real from, rugo_real to, rugo_real period, int single) {
    rugo_real d = to - from;
    while (d < 0.0)
        d += period;
    if (single || d == 0.0) d = period;
    return d;
}

/* u wrapped into [0, period). */
static inline rugo_real rugo__wrap_param(rugo_real u, rugo_real period) {
    rugo_real r = fmod(u, period);
    if (r < 0.0) r += period;
    if (r >= period) r = 0.0;
    return r;
}

/* Builds the regions of the m crossings x (sorted by ua) into r; ints must hold 6 m ints. */
void rugo__build_regions(regions* r, const hit* x, int m, int* ints, const region_io* io);
/* Region of a pair (ua on A, ub on B) if both lie on arcs of the same region, else -1. */
int rugo__region_of_pair(const regions* r, rugo_real ua, rugo_real ub);
/* Whether a point of A or of B lies on an arc of some region. */
int rugo__in_any_region(const regions* r, rugo_real ua, rugo_real ub);

/* ---------------------------------------------------------------------------------------------------
 * The query and its contacts (collide_output.c). */

typedef struct contact_out {
    rugo_collide_context* ctx;
    size_t n;
    rugo_transform xa;
    const rugo_contact_query* q;
    const query_side* A;
    const query_side* B; /* NULL for primitives */
    rugo_real override;
} contact_out;

/* How a query's resolution δ is shared: each shape may take a coarser level whose error is within
 * δ/8 of the chosen one's (the two together move a band-adjusted distance by at most δ/4), the narrow
 * phase runs at δ/2, and a cached answer is given back while the shapes have moved relative to each
 * other by at most δ/4 (contact_cache.c), so every separation stays within δ. */
#define RESOLUTION_LEVEL_SHARE 0.125
#define RESOLUTION_NARROW_SHARE 0.5
#define RESOLUTION_MOTION_SHARE 0.25

/* The query's resolution δ for shapes of the given sizes (RUGO_RESOLUTION_AUTO: 1e-4 of the smaller). */
static inline rugo_real rugo__query_resolution(const rugo_contact_query* q, rugo_real size_a,
                                               rugo_real size_b) {
    if (q->resolution != RUGO_RESOLUTION_AUTO) return q->resolution;
    return 1e-4 * (size_a < size_b ? size_a : size_b);
}
/* RUGO_OK, or what is wrong with the query or the caller's room for contacts. */
rugo_status rugo__check_query(const rugo_contact_query* q, const rugo_contact_output* out);
/* Adds a contact from a pair in A's frame: pa on A (segment sa at ta), pb on B, n unit from A to B.
 * id_b: B's segment, or the primitive's feature, for the id. 0 if out of memory. */
int rugo__emit_contact(contact_out* o, int sa, rugo_real ta, int sb, rugo_real tb, rugo_vec2 pa, rugo_vec2 pb,
                       rugo_vec2 n, int region, int type, int index, int id_b);
/* Orders the contacts and copies what fits into the caller's array. */
void rugo__finish_contacts(contact_out* o, rugo_contact* contacts, int capacity, int* count,
                           rugo_query_stats* stats);

/* ---------------------------------------------------------------------------------------------------
 * Two shapes (collide_shapes.c; their pieces: collide_pieces.c). */

typedef struct shape_pair {
    const query_side* A;
    const query_side* B;
    rugo_transform rel; /* B's frame -> A's frame */
    rugo_real scale;
    rugo_query_stats* stats;
    int src;
    int coincident;     /* some pieces coincide */
    rugo_real margin;   /* query margin: minima up to band + margin count */
    rugo_real delta;    /* the query's resolution (0: round-off, the certified narrow phase) */
    rugo_real override; /* the query's constant band (>= 0), or -1 */
    int thesis_rule;    /* RUGO_CONTACT_THESIS: minima of the distance, not of the band-adjusted distance */
    /* Bezier pieces computed at most once per query and segment (NULL: not set up, see piece table) */
    rugo_vec2 (*tab)[4]; /* A's n pieces, then B's n (in A's frame) */
    uint32_t* stamp;     /* entry valid iff stamp == epoch */
    uint32_t epoch;
} shape_pair;

/* The Bezier pieces of a query's segment pairs, each computed once: the pairs come sorted by A's
 * segment, with B's segments of a small range repeating for each (direct-mapped by the low bits). */
enum { PIECE_CACHE = 16 };
typedef struct piece_cache {
    int ka;
    rugo_vec2 fa[4];
    int kb[PIECE_CACHE];
    rugo_vec2 gb[PIECE_CACHE][4];
} piece_cache;

/* B's segment k as a Bezier piece in A's frame. */
void rugo__piece_of_b(const shape_pair* g, int k, rugo_vec2 out[4]);
/* Sets up g's piece table in ctx for the query (A's and B's segments); 0 if out of memory. */
int rugo__piece_table_setup(rugo_collide_context* ctx, shape_pair* g);
/* Pieces from the query's table (g->tab set up). */
const rugo_vec2* rugo__table_piece_a(const shape_pair* g, int k);
const rugo_vec2* rugo__table_piece_b(const shape_pair* g, int k);
/* Pieces from the table, or without one from the cache pc (rugo__piece_cache_init first). */
void rugo__piece_cache_init(piece_cache* pc);
const rugo_vec2* rugo__cached_piece_a(piece_cache* pc, const shape_pair* g, int k);
const rugo_vec2* rugo__cached_piece_b(piece_cache* pc, const shape_pair* g, int k);

/* Extreme point of A's curve (of_b = 0) or B's (of_b = 1, in A's frame) along direction d: the point
 * maximising p·d (sign = +1) or minimising it (sign = -1); its segment and parameter too. */
rugo_vec2 rugo__support_point(const shape_pair* g, int of_b, rugo_vec2 d, int sign, int* seg_out,
                              rugo_real* t_out);

/* ---------------------------------------------------------------------------------------------------
 * A shape and a primitive (collide_primitive.c, collide_primitive_boundary.c,
 * collide_primitive_narrow.c): B = convex core K (a point, a segment, a convex polygon) grown by a
 * radius R. */

typedef struct primitive {
    int V;             /* 1 circle, 2 segment (capsule), 3..8 polygon */
    rugo_vec2 v[8];    /* A's frame */
    rugo_vec2 m[8];    /* outward unit normal of edge i (v_i -> v_{i+1}) */
    rugo_real arc0[8]; /* vertex arc i: directions from angle arc0 over span (from m_{i-1} to m_i) */
    rugo_real span[8];
    rugo_real R;
    /* period of the boundary parameter: 1 (circle) or 2V (arc i = [2i, 2i+1), edge i = [2i+1, 2i+2)) */
    rugo_real period;
    rugo_vec2 lo, hi; /* bounds of B */
} primitive;

typedef struct primitive_pair {
    const query_side* A;
    const primitive* P;
    rugo_real scale;
    rugo_query_stats* stats;
    int src;
} primitive_pair;

/* P (vertices V, radius R, in world coordinates) into A's frame, with its normals, arcs and bounds. */
void rugo__primitive_into_frame(primitive* P, rugo_transform xa);
/* Signed distance of p to B (negative inside); q, nq (may be NULL): nearest boundary point, its normal. */
rugo_real rugo__primitive_signed_distance(const primitive* P, rugo_vec2 p, rugo_vec2* q, rugo_vec2* nq);
/* Boundary parameter of the point of vertex arc i in direction u, or -1 if u is outside the arc. */
rugo_real rugo__primitive_arc_param(const primitive* P, int i, rugo_vec2 u);
/* The boundary point at parameter w. */
rugo_vec2 rugo__primitive_point(const primitive* P, rugo_real w);
/* The point of B maximising p·dir. */
rugo_vec2 rugo__primitive_support(const primitive* P, rugo_vec2 dir);
/* Outward normal of B's boundary at or next to p (an edge, R = 0, faces both ways: the caller orients). */
rugo_vec2 rugo__primitive_normal_at(const primitive* P, rugo_vec2 p);
/* Whether n (from A to B) fits B's outward normal at the hit's point pb (at a corner: its cone). */
int rugo__primitive_normal_fits(const primitive* P, const hit* h, rugo_vec2 n);

/* The narrow phase of A's segment ka against every feature of B: crossings into xs (if not NULL) and
 * every stationary pair (with B's normal or corner) into ss. 0 if out of memory. */
int rugo__primitive_narrow(rugo_collide_context* ctx, primitive_pair* g, int ka, rugo__array* xs, size_t* nx,
                           rugo__array* ss, size_t* ns);

/* ---------------------------------------------------------------------------------------------------
 * The contact cache (contact_cache.c). */

/* CACHE_MISMATCH if c holds the answer of another pair of shapes (or of shapes rebuilt differently
 * since) or of another context; OK for an empty cache. */
rugo_status rugo__cache_check(const rugo_contact_cache* c, const rugo_shape* a, const rugo_shape* b,
                              const rugo_collide_context* ctx);
/* Gives back the cached answer, moved with the shapes, if the query is the cached one and the shapes
 * moved relative to each other by at most RESOLUTION_MOTION_SHARE delta (delta 0: not at all); 1 if it
 * did. c must have passed rugo__cache_check. */
int rugo__cache_reuse(const rugo_contact_cache* c, rugo_transform xa, rugo_transform xb,
                      const rugo_contact_query* q, rugo_real delta, rugo_contact_output* out);
/* Keeps out's answer (if whole and within the cache's room; else the cache is emptied), searched at xa,
 * xb with B's side at its query level (override: the query's constant band, or < 0). */
void rugo__cache_store(rugo_contact_cache* c, const rugo_shape* a, rugo_transform xa, const rugo_shape* b,
                       rugo_transform xb, const rugo_contact_query* q, const rugo_collide_context* ctx,
                       const query_side* B, rugo_real override, const rugo_contact_output* out);

/* ---------------------------------------------------------------------------------------------------
 * Overlaps below the resolution (collide_below_resolution.c). */

/* The normal (from A to B) that takes apart an overlap too shallow to be resolved, at pa on A (segment
 * sa at ta) and pb on B (g's B at segment sb, tb; or the primitive P when g is NULL), A's frame. */
rugo_vec2 rugo__overlap_normal(const query_side* A, const shape_pair* g, const primitive* P, int sa,
                               rugo_real ta, rugo_vec2 pa, int sb, rugo_real tb, rugo_vec2 pb,
                               rugo_real scale);
/* Contacts for the m crossings x that closed no region: one per cluster, normal of rugo__overlap_normal,
 * regions numbered from first_region. */
rugo_status rugo__emit_unresolved_crossings(contact_out* o, const shape_pair* g, const primitive* P,
                                            const hit* x, int m, rugo_real scale, int first_region);

#endif
