/* The narrow phase at a resolution δ (librugo/query/narrow_resolved.h).
 *
 * References: the round-off narrow phase (narrow.h, itself tested against long-double grids in
 * test_narrow.c) for smooth pieces, and a brute-force search of φ = |f - g| - λ_f - λ_g (a 256 x 256
 * grid, then coordinate-wise golden-section refinement) for banded ones. Properties: no minimum with
 * φ <= cutoff - δ is missed, every reported minimum is within δ of a true one (round-off where Newton
 * polished it), transversal crossings are the round-off phase's, conforming stretches give a bounded
 * handful of points, bad input gives nothing. */
#include "query/narrow.h"
#include "query/narrow_resolved.h"
#include "rough/internal.h"
#include "test_util.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* An arc of radius r from angle a0 over `turn` radians, as a cubic (control points on the
 * circle's tangent construction are not needed: a cubic through four arc points is a gentle
 * curve, which is all these tests ask), moved by `off`. */
static void arc_piece(double r, double a0, double turn, rugo_vec2 off, rugo_vec2 p[4]) {
    for (int i = 0; i < 4; ++i) {
        const double a = a0 + turn * i / 3.0;
        p[i] = rugo_v2(off.x + r * cos(a), off.y + r * sin(a));
    }
}

/* A gently curved piece f and a piece g placed near it: its middle within [-0.02, 0.05] of f's
 * middle along f's normal (negative: crossing), tangent turned by up to 0.3 rad, either way round. */
static void random_pair(test_rng* r, rugo_vec2 f[4], rugo_vec2 g[4]) {
    const double ra = test_rng_uniform(r, 0.5, 2.5), rb = test_rng_uniform(r, 0.5, 2.5);
    const double a0 = test_rng_uniform(r, 0.0, 2 * PI);
    arc_piece(ra, a0, 0.3, rugo_v2(-ra * cos(a0), -ra * sin(a0)), f);
    /* f's middle and outward normal (the arc bends left: its centre is on the left) */
    const double am = a0 + 0.15;
    const rugo_vec2 mid = rugo_v2(ra * cos(am) - ra * cos(a0), ra * sin(am) - ra * sin(a0));
    const rugo_vec2 nrm = rugo_v2(cos(am), sin(am));
    const double dist = test_rng_uniform(r, -0.02, 0.05), slide = test_rng_uniform(r, -0.05, 0.05);
    const rugo_vec2 gm = rugo_v2(mid.x + dist * nrm.x - slide * nrm.y, mid.y + dist * nrm.y + slide * nrm.x);
    /* g: an arc of radius rb through gm, bending away from f (or towards it), turned a little */
    const double turn = test_rng_uniform(r, -0.3, 0.3), sweep = test_rng_uniform(r, 0.05, 0.35);
    const int away = test_rng_uniform(r, 0.0, 1.0) < 0.7, reverse = test_rng_uniform(r, 0.0, 1.0) < 0.5;
    const double dir = am + (away ? 0.0 : PI) + turn; /* direction from g's centre to gm */
    const rugo_vec2 cg = rugo_v2(gm.x - rb * cos(dir), gm.y - rb * sin(dir));
    arc_piece(rb, dir + (reverse ? 0.5 : -0.5) * sweep, (reverse ? -1.0 : 1.0) * sweep, cg, g);
}

static double band_value(const double h[2][4], double s) {
    const int k = s >= 0.5;
    const double u = 2.0 * s - k, w = 1.0 - u;
    const double v =
        w * w * w * h[k][0] + 3 * w * w * u * h[k][1] + 3 * w * u * u * h[k][2] + u * u * u * h[k][3];
    return v > 0.0 ? v : 0.0;
}

static rugo_vec2 bez(const rugo_vec2 p[4], double u) {
    const double w = 1.0 - u;
    const double b0 = w * w * w, b1 = 3 * w * w * u, b2 = 3 * w * u * u, b3 = u * u * u;
    return rugo_v2(b0 * p[0].x + b1 * p[1].x + b2 * p[2].x + b3 * p[3].x,
                   b0 * p[0].y + b1 * p[1].y + b2 * p[2].y + b3 * p[3].y);
}

static double phi_of(const rugo__banded_piece* f, const rugo__banded_piece* g, double s, double t) {
    const rugo_vec2 d = rugo_v2_sub(bez(f->p, s), bez(g->p, t));
    return sqrt(d.x * d.x + d.y * d.y) - band_value(f->band, s) - band_value(g->band, t);
}

/* The global minimum of φ over the square: the best point of a grid, then a compass search (eight
 * directions, the step halved when none improves; robust at the band's kinks) down to 1e-12. */
static double brute_min(const rugo__banded_piece* f, const rugo__banded_piece* g, double* bs, double* bt) {
    const int N = 256;
    double best = HUGE_VAL;
    *bs = *bt = 0.5;
    for (int i = 0; i <= N; ++i)
        for (int j = 0; j <= N; ++j) {
            const double v = phi_of(f, g, (double)i / N, (double)j / N);
            if (v < best) best = v, *bs = (double)i / N, *bt = (double)j / N;
        }
    for (double h = 1.0 / N; h > 1e-12;) {
        int improved = 0;
        for (int k = 0; k < 8; ++k) {
            const double s = *bs + h * cos(k * PI / 4), t = *bt + h * sin(k * PI / 4);
            if (s < 0.0 || s > 1.0 || t < 0.0 || t > 1.0) continue;
            const double v = phi_of(f, g, s, t);
            if (v < best) best = v, *bs = s, *bt = t, improved = 1;
        }
        if (!improved) h *= 0.5;
    }
    return best;
}

START_TEST(test_smooth_against_round_off) {
    const double deltas[3] = {1e-2, 1e-4, 1e-7};
    for (int di = 0; di < 3; ++di) {
        const double delta = deltas[di], cutoff = 0.05;
        test_rng r = test_rng_seed(71);
        int checked = 0, transversal = 0;
        for (int k = 0; k < 3000; ++k) {
            rugo_vec2 f[4], g[4];
            random_pair(&r, f, g);
            rugo__narrow_result ex, rs;
            rugo__narrow_pieces(f, g, cutoff, &ex);
            rugo__banded_piece bf, bg;
            rugo__banded_piece_smooth(f, &bf);
            rugo__banded_piece_smooth(g, &bg);
            rugo__narrow_resolved(&bf, &bg, cutoff, NAN, delta,
                                  RUGO__RESOLVED_CROSSINGS | RUGO__RESOLVED_MINIMA, &rs);
            ck_assert_int_eq(rs.overflow, 0);
            /* No minimum missed, each within δ (a polished one to round-off). */
            for (int i = 0; i < ex.stationary_count && ex.crossing_count == 0; ++i) {
                const rugo__pair_point* e = &ex.stationary[i];
                if (e->kind != RUGO__MINIMUM || e->distance > cutoff - delta) continue;
                double best = HUGE_VAL;
                for (int j = 0; j < rs.stationary_count; ++j)
                    if (rs.stationary[j].kind == RUGO__MINIMUM &&
                        fabs(rs.stationary[j].distance - e->distance) < best)
                        best = fabs(rs.stationary[j].distance - e->distance);
                ck_assert_msg(best <= delta, "delta %g pair %d: minimum at distance %.9g missed (best %.3g)",
                              delta, k, e->distance, best);
                ++checked;
            }
            /* Every reported minimum lies on both curves, within the cutoff (+ δ). */
            for (int j = 0; j < rs.stationary_count; ++j) {
                const rugo__pair_point* p = &rs.stationary[j];
                ck_assert(p->s >= 0.0 && p->s <= 1.0 && p->t >= 0.0 && p->t <= 1.0);
                ck_assert_double_le(p->distance, cutoff + 2.0 * delta);
            }
            /* Every crossing is the round-off phase's (kind included), and each of those is found,
             * or the curves touch to δ there (an overlap shallower than δ). */
            for (int j = 0; j < rs.crossing_count; ++j) {
                int same = 0;
                for (int i = 0; i < ex.crossing_count; ++i)
                    same |= fabs(rs.crossings[j].s - ex.crossings[i].s) <= 1e-9 &&
                            fabs(rs.crossings[j].t - ex.crossings[i].t) <= 1e-9 &&
                            rs.crossings[j].kind == ex.crossings[i].kind;
                ck_assert_msg(same || ex.overflow,
                              "delta %g pair %d: crossing (%.9f, %.9f) not the round-off one", delta, k,
                              rs.crossings[j].s, rs.crossings[j].t);
            }
            for (int i = 0; i < ex.crossing_count && !ex.overflow; ++i) {
                int found = 0;
                for (int j = 0; j < rs.crossing_count; ++j)
                    found |= fabs(rs.crossings[j].s - ex.crossings[i].s) <= 1e-9 &&
                             fabs(rs.crossings[j].t - ex.crossings[i].t) <= 1e-9;
                /* an overlap shallower than δ: another of its crossings, or a touching to δ */
                found |= rs.crossing_count > 0;
                for (int j = 0; j < rs.stationary_count && !found; ++j)
                    found |= rs.stationary[j].kind == RUGO__MINIMUM && rs.stationary[j].distance <= delta;
                ck_assert_msg(found, "delta %g pair %d: crossing (%.9f, %.9f) missed", delta, k,
                              ex.crossings[i].s, ex.crossings[i].t);
                transversal += found;
            }
        }
        ck_assert_int_gt(checked, 200);
        ck_assert_int_gt(transversal, 300);
    }
}
END_TEST

START_TEST(test_banded_against_brute_force) {
    test_rng r = test_rng_seed(5);
    int checked = 0, overflows = 0;
    for (int k = 0; k < 400; ++k) {
        rugo__banded_piece f, g;
        random_pair(&r, f.p, g.p);
        /* bands as shapes carry them: per-segment values (here 0..20 mm on pieces of 0.3..0.75, a very
         * rough surface) interpolated along the segment (rugo_tolerance_at's cubic halves) */
        double lf[4], lg[4];
        for (int i = 0; i < 4; ++i) {
            lf[i] = test_rng_uniform(&r, 0.0, 0.02);
            lg[i] = test_rng_uniform(&r, 0.0, 0.02);
        }
        rugo__tolerance_halves(lf, 4, 1, f.band);
        rugo__tolerance_halves(lg, 4, 1, g.band);
        double bs = 0.5, bt = 0.5;
        const double ref = brute_min(&f, &g, &bs, &bt);
        const double cutoff = 0.02;
        if (ref > cutoff - 1e-3) continue;
        /* an interior global minimum with no crossing near (the pieces' own minimum, not a neighbour's) */
        if (bs < 0.01 || bs > 0.99 || bt < 0.01 || bt > 0.99) continue;
        const rugo_vec2 d = rugo_v2_sub(bez(f.p, bs), bez(g.p, bt));
        if (sqrt(d.x * d.x + d.y * d.y) < 1e-3) continue;
        for (int di = 0; di < 2; ++di) {
            const double delta = di == 0 ? 1e-3 : 1e-6;
            rugo__narrow_result rs;
            rugo__narrow_resolved(&f, &g, cutoff, NAN, delta,
                                  RUGO__RESOLVED_CROSSINGS | RUGO__RESOLVED_MINIMA, &rs);
            if (rs.overflow) { /* the box budget ran out (the query falls back to the round-off phase) */
                ++overflows;
                continue;
            }
            if (rs.crossing_count > 0) continue;
            double best = HUGE_VAL;
            for (int j = 0; j < rs.stationary_count; ++j) {
                const double v = phi_of(&f, &g, rs.stationary[j].s, rs.stationary[j].t);
                if (v < best) best = v;
            }
            ck_assert_msg(best <= ref + delta + 1e-9, "pair %d delta %g: best %.9g, brute force %.9g", k,
                          delta, best, ref);
            ck_assert_double_ge(best, ref - 1e-9); /* a real pair cannot beat the minimum */
        }
        ++checked;
    }
    ck_assert_int_gt(checked, 10);
    ck_assert_int_le(overflows, checked / 10);
}
END_TEST

START_TEST(test_conforming_arcs_give_a_patch) {
    /* An arc inside a concentric arc 0.1 % larger, facing each other: φ is flat along the whole
     * piece; the call reports its two ends and its deepest point at most, each at the true gap. */
    rugo_vec2 f[4], g[4];
    arc_piece(1.0, 0.2, 0.5, rugo_v2(0.0, 0.0), f);
    arc_piece(1.001, 0.2 + 0.5, -0.5, rugo_v2(0.0, 0.0), g); /* reversed: outer curve runs the other way */
    rugo__banded_piece bf, bg;
    rugo__banded_piece_smooth(f, &bf);
    rugo__banded_piece_smooth(g, &bg);
    for (int di = 0; di < 3; ++di) {
        const double delta = di == 0 ? 1e-3 : (di == 1 ? 1e-5 : 1e-6);
        rugo__narrow_result rs;
        rugo__narrow_resolved(&bf, &bg, 0.01, NAN, delta, RUGO__RESOLVED_CROSSINGS | RUGO__RESOLVED_MINIMA,
                              &rs);
        ck_assert_msg(rs.overflow == 0, "delta %g: overflow", delta);
        ck_assert_int_eq(rs.crossing_count, 0);
        ck_assert_int_ge(rs.stationary_count, 1);
        ck_assert_int_le(rs.stationary_count, 3);
        for (int j = 0; j < rs.stationary_count; ++j) {
            /* the gap of the cubic approximations of the two arcs, ~1e-3 */
            ck_assert_near(rs.stationary[j].distance, 1e-3, 2e-4 + delta);
        }
    }
}
END_TEST

START_TEST(test_bad_input_gives_nothing) {
    rugo_vec2 f[4], g[4];
    arc_piece(1.0, 0.0, 0.3, rugo_v2(0, 0), f);
    arc_piece(1.0, 0.1, 0.3, rugo_v2(0.0, 0.01), g);
    rugo__banded_piece bf, bg;
    rugo__banded_piece_smooth(f, &bf);
    rugo__banded_piece_smooth(g, &bg);
    rugo__narrow_result rs;
    const double deltas[4] = {0.0, -1.0, NAN, INFINITY};
    for (int i = 0; i < 4; ++i) {
        rugo__narrow_resolved(&bf, &bg, 0.1, 0.1, deltas[i], 7, &rs);
        ck_assert_int_eq(rs.crossing_count + rs.stationary_count, 0);
    }
    bg.p[2].x = NAN;
    rugo__narrow_resolved(&bf, &bg, 0.1, 0.1, 1e-3, 7, &rs);
    ck_assert_int_eq(rs.crossing_count + rs.stationary_count, 0);
    bg.p[2].x = g[2].x;
    bg.band[1][2] = INFINITY;
    rugo__narrow_resolved(&bf, &bg, 0.1, 0.1, 1e-3, 7, &rs);
    ck_assert_int_eq(rs.crossing_count + rs.stationary_count, 0);
    /* a NaN cutoff asks for no minima; crossings are still found */
    bg.band[1][2] = 0.0;
    arc_piece(1.0, 0.0, 0.3, rugo_v2(0.05, -0.05), g);
    rugo__banded_piece_smooth(g, &bg);
    rugo__narrow_resolved(&bf, &bg, NAN, NAN, 1e-3, 7, &rs);
    for (int j = 0; j < rs.stationary_count; ++j)
        ck_assert_int_ne(rs.stationary[j].kind, RUGO__MINIMUM);
}
END_TEST

static Suite* narrow_resolved_suite(void) {
    Suite* s = suite_create("narrow_resolved");
    TCase* tc = tcase_create("core");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, test_smooth_against_round_off);
    tcase_add_test(tc, test_banded_against_brute_force);
    tcase_add_test(tc, test_conforming_arcs_give_a_patch);
    tcase_add_test(tc, test_bad_input_gives_nothing);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) { return test_run_suite(narrow_resolved_suite()); }
