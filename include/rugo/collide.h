/** @file rugo/collide.h
 * librugo — contacts between rough curves at a chosen level of detail (SPEC 7, 8; thesis 6.2).
 *
 * Semantics (docs/contacts.md has the full statement):
 *  - Normal points from A to B; separation s = (point_b - point_a)·normal is the signed distance
 *    between the true curves of the query's level: positive apart, negative inside.
 *  - The state is INTERSECTING if the curves cross; then there is one contact per overlap region
 *    (the region inside both): its deepest pair of points (a stationary pair of the distance, 6.14,
 *    whose connecting vector is normal to both curves), with negative separation, and the normal the
 *    direction that separates the bodies fastest. An overlap too shallow for its crossings to be told
 *    apart (entry and exit within 1e-9 of the size) gets a contact at its crossing, separation ~0:
 *    an INTERSECTING state always comes with at least one contact.
 *  - Otherwise the state is CONTACT if some local minimum of the distance between the curves is within
 *    the summed tolerance λ_A(t_A) + λ_B(t_B) (6.15) — one contact per such local minimum — and APART
 *    if none is.
 *  - A point with t = 1 belongs to the next segment: no duplicate contacts at joints.
 *  - Contacts carry λ at both points, the mixed friction μ and restitution ε of the two surfaces
 *    there, and an id that stays the same while the contact persists (warm starting).
 *  - INTERSECTING also covers one body lying wholly inside the other (contact: the shortest way out).
 *  - Primitive contacts carry the shape's own friction and restitution, unmixed.
 * Nothing is missed: the narrow phase certifies apart/contact/crossing with Bezier-hull subdivision
 * when Newton does not converge. Queries allocate only when a context grows (it never shrinks).
 * A NULL query means rugo_default_contact_query(); an output of capacity 0 asks for the state only.
 * Rotations in transforms are assumed unit (only finiteness is checked).
 *
 * Units: positions, separations and tolerances in the shapes' length units; μ and ε dimensionless.
 * Ownership: contacts, pairs and stats are written into caller-owned arrays; shapes are only read; a
 * context is created by rugo_collide_context_create, owned by the caller and used by one thread at a
 * time. Query errors leave *count = 0. */
#ifndef RUGO_COLLIDE_H
#define RUGO_COLLIDE_H

#include "rugo/base.h"
#include "rugo/mobb.h"
#include "rugo/shape.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** What a query found between two shapes (see the top of this file). */
typedef enum rugo_contact_state {
    RUGO_STATE_APART = 0,       /**< no distance minimum within the summed bands (or the margin) */
    RUGO_STATE_CONTACT = 1,     /**< apart curves whose bands touch: one contact per local minimum */
    RUGO_STATE_INTERSECTING = 2 /**< the curves cross (or one lies inside the other) */
} rugo_contact_state;

/** The state's name, "apart", "contact" or "intersecting" (a static string; "unknown" for an invalid
 * value). */
RUGO_API const char* rugo_contact_state_name(rugo_contact_state s);

/** One contact point pair between shape A and shape B (or a primitive as B). */
typedef struct rugo_contact {
    /** World points on the curves of A and B. @{ */
    rugo_vec2 point_a, point_b;
    /** @} */
    rugo_vec2 normal;     /**< unit, from A to B */
    rugo_real separation; /**< (point_b - point_a)·normal; negative = penetration */
    /** Segment indices at the query's level of each shape (-1: primitive). @{ */
    int segment_a, segment_b;
    /** @} */
    /** Parameters in [0, 1) on those segments (t_b = 0 for primitives). @{ */
    rugo_real t_a, t_b;
    /** @} */
    /** The absolute level (J_min..J) of each shape used (0 for primitives). @{ */
    int level_a, level_b;
    /** @} */
    /** λ(t) at the points (the override if the query gives one), length units. @{ */
    rugo_real tolerance_a, tolerance_b;
    /** @} */
    rugo_real friction;    /**< mixed μ of the two surfaces at the points */
    rugo_real restitution; /**< mixed base restitution ε of the two surfaces */
    int region;            /**< contact region index (overlap region or local minimum), from 0 */
    uint64_t id;           /**< stable while the contact persists */
} rugo_contact;

/** What a query cost, to set speed against error. */
typedef struct rugo_query_stats {
    long box_tests;         /**< OBB overlap tests in the tree traversal */
    long segment_pairs;     /**< segment pairs given to the narrow phase */
    long newton_iterations; /**< total Newton iterations */
    long fallbacks;         /**< pairs decided by subdivision because Newton did not settle */
    int contacts_found;     /**< before truncation to the caller's capacity */
    int reused;             /**< 1: the answer is the contact cache's, moved with the shapes (no search) */
} rugo_query_stats;

/** rugo_contact_query.lod (and the Box2D bridge's RoughBodyDef::lod): each shape's coarsest level whose
 * certified level-of-detail error (rugo_shape_level_error) is at most the query's lod_error_budget at
 * that level and every finer one. */
#define RUGO_LOD_AUTO (-1000000)

/** Where a contact's points are (rugo_contact_query.contact_rule). */
typedef enum rugo_contact_rule {
    /** At a local minimum of the band-adjusted distance d - λ_A(t_A) - λ_B(t_B): the surfaces touch
     * where their bands reach farthest, so the points and separations a coarser level of detail
     * reports stay within its certified error of the finest level's (the default). */
    RUGO_CONTACT_BAND_ADJUSTED = 0,
    /** At a local minimum of the distance d between the curves, the bands added afterwards (the
     * thesis' 6.15): the rule of the thesis' simulator (rugo_world_def.contact_rule's default). */
    RUGO_CONTACT_THESIS = 1
} rugo_contact_rule;

/** rugo_contact_query.resolution: 1e-4 of the smaller shape's size (the diagonal of its root box). */
#define RUGO_RESOLUTION_AUTO (-1.0)

/** Options of a contact query. Start from rugo_default_contact_query() (or pass NULL for the
 * defaults). */
typedef struct rugo_contact_query {
    /** The resolution δ the query is certified to (length units; docs/contacts.md, "Resolution"): no
     * contact whose band-adjusted separation is below the threshold (the band plus margin) by more
     * than δ is missed, and every reported separation is within δ of the true one (round-off where the
     * point was polished by Newton on the true curves); overlaps shallower than δ may be reported as a
     * touching. A stretch along which the curves stay parallel to δ (flat on flat, a disc in a matching
     * bowl) is one contact region whose two ends (and deepest point) are its contacts. The work is
     * bounded by the number of pieces flat to δ near the contact, about (length / δ)^(1/2). 0: the
     * round-off answers (every crossing and minimum certified to the last bits, at a cost that grows
     * without bound for conforming curves). Default RUGO_RESOLUTION_AUTO: 1e-4 of the smaller shape's
     * size. Errors: NOT_FINITE, BAD_ARGUMENT (negative other than RUGO_RESOLUTION_AUTO). */
    rugo_real resolution;
    /** Where contacts are (rugo_contact_rule); default RUGO_CONTACT_BAND_ADJUSTED. Errors: BAD_ARGUMENT
     * for an unknown rule. */
    rugo_contact_rule contact_rule;
    /** Level of detail, relative to each shape: 0 = its finest level, -1 = one level coarser, ...
     * (clamped at its coarsest level), or RUGO_LOD_AUTO. Coarse levels use their coarse segments with
     * their accumulated tolerances λ^j. Contacts report the absolute level used (level_a, level_b).
     * Errors: BAD_ARGUMENT for a positive value (absolute levels are not levels of detail). */
    int lod;
    /** With RUGO_LOD_AUTO: the largest certified error a shape's level may have (length units, >= 0;
     * default 0: the finest level). Errors: NOT_FINITE, BAD_ARGUMENT (negative). */
    rugo_real lod_error_budget;
    /** < 0 (default): use the shapes' tolerances; >= 0: both shapes get this constant band (length
     * units) instead. */
    rugo_real tolerance;
    rugo_mix_rule friction_mix;    /**< default RUGO_MIX_MAX (thesis) */
    rugo_mix_rule restitution_mix; /**< default RUGO_MIX_MIN (thesis) */
    /** >= 0 (length units), default 0: also report local minima of the distance within λ_A + λ_B + margin
     * (speculative contacts for continuous collision, separation > band). The state is then CONTACT when such
     * a minimum exists. Errors: NOT_FINITE, BAD_ARGUMENT (negative). */
    rugo_real margin;
    int cookie; /**< set by rugo_default_contact_query; catches uninitialised queries */
} rugo_contact_query;

/** Resolution RUGO_RESOLUTION_AUTO, level of detail 0 (finest), budget 0, the shapes' tolerances, max
 * for μ, min for ε, margin 0, cookie set. */
RUGO_API rugo_contact_query rugo_default_contact_query(void);

/** The last answer for one pair of shapes, kept by the caller from step to step (opaque; one per pair;
 * see rugo_contact_output.cache and docs/contacts.md, "Coherence"). */
typedef struct rugo_contact_cache rugo_contact_cache;

/** Where a query writes what it found. The caller sets `contacts` and `capacity` (its room: contacts
 * may be NULL when capacity is 0), and optionally `cache`; the query sets the rest. Capacity 0 asks for
 * the state only: the query then stops as soon as the state is known, and count, contacts_found and
 * the statistics of the stages it skipped stay 0. */
typedef struct rugo_contact_output {
    rugo_contact* contacts; /**< caller's array of `capacity` contacts (deepest first within each region,
                               regions in a stable order) */
    int capacity;           /**< room in `contacts` (>= 0) */
    /** Optional (NULL: none): the pair's cache. A query whose shapes moved relative to each other by
     * at most a quarter of its resolution since the answer the cache holds returns that answer moved
     * with the shapes (stats.reused 1; still certified to the resolution); otherwise it searches and
     * stores its answer in the cache. Resolution 0 reuses only an unchanged pair of poses. */
    rugo_contact_cache* cache;
    int count;                /**< contacts written (<= capacity) */
    rugo_contact_state state; /**< what the query found */
    rugo_query_stats stats;   /**< what it cost */
} rugo_contact_output;

/** An output over the caller's array: contacts, capacity; the rest zero (no cache). */
RUGO_API rugo_contact_output rugo_contact_output_of(rugo_contact* contacts, int capacity);

/** Creates an empty contact cache with room for `capacity` contacts into *out (owned by the caller; free
 * with rugo_contact_cache_destroy). It allocates through a copy of `allocator` (NULL = malloc/free)
 * here and in rugo_contact_cache_reserve only: queries never allocate for it (an answer with more
 * contacts than its room is not kept). Errors: NULL_ARGUMENT, BAD_ARGUMENT (capacity < 0 or beyond
 * RUGO_MAX_CONTROL_POINTS), OUT_OF_MEMORY. */
RUGO_API rugo_status rugo_contact_cache_create(const rugo_allocator* allocator, int capacity,
                                               rugo_contact_cache** out);
/** Grows the cache's room to at least `capacity` contacts (it never shrinks; the answer it holds is
 * kept). Errors: NULL_ARGUMENT, BAD_ARGUMENT (as create), OUT_OF_MEMORY (the cache keeps what it had). */
RUGO_API rugo_status rugo_contact_cache_reserve(rugo_contact_cache* cache, int capacity);
/** Forgets the answer (e.g. when a shape of the pair is destroyed or replaced); the room is kept. The
 * next query with it searches, for any pair. NULL is allowed. */
RUGO_API void rugo_contact_cache_clear(rugo_contact_cache* cache);
/** Frees the cache; NULL is allowed. */
RUGO_API void rugo_contact_cache_destroy(rugo_contact_cache* cache);

/** Reusable scratch for queries (node stacks, pair lists; opaque). One per thread. */
typedef struct rugo_collide_context rugo_collide_context;
/** Creates an empty context into *out (owned by the caller; free with rugo_collide_context_destroy).
 * It allocates through a copy of `allocator` (NULL = malloc/free; its functions and ctx must outlive
 * the context) when a query needs more room, and keeps that room. Errors: NULL_ARGUMENT,
 * OUT_OF_MEMORY. */
RUGO_API rugo_status rugo_collide_context_create(const rugo_allocator* allocator, rugo_collide_context** out);
/** Frees the context and its buffers; NULL is allowed. */
RUGO_API void rugo_collide_context_destroy(rugo_collide_context* ctx);
/** Allocates now the room that queries between two shapes no larger than `shape` (its coarsest and
 * finest levels) with up to `contacts` contacts would grow the context to, so that such queries do
 * not allocate later (e.g. call it when a body is added, not during a step). Queries at coarser
 * levels, and against primitives, need less. A query beyond it (shapes deeply overlapping, many more
 * contacts) still grows the context. Calls add up to the largest sizes asked for; the context never
 * shrinks. Errors: NULL_ARGUMENT, BAD_ARGUMENT (contacts < 0 or beyond RUGO_MAX_CONTROL_POINTS),
 * OUT_OF_MEMORY (the context keeps what it had). */
RUGO_API rugo_status rugo_collide_context_reserve(rugo_collide_context* ctx, const rugo_shape* shape,
                                                  int contacts);

/** Contacts between shape A placed by xa and shape B placed by xb, into *out (out->contacts and
 * out->capacity set by the caller; see rugo_contact_output). query may be NULL (the defaults). Errors
 * (then out->count is 0 and out->state APART): NULL_ARGUMENT (a, b, ctx, out, or contacts with
 * capacity > 0), BAD_ARGUMENT (query cookie, lod, budget, margin, mix rules, capacity < 0),
 * NOT_FINITE (a transform or a query length), OUT_OF_MEMORY (the context could not grow),
 * CACHE_MISMATCH (out->cache holds the answer of other shapes, of shapes since destroyed and rebuilt
 * differently, or of another context: clear it; the cache is left as it was). */
RUGO_API rugo_status rugo_collide_shapes(const rugo_shape* a, rugo_transform xa, const rugo_shape* b,
                                         rugo_transform xb, const rugo_contact_query* query,
                                         rugo_collide_context* ctx, rugo_contact_output* out);

/** The most points a primitive has (Box2D's b2_maxPolygonVertices). */
#define RUGO_PRIMITIVE_MAX_POINTS 8

/** A Box2D-like convex primitive: the convex hull of its points grown by a radius — one point is a
 * circle, two a capsule (radius 0: a segment, an edge with no inside), 3..8 a convex polygon with a
 * skin (Box2D's polygon radius). Points counter-clockwise, in the primitive's own frame (its transform
 * is given to the query). A plain value: build it with rugo_make_circle, rugo_make_capsule,
 * rugo_make_segment or rugo_make_polygon. */
typedef struct rugo_primitive {
    rugo_vec2 points[RUGO_PRIMITIVE_MAX_POINTS]; /**< the first `count` are used */
    int count;                                   /**< 1 .. RUGO_PRIMITIVE_MAX_POINTS */
    rugo_real radius;                            /**< >= 0, length units */
} rugo_primitive;

/** A circle (one point and a radius). */
RUGO_API rugo_primitive rugo_make_circle(rugo_vec2 center, rugo_real radius);
/** A capsule: the segment p1-p2 grown by radius (two equal points: a circle). */
RUGO_API rugo_primitive rugo_make_capsule(rugo_vec2 p1, rugo_vec2 p2, rugo_real radius);
/** A segment (an edge: no inside; a capsule of radius 0). */
RUGO_API rugo_primitive rugo_make_segment(rugo_vec2 p1, rugo_vec2 p2);
/** A convex polygon of 3..8 counter-clockwise points with a skin radius, into *out (validated as
 * rugo_collide_primitive validates it). Errors: NULL_ARGUMENT, NOT_FINITE, BAD_ARGUMENT (count outside
 * 3..8, negative radius, not convex and counter-clockwise, repeated or collinear points). */
RUGO_API rugo_status rugo_make_polygon(const rugo_vec2* points, int count, rugo_real radius,
                                       rugo_primitive* out);

/** Contacts between shape A placed by xa and primitive B placed by xb (B smooth: tolerance 0 unless
 * the query overrides it), into *out as rugo_collide_shapes (at round-off whatever query.resolution, which
 * is checked; out->cache is not used). Contacts carry the shape's own friction
 * and restitution, unmixed (segment_b -1, t_b 0, level_b 0). Errors: those of rugo_collide_shapes, and
 * NULL_ARGUMENT (b), NOT_FINITE (a point or the radius), BAD_ARGUMENT (count outside 1..8, negative
 * radius, 3..8 points not convex and counter-clockwise). */
RUGO_API rugo_status rugo_collide_primitive(const rugo_shape* a, rugo_transform xa, const rugo_primitive* b,
                                            rugo_transform xb, const rugo_contact_query* query,
                                            rugo_collide_context* ctx, rugo_contact_output* out);

/** A pair of MOBBtree nodes whose boxes overlap (rugo_tree_pairs). */
typedef struct rugo_node_pair {
    /** Node indices at the stop levels of tree A and tree B. @{ */
    int k_a, k_b;
    /** @} */
} rugo_node_pair;
/** Tree against tree (SPEC 7): the node pairs whose boxes overlap, descending the taller subtree
 * (both when equally tall) and stopping at level_a / level_b (absolute levels, clamped to each
 * tree). Writes at most capacity pairs; *count = number found (may exceed capacity);
 * *box_tests = OBB tests done (box_tests may be NULL). Errors: NULL_ARGUMENT (ctx, a tree, count, or
 * pairs with capacity > 0), BAD_ARGUMENT (capacity < 0), NOT_FINITE (a transform), OUT_OF_MEMORY. */
RUGO_API rugo_status rugo_tree_pairs(const rugo_mobb_tree* a, rugo_transform xa, int level_a,
                                     const rugo_mobb_tree* b, rugo_transform xb, int level_b,
                                     rugo_collide_context* ctx, rugo_node_pair* pairs, int capacity,
                                     int* count, long* box_tests);

/** Manifold reduction in place: keeps at most k contacts per region (k >= 1; smaller k counts as 1):
 * the deepest, then repeatedly the one farthest from those kept. Order is preserved otherwise. Returns
 * the new count (0 for NULL or count <= 0). Allocates nothing. */
RUGO_API int rugo_reduce_manifold(rugo_contact* contacts, int count, int k);

#ifdef __cplusplus
}
#endif

#endif
