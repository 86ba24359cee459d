/** @file rugo/mobb.h
 * librugo — oriented boxes and the MOBBtree, the multiresolution oriented bounding box tree
 * (SPEC 5; thesis chapters 3-4).
 *
 * Node (j, k) of the tree is the box of coarse segment f^j_k: it covers exactly the finest segments
 * k 2^(J-j) .. (k+1) 2^(J-j) - 1 that converge to f^j_k (Theorem 4.1). Leaves (j = J) are the
 * "basic boxes" of the finest segments. With n = 2^J segments there are 2n - 2^(J_min) ... 2n - 1
 * boxes (levels J_min..J), built in O(n).
 *
 * Invariant (tested): node (j, k) contains (i) every descendant finest segment thickened by its hard
 * bound β^J (so the finest curve plus its band), and (ii) its own coarse segment f^j_k thickened by
 * that level's total tolerance λ^j_k, so that queries stopped at level j (levels of detail) are
 * conservative too. Leaves use max(β^J, λ^J). Every tree box is grown by 64 ε (|centre| + extents)
 * so that the invariant survives round-off, and the overlap test counts boxes touching up to
 * round-off of their coordinates as overlapping. Boxes are in the shape's local frame; arc lengths
 * and tolerances per node come from rugo_contour_segment_length and rugo_tolerances_level.
 *
 * Ownership: boxes are plain values; a tree is created by rugo_mobb_tree_create, owned by the caller
 * (or by a rugo_shape) and freed by rugo_mobb_tree_destroy; it does not keep the pyramid or the
 * tolerances. Box functions take non-NULL box pointers; given NULL they return zeros, false or NULL. */
#ifndef RUGO_MOBB_H
#define RUGO_MOBB_H

#include "rugo/base.h"
#include "rugo/contour.h"
#include "rugo/multires.h"
#include "rugo/tolerance.h"

#ifdef __cplusplus
extern "C" {
#endif

/** An oriented box: centre, orthonormal axes (axis[1] = perp(axis[0])), half-extents >= 0. */
typedef struct rugo_obb {
    rugo_vec2 center;  /**< centre (length units) */
    rugo_vec2 axis[2]; /**< unit axes; axis[1] = perp(axis[0]) */
    rugo_real half[2]; /**< half-extents along each axis (length units), >= 0 */
} rugo_obb;

/** Covariance axes of points (SPEC 5.1, thesis 3.2): eigenvectors of the 2x2 covariance about the mean
 * (1/n) Σ p_k; b = 0 or equal eigenvalues give the coordinate axes. Returns unit axis[0], and
 * axis[1] = perp(axis[0]), into axis (caller-owned). n >= 1 (NULL points or n < 1 give the coordinate
 * axes; a NULL axis does nothing). */
RUGO_API void rugo_covariance_axes(const rugo_vec2* points, int n, rugo_vec2 axis[2]);

/** Leaf box of segment j (SPEC 5.2): covariance axes of 5 samples (2 if the arc length <= min_length),
 * exact extents from the segment's end points and the roots in [0,1] of f'(t)·e = 0 for each axis
 * (all degenerate cases: cubic, linear when v·e = 0, straight and point-like segments), centre
 * recomputed from the extents, both half-extents inflated by `band` (>= 0, length units). min_length is
 * in length units. The segment index wraps. */
RUGO_API rugo_obb rugo_segment_box(rugo_contour c, int segment, rugo_real band, rugo_real min_length);

/** Smallest box with the axes of box_with_axes (only its axes are used, not its extent) containing
 * the box b (its four corners). */
RUGO_API rugo_obb rugo_obb_enclose(rugo_obb box_with_axes, const rugo_obb* b);
/** The box moved by a rigid transform (a zeroed box for NULL). */
RUGO_API rugo_obb rugo_obb_transform(rugo_transform t, const rugo_obb* b);
/** Separating-axis test on the four box axes (SPEC 7, 6.7-6.8): true if the boxes overlap (touching
 * counts as overlap), false if an axis separates them. Both boxes in the same frame. */
RUGO_API bool rugo_obb_overlap(const rugo_obb* a, const rugo_obb* b);
/** true if p lies in the box grown by `slack` (length units) on every side (a negative slack shrinks
 * it). */
RUGO_API bool rugo_obb_contains(const rugo_obb* b, rugo_vec2 p, rugo_real slack);
/** Area 4 half[0] half[1] (squared length units); 0 for NULL. */
RUGO_API rugo_real rugo_obb_area(const rugo_obb* b);
/** The four corners into out (caller-owned), counter-clockwise; nothing for NULL. */
RUGO_API void rugo_obb_corners(const rugo_obb* b, rugo_vec2 out[4]);

/** How upper boxes are built (SPEC 5.3); both are required, (b) is the default. */
typedef enum rugo_box_method {
    RUGO_BOXES_MULTIRES = 0, /**< (b) box of the coarse segment itself, enlarged to contain its descendants */
    RUGO_BOXES_OF_BOXES = 1  /**< (a) axes from the arc-length weighted covariance of the centres of all
                                descendant leaf boxes (3.11-3.12; running sums keep it O(1) a node) */
} rugo_box_method;

/** The MOBBtree of a contour (opaque): one box per segment of every level. */
typedef struct rugo_mobb_tree rugo_mobb_tree;

/** What rugo_mobb_tree_create needs. Start from rugo_default_mobb_tree_def(). */
typedef struct rugo_mobb_tree_def {
    const rugo_pyramid* pyramid;       /**< geometry of every level (borrowed during creation) */
    const rugo_tolerances* tolerances; /**< λ and β of every level; NULL = a smooth shape (all zero) */
    rugo_box_method method;            /**< default RUGO_BOXES_MULTIRES */
    rugo_real min_length;              /**< leaf sampling switch l_min (SPEC 5.2); default 0 */
    rugo_allocator allocator;          /**< zeroed = malloc/free */
    int cookie;                        /**< set by rugo_default_mobb_tree_def; catches uninitialised defs */
} rugo_mobb_tree_def;

/** A def with the defaults above and its cookie set; fill in pyramid (and tolerances). */
RUGO_API rugo_mobb_tree_def rugo_default_mobb_tree_def(void);

/** Builds the tree for every level of the pyramid. On success *out is new and owned by the caller
 * (free with rugo_mobb_tree_destroy); on error it is NULL. Errors: NULL_ARGUMENT, BAD_ARGUMENT (cookie,
 * method, min_length < 0 or not finite), BAD_LEVEL (tolerances built for another pyramid),
 * OUT_OF_MEMORY. */
RUGO_API rugo_status rugo_mobb_tree_create(const rugo_mobb_tree_def* def, rugo_mobb_tree** out);
/** Frees the tree through its allocator; NULL is allowed. */
RUGO_API void rugo_mobb_tree_destroy(rugo_mobb_tree* tree);

/** The finest level J (the leaves); -1 for NULL. */
RUGO_API int rugo_mobb_tree_finest_level(const rugo_mobb_tree* tree);
/** The coarsest level J_min; -1 for NULL. */
RUGO_API int rugo_mobb_tree_coarsest_level(const rugo_mobb_tree* tree);
/** The method the upper boxes were built with (RUGO_BOXES_MULTIRES for NULL). */
RUGO_API rugo_box_method rugo_mobb_tree_method(const rugo_mobb_tree* tree);
/** Node (level, k), k in [0, 2^level), in the shape's local frame: a pointer into the tree, valid until
 * it is destroyed; NULL outside the tree. */
RUGO_API const rugo_obb* rugo_mobb_tree_node(const rugo_mobb_tree* tree, int level, int k);
/** A box around the whole shape (covariance axes of the coarsest level's box corners, enclosing every
 * coarsest node): the tree's root, for broad phases. Owned by the tree; NULL for NULL. */
RUGO_API const rugo_obb* rugo_mobb_tree_root(const rugo_mobb_tree* tree);
/** Sum of the box areas of one level (thesis Fig. 4.6); NaN outside the tree. */
RUGO_API rugo_real rugo_mobb_tree_level_area(const rugo_mobb_tree* tree, int level);

#ifdef __cplusplus
}
#endif

#endif
