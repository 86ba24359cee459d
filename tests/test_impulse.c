/* Impulse suite (SPEC 10 with the errata of SPEC 12): 200 000 seeded random collisions check, on every
 * impulse, with the bodies' velocities recomputed here from J:
 *  - Newton's restitution law v_n' = -ε v_n for the sticking and frictionless branches, and for the
 *    sliding branch too (its J_n is chosen for it); the sticking branch also stops the tangential slip;
 *    the plastic last resort (frictionless with ε = 0) is allowed where round-off alone would add energy;
 *  - the friction cone J_n >= 0 and |J_t| <= μ J_n;
 *  - kinetic energy never increases.
 * Tolerances: velocities to 1e-9 of the case's speed scale and energies to 1e-10 of the case's kinetic
 * energy — a few hundred ulps of the sums involved, far below any physical effect (the thesis' defect
 * the guard removes is a gain of up to 9x). */
#include "sim/internal.h" /* the impulse at one contact */
#include "test_util.h"

#include <stdio.h>

static rugo_vec2 pv(rugo_vec2 v, rugo_real w, rugo_vec2 r) {
    return rugo_v2_add(v, rugo_v2_scale(w, rugo_v2_perp(r)));
}

static double ke(double im, double ii, rugo_vec2 v, double w) {
    double e = 0.0;
    if (im > 0.0) e += 0.5 * rugo_v2_dot(v, v) / im;
    if (ii > 0.0) e += 0.5 * w * w / ii;
    return e;
}

START_TEST(test_random_collisions) {
    test_rng r = test_rng_seed(2024);
    long branches[4] = {0, 0, 0, 0};
    long guarded = 0; /* raw sticking impulse inside the cone but adding energy: must be rejected */
    const long cases = 200000;
    for (long it = 0; it < cases; ++it) {
        rugo__impulse_input in;
        in.inv_mass_a = 1.0 / test_rng_uniform(&r, 0.1, 10.0);
        in.inv_inertia_a = 1.0 / test_rng_uniform(&r, 0.01, 10.0);
        int b_static = test_rng_uniform(&r, 0, 1) < 0.3;
        in.inv_mass_b = b_static ? 0.0 : 1.0 / test_rng_uniform(&r, 0.1, 10.0);
        in.inv_inertia_b = b_static ? 0.0 : 1.0 / test_rng_uniform(&r, 0.01, 10.0);
        in.r_a = rugo_v2(test_rng_uniform(&r, -2, 2), test_rng_uniform(&r, -2, 2));
        in.r_b = rugo_v2(test_rng_uniform(&r, -2, 2), test_rng_uniform(&r, -2, 2));
        in.v_a = rugo_v2(test_rng_uniform(&r, -5, 5), test_rng_uniform(&r, -5, 5));
        in.v_b = b_static ? rugo_v2(0, 0) : rugo_v2(test_rng_uniform(&r, -5, 5), test_rng_uniform(&r, -5, 5));
        in.w_a = test_rng_uniform(&r, -5, 5);
        in.w_b = b_static ? 0.0 : test_rng_uniform(&r, -5, 5);
        double ang = test_rng_uniform(&r, 0, 6.283185307179586);
        in.normal = rugo_v2(cos(ang), sin(ang));
        double u = test_rng_uniform(&r, 0, 1);
        in.friction = u < 0.1 ? 0.0 : test_rng_uniform(&r, 0.0, 1.5);
        u = test_rng_uniform(&r, 0, 1);
        in.restitution = u < 0.1 ? 0.0 : u > 0.9 ? 1.0 : test_rng_uniform(&r, 0.0, 1.0);
        rugo_vec2 vrel = rugo_v2_sub(pv(in.v_a, in.w_a, in.r_a), pv(in.v_b, in.w_b, in.r_b));
        double vn = rugo_v2_dot(vrel, in.normal);
        if (it % 10 != 0 && vn > 0.0) { /* mostly colliding cases; every 10th as drawn */
            in.normal = rugo_v2_scale(-1.0, in.normal);
            vn = -vn;
        }
        rugo__impulse_result res;
        ck_assert_int_eq(rugo__collision_impulse(&in, &res), RUGO_OK);
        ck_assert_int_ge(res.branch, 0);
        ck_assert_int_le(res.branch, 3);
        branches[res.branch]++;
        double speed = rugo_v2_dot(vrel, vrel);
        speed = sqrt(speed) + 1e-300;
        if (vn >= 0.0) {
            ck_assert_int_eq(res.branch, 0);
            ck_assert(res.impulse.x == 0.0 && res.impulse.y == 0.0);
            continue;
        }
        ck_assert_int_ne(res.branch, 0);
        rugo_vec2 j = res.impulse;
        rugo_vec2 va = rugo_v2_add(in.v_a, rugo_v2_scale(in.inv_mass_a, j));
        double wa = in.w_a + in.inv_inertia_a * rugo_v2_cross(in.r_a, j);
        rugo_vec2 vb = rugo_v2_sub(in.v_b, rugo_v2_scale(in.inv_mass_b, j));
        double wb = in.w_b - in.inv_inertia_b * rugo_v2_cross(in.r_b, j);
        rugo_vec2 vrel2 = rugo_v2_sub(pv(va, wa, in.r_a), pv(vb, wb, in.r_b));
        double vn2 = rugo_v2_dot(vrel2, in.normal);
        double vt2 = rugo_v2_dot(vrel2, rugo_v2_perp(in.normal));
        double vtol = 1e-9 * speed;
        /* Newton's law; the plastic last resort shows up as v_n' = 0 in the frictionless branch */
        if (res.branch == 3 && fabs(vn2 + in.restitution * vn) > vtol)
            ck_assert_msg(fabs(vn2) <= vtol, "frictionless: vn=%g vn'=%g eps=%g", vn, vn2, in.restitution);
        else
            ck_assert_msg(fabs(vn2 + in.restitution * vn) <= vtol, "branch %d: vn=%g vn'=%g eps=%g",
                          res.branch, vn, vn2, in.restitution);
        if (res.branch == 1) ck_assert_msg(fabs(vt2) <= vtol, "sticking leaves slip %g", vt2);
        /* friction cone, from the vector itself */
        double jn = rugo_v2_dot(j, in.normal);
        double jt = rugo_v2_dot(j, rugo_v2_perp(in.normal));
        double jlen = sqrt(rugo_v2_dot(j, j));
        ck_assert_msg(jn >= -1e-12 * jlen, "J_n = %g", jn);
        ck_assert_msg(fabs(jt) <= in.friction * jn + 1e-12 * jlen, "|J_t| = %g > mu J_n = %g", fabs(jt),
                      in.friction * jn);
        ck_assert_near(res.impulse_normal, jn, 1e-12 * jlen);
        ck_assert_near(fabs(res.impulse_tangent), fabs(jt), 1e-9 * jlen); /* sliding reports μ J_n exactly */
        /* energy */
        double e0 = ke(in.inv_mass_a, in.inv_inertia_a, in.v_a, in.w_a) +
                    ke(in.inv_mass_b, in.inv_inertia_b, in.v_b, in.w_b);
        double e1 = ke(in.inv_mass_a, in.inv_inertia_a, va, wa) + ke(in.inv_mass_b, in.inv_inertia_b, vb, wb);
        ck_assert_msg(e1 - e0 <= 1e-10 * e0, "energy grew by %g of %g (branch %d)", e1 - e0, e0, res.branch);
        ck_assert_near(res.energy_change, e1 - e0, 1e-10 * e0);

        /* the raw sticking impulse, computed here: count the cases the energy guard had to reject */
        if (in.friction > 0.0) {
            rugo_vec2 ra = rugo_v2_perp(in.r_a), rb = rugo_v2_perp(in.r_b);
            double im = in.inv_mass_a + in.inv_mass_b;
            double kxx = im + in.inv_inertia_a * ra.x * ra.x + in.inv_inertia_b * rb.x * rb.x;
            double kxy = in.inv_inertia_a * ra.x * ra.y + in.inv_inertia_b * rb.x * rb.y;
            double kyy = im + in.inv_inertia_a * ra.y * ra.y + in.inv_inertia_b * rb.y * rb.y;
            double det = kxx * kyy - kxy * kxy;
            rugo_vec2 tg = rugo_v2_add(vrel, rugo_v2_scale(in.restitution * vn, in.normal));
            rugo_vec2 js =
                rugo_v2_scale(-1.0 / det, rugo_v2(kyy * tg.x - kxy * tg.y, -kxy * tg.x + kxx * tg.y));
            double sjn = rugo_v2_dot(js, in.normal), sjt = rugo_v2_dot(js, rugo_v2_perp(in.normal));
            rugo_vec2 vav = rugo_v2_add(
                vrel, rugo_v2_scale(0.5, rugo_v2(kxx * js.x + kxy * js.y, kxy * js.x + kyy * js.y)));
            double de = rugo_v2_dot(js, vav);
            if (sjn >= 0.0 && fabs(sjt) <= in.friction * sjn && de > 1e-6 * e0) {
                ++guarded;
                ck_assert_int_ne(res.branch, 1);
            }
        }
    }
    /* every branch is exercised, and the guard really had work to do */
    ck_assert_int_gt(branches[1], 10000);
    ck_assert_int_gt(branches[2], 10000);
    ck_assert_int_gt(branches[3], 10000);
    ck_assert_int_gt(guarded, 100);
    fprintf(stderr,
            "impulse: %ld cases: none %ld, sticking %ld, sliding %ld, frictionless %ld; energy guard %ld\n",
            cases, branches[0], branches[1], branches[2], branches[3], guarded);
}
END_TEST

START_TEST(test_head_on) {
    /* equal discs head on, ε = 1, frictionless: velocities exchange */
    rugo__impulse_input in;
    in.inv_mass_a = in.inv_mass_b = 1.0;
    in.inv_inertia_a = in.inv_inertia_b = 2.0;
    in.r_a = rugo_v2(-0.5, 0);
    in.r_b = rugo_v2(0.5, 0);
    in.v_a = rugo_v2(-1, 0);
    in.v_b = rugo_v2(1, 0);
    in.w_a = in.w_b = 0.0;
    in.normal = rugo_v2(1, 0); /* from B (left) to A (right) */
    in.friction = 0.0;
    in.restitution = 1.0;
    rugo__impulse_result res;
    ck_assert_int_eq(rugo__collision_impulse(&in, &res), RUGO_OK);
    ck_assert_int_eq(res.branch, 3);
    ck_assert_near(res.impulse.x, 2.0, 1e-15);
    ck_assert_near(res.impulse.y, 0.0, 1e-15);
    ck_assert_near(res.energy_change, 0.0, 1e-15);
    /* separating: nothing */
    in.v_a = rugo_v2(1, 0);
    in.v_b = rugo_v2(-1, 0);
    ck_assert_int_eq(rugo__collision_impulse(&in, &res), RUGO_OK);
    ck_assert_int_eq(res.branch, 0);
    /* both static: nothing can move */
    in.v_a = rugo_v2(-1, 0);
    in.inv_mass_a = in.inv_mass_b = in.inv_inertia_a = in.inv_inertia_b = 0.0;
    ck_assert_int_eq(rugo__collision_impulse(&in, &res), RUGO_OK);
    ck_assert_int_eq(res.branch, 0);
}
END_TEST

START_TEST(test_bad_input) {
    rugo__impulse_input in;
    in.inv_mass_a = in.inv_mass_b = 1.0;
    in.inv_inertia_a = in.inv_inertia_b = 1.0;
    in.r_a = in.r_b = rugo_v2(0, 0);
    in.v_a = rugo_v2(0, -1);
    in.v_b = rugo_v2(0, 0);
    in.w_a = in.w_b = 0.0;
    in.normal = rugo_v2(0, 1);
    in.friction = 0.5;
    in.restitution = 0.5;
    rugo__impulse_result res;
    ck_assert_int_eq(rugo__collision_impulse(NULL, &res), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(rugo__collision_impulse(&in, NULL), RUGO_ERR_NULL_ARGUMENT);
    rugo__impulse_input b = in;
    b.v_a.x = NAN;
    ck_assert_int_eq(rugo__collision_impulse(&b, &res), RUGO_ERR_NOT_FINITE);
    b = in;
    b.inv_inertia_b = INFINITY;
    ck_assert_int_eq(rugo__collision_impulse(&b, &res), RUGO_ERR_NOT_FINITE);
    b = in;
    b.friction = -0.1;
    ck_assert_int_eq(rugo__collision_impulse(&b, &res), RUGO_ERR_BAD_ARGUMENT);
    b = in;
    b.restitution = 1.5;
    ck_assert_int_eq(rugo__collision_impulse(&b, &res), RUGO_ERR_BAD_ARGUMENT);
    b = in;
    b.normal = rugo_v2(0, 2);
    ck_assert_int_eq(rugo__collision_impulse(&b, &res), RUGO_ERR_BAD_ARGUMENT);
    b = in;
    b.inv_mass_a = -1.0;
    ck_assert_int_eq(rugo__collision_impulse(&b, &res), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(rugo__collision_impulse(&in, &res), RUGO_OK);
    ck_assert_int_ne(res.branch, 0);
}
END_TEST

static Suite* impulse_suite(void) {
    Suite* s = suite_create("impulse");
    TCase* t = tcase_create("core");
    tcase_set_timeout(t, 120);
    tcase_add_test(t, test_random_collisions);
    tcase_add_test(t, test_head_on);
    tcase_add_test(t, test_bad_input);
    suite_add_tcase(s, t);
    return s;
}

int main(void) { return test_run_suite(impulse_suite()); }
