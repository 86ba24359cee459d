/* Built-in outlines for the samples and the demo (deterministic; no files needed). */
#ifndef RUGO_SAMPLE_SHAPES_H
#define RUGO_SAMPLE_SHAPES_H

#include "rugo/rugo.h"

/* An irregular, partly concave "object" like the thesis' figures: n control points (any n >= 8)
 * around `centre` with mean radius `radius`, counter-clockwise. */
void sample_object(int n, rugo_vec2 centre, double radius, rugo_vec2* out);

#endif
