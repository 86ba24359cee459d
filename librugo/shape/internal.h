/* Private helpers of the shape layer (shape.c, mobb.c, baked.c, baked_file.c, point_query.c) for its own
 * files and the layers above it. Not installed, not public API. */
#ifndef RUGO_SHAPE_INTERNAL_H
#define RUGO_SHAPE_INTERNAL_H

#include "rugo/baked.h" /* rugo_baked_error */
#include "rugo/shape.h"

#include "curve/internal.h" /* rugo__ray */

/* Per segment of `level`: a certified upper bound of λ(t) over the segment. */
const rugo_real* rugo__shape_band_bounds(const rugo_shape* s, int level);
/* How far those bounds exceed the level's λ at most: coarse-level queries grow boxes by it so that no
 * contact inside the band is pruned. */
rugo_real rugo__shape_band_excess(const rugo_shape* s, int level);

/* Everything a shape holds, as flat arrays (levels J_min..J concatenated, coarsest first: level j
 * at offset 2^j - 2^J_min), in the baked encoding: little-endian binary64, decoded straight into the
 * shape's own memory (rugo__decode_f64_le). Used by the baked-file loader, which has validated every
 * value (finite, bounded, signs, boxes) before calling; the byte pointers need no alignment. */
typedef struct rugo__shape_parts {
    int finest, coarsest;
    rugo_filter filter;
    rugo_box_method box_method;
    bool rough, reversed;
    rugo_mass_properties mass;
    rugo_friction_map friction;
    rugo_restitution restitution;
    const unsigned char* points;      /* control points C^j (x, y): 2^(J+1) - 2^J_min */
    const unsigned char* world;       /* details D^j, j < J: 2^J - 2^J_min (NULL when J = J_min) */
    const unsigned char* local;       /* the same in local frames */
    const unsigned char* tolerances;  /* own, then total λ, then bound β: 3 (2^(J+1) - 2^J_min) */
    const unsigned char* band_bound;  /* 2^(J+1) - 2^J_min */
    const unsigned char* band_excess; /* J - J_min + 1 */
    const unsigned char* nodes;       /* tree nodes, 8 values each (rugo_obb order): 2^(J+1) - 2^J_min */
    rugo_obb root;
    rugo_allocator allocator;
} rugo__shape_parts;

/* rugo_shape_level_error's bound at a level (J_min..J; computed when the shape was built; +inf where it
 * failed or the level is out of range). */
rugo_real rugo__shape_level_error(const rugo_shape* s, int level);

/* A 64-bit hash of everything a contact query reads from the shape (every level's control points and
 * bands, the friction map, the restitution), computed when the shape was built; 0 for NULL. Equal
 * shapes have equal fingerprints, in any process. */
uint64_t rugo__shape_fingerprint(const rugo_shape* s);

/* A shape from stored parts, without recomputing them (values are decoded once, into the pyramid,
 * the tree and the shape). Checks levels and the surface; the pyramid constructor below checks the
 * outline. Errors: NULL_ARGUMENT, BAD_LEVEL, the surface's, OUT_OF_MEMORY, the outline's. */
rugo_status rugo__shape_create_from_parts(const rugo__shape_parts* parts, rugo_shape** out);

/* ---- internal constructors from stored data (multires.c, mobb.c), for rugo__shape_create_from_parts.
 * They copy instead of analysing or building; the caller must have validated every value. */

/* A tree holding the stored boxes (2^(J+1) - 2^J_min nodes encoded as in rugo__shape_parts, level by
 * level from the coarsest) and root, without building it. BAD_LEVEL, BAD_ARGUMENT (unknown method),
 * OUT_OF_MEMORY. */
rugo_status rugo__mobb_tree_from_nodes(int finest, int coarsest, rugo_box_method method,
                                       const unsigned char* nodes, const rugo_obb* root,
                                       const rugo_allocator* allocator, rugo_mobb_tree** out);

/* rugo_contour_contains on the shape's curve of absolute `level` (J_min..J, already resolved), p in the
 * shape's local frame, with the same answer on every input but computed through the shape's MOBBtree
 * (point_query.c): only segments under boxes that the ray from p towards +x may meet are evaluated.
 * *visited (may be NULL) gets their number. */
int rugo__level_contains(const rugo_shape* shape, int level, rugo_vec2 p, int* visited);

/* Runs the ray r (from rugo__ray_begin, curve/internal.h) over the shape's curve of absolute `level`
 * (J_min..J, already resolved) through its MOBBtree (point_query.c): rugo__ray_segment on the segments
 * under the boxes the ray segment up to the running best hit may meet, in increasing order, which leaves
 * r as the pass over all segments would. *visited (may be NULL) gets their number. */
void rugo__level_ray_cast(const rugo_shape* shape, int level, rugo__ray* r, int* visited);

/* ---- error detail of the baked format (baked.c), also for its files (baked_file.c) ---------------- */

/* Fills *d (when not NULL): the byte offset, the field (NULL: none) and the message. */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
void
rugo__baked_detail(rugo_baked_error* d, size_t offset, const char* field, const char* fmt, ...);
/* Empties *d (when not NULL). */
void rugo__baked_clear_detail(rugo_baked_error* d);

#endif
