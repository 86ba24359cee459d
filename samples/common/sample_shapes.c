#include "sample_shapes.h"

#include <math.h>

void sample_object(int n, rugo_vec2 centre, double radius, rugo_vec2* out) {
    /* A few fixed harmonics give lobes and one deep bay; kept star-shaped so the outline is simple. */
    for (int k = 0; k < n; ++k) {
        double th = 6.283185307179586 * k / n;
        double r = 1.0 + 0.22 * sin(3.0 * th + 0.4) + 0.10 * cos(5.0 * th) + 0.05 * sin(7.0 * th + 1.1) -
                   0.18 * exp(-8.0 * (1.0 - cos(th - 4.4)));
        out[k] = rugo_v2(centre.x + radius * r * cos(th), centre.y + 0.8 * radius * r * sin(th));
    }
}
