/* librugo — the impulse at one contact point (SPEC 10, thesis 7.2 with the errata of SPEC 12).
 *
 * Relative velocity v = ṗ_a - ṗ_b, normal n from B to A, v_n = v·n (< 0: approaching). A change of
 * relative velocity Δv = K J for an impulse J on A (-J on B), K the 2-D collision matrix. Branches:
 *  1. sticking: J = -K⁻¹(v + ε v_n n), so v' = -ε v_n n; accepted iff J_n >= 0, |J_t| <= μ J_n (the
 *     two-sided test) and the kinetic energy does not grow;
 *  2. sliding: J = J_n (n - μ t̂) with J_n from v_n' = -ε v_n; accepted iff J_n >= 0 and the energy
 *     does not grow;
 *  3. frictionless: J = J_n n, J_n = -(1 + ε) v_n / (n·K·n). Its energy change is
 *     J_n v_n (1 - ε) / 2 <= 0 for ε <= 1, so it never adds energy except by round-off; if round-off
 *     makes it positive anyway the plastic impulse (ε = 0) is used.
 * The energy change of an impulse is J·(v + v')/2 (exact for rigid bodies), so it is checked without
 * touching the bodies. */
#include "core/internal.h"
#include "sim/internal.h"

/* Relative slack of the acceptance tests: an impulse whose energy gain is below this fraction of the
 * relative kinetic energy ½ vᵀK⁻¹v is round-off, not a defect of the branch. */
#define ENERGY_SLACK 1e-12

typedef struct mat2 {
    rugo_real xx, xy, yy; /* symmetric */
} mat2;

static rugo_vec2 mat2_mul(mat2 m, rugo_vec2 v) {
    return rugo_v2(m.xx * v.x + m.xy * v.y, m.xy * v.x + m.yy * v.y);
}

static int input_finite(const rugo__impulse_input* in) {
    return isfinite(in->inv_mass_a) && isfinite(in->inv_inertia_a) && isfinite(in->inv_mass_b) &&
           isfinite(in->inv_inertia_b) && rugo__v2_finite(in->r_a) && rugo__v2_finite(in->r_b) &&
           rugo__v2_finite(in->v_a) && rugo__v2_finite(in->v_b) && isfinite(in->w_a) && isfinite(in->w_b) &&
           rugo__v2_finite(in->normal) && isfinite(in->friction) && isfinite(in->restitution);
}

/* Energy change J·(v + v')/2 with v' = v + K J. */
static rugo_real energy_change(mat2 k, rugo_vec2 v, rugo_vec2 j) {
    rugo_vec2 kj = mat2_mul(k, j);
    return rugo_v2_dot(j, rugo_v2_add(v, rugo_v2_scale(0.5, kj)));
}

static void set_result(rugo__impulse_result* out, rugo_vec2 j, rugo_vec2 n, rugo_vec2 tangent, int branch,
                       mat2 k, rugo_vec2 v) {
    out->impulse = j;
    out->impulse_normal = rugo_v2_dot(j, n);
    out->impulse_tangent = -rugo_v2_dot(j, tangent); /* J = J_n n - J_t t̂ */
    out->branch = branch;
    out->energy_change = energy_change(k, v, j);
}

rugo_status rugo__collision_impulse(const rugo__impulse_input* in, rugo__impulse_result* out) {
    if (in == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (!input_finite(in)) return RUGO_ERR_NOT_FINITE;
    if (in->friction < 0.0 || in->restitution < 0.0 || in->restitution > 1.0) return RUGO_ERR_BAD_ARGUMENT;
    if (in->inv_mass_a < 0.0 || in->inv_mass_b < 0.0 || in->inv_inertia_a < 0.0 || in->inv_inertia_b < 0.0)
        return RUGO_ERR_BAD_ARGUMENT;
    if (fabs(rugo__v2_length(in->normal) - 1.0) > 1e-6) return RUGO_ERR_BAD_ARGUMENT;

    rugo_vec2 n = in->normal;
    rugo_real mu = in->friction, eps = in->restitution;
    rugo_vec2 pa = rugo_v2_add(in->v_a, rugo_v2_scale(in->w_a, rugo_v2_perp(in->r_a)));
    rugo_vec2 pb = rugo_v2_add(in->v_b, rugo_v2_scale(in->w_b, rugo_v2_perp(in->r_b)));
    rugo_vec2 v = rugo_v2_sub(pa, pb);
    rugo_real vn = rugo_v2_dot(v, n);

    /* K = (1/m_a + 1/m_b) I + r_a⊥ r_a⊥ᵀ/I_a + r_b⊥ r_b⊥ᵀ/I_b, r⊥ = (-r_y, r_x). */
    rugo_vec2 ra = rugo_v2_perp(in->r_a), rb = rugo_v2_perp(in->r_b);
    rugo_real im = in->inv_mass_a + in->inv_mass_b;
    mat2 k;
    k.xx = im + in->inv_inertia_a * ra.x * ra.x + in->inv_inertia_b * rb.x * rb.x;
    k.xy = in->inv_inertia_a * ra.x * ra.y + in->inv_inertia_b * rb.x * rb.y;
    k.yy = im + in->inv_inertia_a * ra.y * ra.y + in->inv_inertia_b * rb.y * rb.y;
    rugo_real knn = rugo_v2_dot(n, mat2_mul(k, n));

    /* Tangent: the direction of the tangential slip, or n's perpendicular when there is none. */
    rugo_vec2 vt = rugo_v2_sub(v, rugo_v2_scale(vn, n));
    rugo_real vt_len = rugo__v2_length(vt);
    rugo_real v_len = rugo__v2_length(v);
    int slipping = vt_len > 1e-14 * v_len && vt_len > 0.0;
    rugo_vec2 t = slipping ? rugo_v2_scale(1.0 / vt_len, vt) : rugo_v2_perp(n);

    out->impulse = rugo_v2(0.0, 0.0);
    out->impulse_normal = 0.0;
    out->impulse_tangent = 0.0;
    out->branch = 0;
    out->energy_change = 0.0;
    /* Separating or resting, or nothing can move (both static, or K degenerate). */
    if (!(vn < 0.0) || !(knn > 0.0)) return RUGO_OK;

    rugo_real det = k.xx * k.yy - k.xy * k.xy;
    /* Scale of the kinetic energy available in the relative motion, for the round-off slack. */
    rugo_real e_scale = 0.5 * vn * vn / knn + 0.5 * v_len * v_len / (k.xx + k.yy);
    rugo_real slack = ENERGY_SLACK * e_scale;

    if (mu > 0.0 && det > 1e-14 * (k.xx + k.yy) * (k.xx + k.yy)) {
        /* 1. sticking */
        rugo_vec2 target = rugo_v2_add(v, rugo_v2_scale(eps * vn, n));
        rugo_vec2 j = rugo_v2_scale(
            -1.0 / det, rugo_v2(k.yy * target.x - k.xy * target.y, -k.xy * target.x + k.xx * target.y));
        rugo_real jn = rugo_v2_dot(j, n);
        rugo_real jt = rugo_v2_dot(j, rugo_v2_perp(n));
        if (jn >= 0.0 && fabs(jt) <= mu * jn && energy_change(k, v, j) <= slack) {
            set_result(out, j, n, t, 1, k, v);
            return RUGO_OK;
        }
    }
    if (mu > 0.0 && slipping) {
        /* 2. sliding: friction μ J_n against the slip; v_n' = -ε v_n still holds. */
        rugo_vec2 d = rugo_v2_sub(n, rugo_v2_scale(mu, t));
        rugo_real denom = rugo_v2_dot(n, mat2_mul(k, d)); /* n·K·n - μ n·K·t̂ */
        if (denom > 0.0) {
            rugo_real jn = -(1.0 + eps) * vn / denom;
            rugo_vec2 j = rugo_v2_scale(jn, d);
            if (jn >= 0.0 && energy_change(k, v, j) <= slack) {
                set_result(out, j, n, t, 2, k, v);
                out->impulse_normal = jn;
                out->impulse_tangent = mu * jn; /* exact, not re-projected */
                return RUGO_OK;
            }
        }
    }
    /* 3. frictionless (also the fallback), then plastic if round-off alone would add energy. */
    {
        rugo_real jn = -(1.0 + eps) * vn / knn;
        rugo_vec2 j = rugo_v2_scale(jn, n);
        if (energy_change(k, v, j) > slack) {
            jn = -vn / knn;
            j = rugo_v2_scale(jn, n);
        }
        set_result(out, j, n, t, 3, k, v);
        out->impulse_normal = jn;
        out->impulse_tangent = 0.0;
    }
    return RUGO_OK;
}
