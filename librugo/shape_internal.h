/* Private accessors of shape.c for collide.c. Not installed, not public API. */
#ifndef RUGO_SHAPE_INTERNAL_H
#define RUGO_SHAPE_INTERNAL_H

#include "rugo/shape.h"

/* Per segment of `level`: a certified upper bound of λ(t) over the segment. */
const rugo_real* rugo__shape_band_bounds(const rugo_shape* s, int level);
/* How far those bounds exceed the level's λ at most: coarse-level queries grow boxes by it so that no
 * contact inside the band is pruned. */
rugo_real rugo__shape_band_excess(const rugo_shape* s, int level);

#endif
