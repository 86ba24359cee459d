/* Points and derivatives of a path's segments (rugo_path_segment, import.h): lines, quadratic and cubic
 * Beziers, elliptical arcs in centre form. */
#include "curve/internal.h"

#include "core/internal.h"

rugo_vec2 rugo__path_segment_end(const rugo_path_segment* s) {
    switch (s->kind) {
    case RUGO_PATH_LINE:
    case RUGO_PATH_ARC:
        return s->p[1];
    case RUGO_PATH_QUADRATIC:
        return s->p[2];
    default:
        return s->p[3];
    }
}

rugo_vec2 rugo__path_segment_point(const rugo_path_segment* s, double t) {
    if (t == 0.0) return s->p[0];
    if (t == 1.0) return rugo__path_segment_end(s);
    const double u = 1.0 - t;
    switch (s->kind) {
    case RUGO_PATH_LINE:
        return rugo_v2(s->p[0].x + t * (s->p[1].x - s->p[0].x), s->p[0].y + t * (s->p[1].y - s->p[0].y));
    case RUGO_PATH_QUADRATIC: {
        const double b0 = u * u, b1 = 2.0 * u * t, b2 = t * t;
        return rugo_v2(b0 * s->p[0].x + b1 * s->p[1].x + b2 * s->p[2].x,
                       b0 * s->p[0].y + b1 * s->p[1].y + b2 * s->p[2].y);
    }
    case RUGO_PATH_CUBIC: {
        const double b0 = u * u * u, b1 = 3.0 * u * u * t, b2 = 3.0 * u * t * t, b3 = t * t * t;
        return rugo_v2(b0 * s->p[0].x + b1 * s->p[1].x + b2 * s->p[2].x + b3 * s->p[3].x,
                       b0 * s->p[0].y + b1 * s->p[1].y + b2 * s->p[2].y + b3 * s->p[3].y);
    }
    default: {
        const double th = s->theta1 + t * s->dtheta;
        const double ex = s->rx * cos(th), ey = s->ry * sin(th);
        const double c = cos(s->phi), sn = sin(s->phi);
        return rugo_v2(s->centre.x + c * ex - sn * ey, s->centre.y + sn * ex + c * ey);
    }
    }
}

rugo_vec2 rugo__path_segment_derivative(const rugo_path_segment* s, double t) {
    const double u = 1.0 - t;
    switch (s->kind) {
    case RUGO_PATH_LINE:
        return rugo_v2_sub(s->p[1], s->p[0]);
    case RUGO_PATH_QUADRATIC: {
        rugo_vec2 d0 = rugo_v2_sub(s->p[1], s->p[0]), d1 = rugo_v2_sub(s->p[2], s->p[1]);
        return rugo_v2(2.0 * (u * d0.x + t * d1.x), 2.0 * (u * d0.y + t * d1.y));
    }
    case RUGO_PATH_CUBIC: {
        rugo_vec2 d0 = rugo_v2_sub(s->p[1], s->p[0]), d1 = rugo_v2_sub(s->p[2], s->p[1]),
                  d2 = rugo_v2_sub(s->p[3], s->p[2]);
        const double b0 = 3.0 * u * u, b1 = 6.0 * u * t, b2 = 3.0 * t * t;
        return rugo_v2(b0 * d0.x + b1 * d1.x + b2 * d2.x, b0 * d0.y + b1 * d1.y + b2 * d2.y);
    }
    default: {
        const double th = s->theta1 + t * s->dtheta;
        const double ex = -s->rx * sin(th) * s->dtheta, ey = s->ry * cos(th) * s->dtheta;
        const double c = cos(s->phi), sn = sin(s->phi);
        return rugo_v2(c * ex - sn * ey, sn * ex + c * ey);
    }
    }
}

rugo_vec2 rugo_path_segment_point(const rugo_path_segment* segment, rugo_real t) {
    if (segment == NULL) return rugo_v2(NAN, NAN);
    return rugo__path_segment_point(segment, t);
}

rugo_vec2 rugo_path_segment_derivative(const rugo_path_segment* segment, rugo_real t) {
    if (segment == NULL) return rugo_v2(NAN, NAN);
    return rugo__path_segment_derivative(segment, t);
}
