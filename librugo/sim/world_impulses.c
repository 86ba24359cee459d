/* The impulses of a step: one impulse per contact group (a face contact gets it at its centre of
 * pressure), with the surfaces' μ and ε at the points, micro-collisions for resting contact (7.3), in
 * sweeps over the groups until nothing approaches. Separate because it only changes velocities, from
 * contacts the other parts gathered. */
#include "sim/world_internal.h"

#define CONTACT_SWEEPS 4 /* enough for small stacks; each sweep after the first is usually empty */

static rugo_vec2 point_velocity(const body* b, rugo_vec2 r) {
    return rugo_v2_add(b->v, rugo_v2_scale(b->w, rugo_v2_perp(r)));
}

/* Relative normal velocity (SPEC 10 sign: < 0 approaching) of a contact's midpoint. */
static rugo_real contact_vn(const rugo_world* w, const world_contact* wc, rugo_vec2* point) {
    const body* A = &rugo__world_bodies(w)[wc->a];
    const body* B = &rugo__world_bodies(w)[wc->b];
    *point = rugo_v2_scale(0.5, rugo_v2_add(wc->c.point_a, wc->c.point_b));
    rugo_vec2 va = point_velocity(A, rugo_v2_sub(*point, rugo__body_center(A)));
    rugo_vec2 vb = point_velocity(B, rugo_v2_sub(*point, rugo__body_center(B)));
    return -rugo_v2_dot(rugo_v2_sub(va, vb), wc->c.normal);
}

static rugo_real band_of(const rugo_contact* c) {
    return (c->tolerance_a > 0.0 ? c->tolerance_a : 0.0) + (c->tolerance_b > 0.0 ? c->tolerance_b : 0.0);
}

/* ε of a contact approaching at vn (< 0): the surfaces' ε, or for a micro-collision (7.3) ε_c(δ)
 * applied to an incoming speed of at most sqrt(2 g δ), the speed of a fall through the depth reached
 * (7.21-7.22): dissipative, so resting bodies settle. Never above 1 (no energy added). */
static rugo_real contact_restitution(const rugo_world* w, const body* A, const body* B, rugo_real vn,
                                     rugo_real lam, rugo_real la, rugo_real lb, rugo_real delta,
                                     rugo_real base_eps, bool* micro) {
    rugo_real eps = base_eps;
    *micro = w->def.micro_collisions && w->g > 0.0 && lam > 0.0 && vn < 0.0 && -vn < sqrt(2.0 * w->g * lam);
    if (*micro) {
        /* ε_c = max over the bodies of ε_c(δ_i), each band taking its share δ λ_i/λ of the depth */
        rugo_real ea = rugo_restitution_in_band(&A->restitution, delta * la / lam, la);
        rugo_real eb = rugo_restitution_in_band(&B->restitution, delta * lb / lam, lb);
        rugo_real ec = ea > eb ? ea : eb;
        rugo_real fall = sqrt(2.0 * w->g * delta);
        eps = fall < -vn ? ec * fall / -vn : ec;
    }
    if (!(eps >= 0.0)) eps = 0.0;
    return eps > 1.0 ? 1.0 : eps;
}

/* Rolling resistance from roughness (rugo_body_def.rolling_resistance): the asperities of the bands
 * resist the bodies' relative turning with an angular impulse of at most k J_n (λ_A + λ_B), the normal
 * impulse times the bands at the contact, never more than stops the relative turning (so it never adds
 * energy). A smooth contact (λ = 0) rolls freely. */
static void resist_rolling(body* A, body* B, rugo_real impulse_normal, rugo_real lam) {
    const rugo_real k =
        A->rolling_resistance > B->rolling_resistance ? A->rolling_resistance : B->rolling_resistance;
    const rugo_real ii = A->inv_inertia + B->inv_inertia;
    const rugo_real rel = B->w - A->w;
    if (!(k > 0.0) || !(lam > 0.0) || !(ii > 0.0) || rel == 0.0) return;
    rugo_real j = k * fabs(impulse_normal) * lam;
    if (j > fabs(rel) / ii) j = fabs(rel) / ii;
    if (rel < 0.0) j = -j;
    A->w += A->inv_inertia * j;
    B->w -= B->inv_inertia * j;
}

/* One impulse for the group led by contact g (see docs/simulator.md, "Contact groups"): at the centre
 * of the approaching points weighted by approach speed × depth in the band, so that a flat face
 * resting on a flat face gets its impulse in the middle rather than at one end first. Returns 1 if an
 * impulse was applied. */
static int resolve_group(rugo_world* w, int g, rugo_status* status) {
    const world_contact* contacts = rugo__world_contacts(w); /* no contact is added here */
    const world_contact* lead = &contacts[g];
    body* A = &rugo__world_bodies(w)[lead->a];
    body* B = &rugo__world_bodies(w)[lead->b];
    rugo_real sw = 0.0, wmax = -1.0;
    rugo_vec2 sn = rugo_v2(0, 0);
    rugo_real sl = 0.0, sla = 0.0, sd = 0.0, ss = 0.0, smu = 0.0, seps = 0.0;
    int best = -1;
    for (int k = g; k < w->contact_count && contacts[k].a == lead->a && contacts[k].b == lead->b; ++k) {
        const world_contact* wc = &contacts[k];
        if (wc->group != g) continue;
        rugo_vec2 pt;
        rugo_real vn = contact_vn(w, wc, &pt);
        rugo_real lam = band_of(&wc->c);
        rugo_real depth = lam - wc->c.separation; /* into the combined band; beyond it if > λ */
        if (depth < 0.0) depth = 0.0;
        /* Depth, not speed: weighting by approach speed feeds rocking (the end coming down fastest
         * takes the impulse and flips the rotation). */
        rugo_real wt = depth + 0.1 * lam + 1e-9 * (A->size < B->size ? A->size : B->size);
        if (vn < 0.0 && wt > wmax) {
            wmax = wt;
            best = k;
        }
        sw += wt;

        sn = rugo_v2_add(sn, rugo_v2_scale(wt, wc->c.normal));
        sl += wt * lam;
        sla += wt * (wc->c.tolerance_a > 0.0 ? wc->c.tolerance_a : 0.0);
        sd += wt * (depth < lam ? depth : lam);
        ss += wt * wc->c.separation;
        smu += wt * wc->c.friction;
        seps += wt * wc->c.restitution;
    }
    if (best < 0 || !(sw > 0.0)) return 0;
    rugo_real nl = rugo__v2_length(sn);
    rugo_vec2 normal = nl > 0.0 ? rugo_v2_scale(1.0 / nl, sn) : contacts[best].c.normal;
    rugo_real lam = sl / sw, la = sla / sw, delta = sd / sw, sep = ss / sw;
    rugo_real mu = smu / sw, base_eps = seps / sw;
    rugo_real lb = lam - la;
    if (lb < 0.0) lb = 0.0;
    rugo_vec2 ca = rugo__body_center(A), cb = rugo__body_center(B);
    rugo_vec2 nba = rugo_v2_scale(-1.0, normal); /* SPEC 10: from B to A */

    /* The patch's two extreme points along the tangent, and the impulse pair that gives both the
     * restitution target simultaneously (2x2 normal system, compressive only). Its resultant acts at
     * their centre of pressure, where one impulse of SPEC 10 has the same effect on both bodies. */
    rugo_vec2 tau = rugo_v2_perp(normal);
    rugo_vec2 p1 = rugo_v2(0, 0), p2 = rugo_v2(0, 0);
    rugo_real u1 = INFINITY, u2 = -INFINITY;
    for (int k = g; k < w->contact_count && contacts[k].a == lead->a && contacts[k].b == lead->b; ++k) {
        if (contacts[k].group != g) continue;
        rugo_vec2 pt = rugo_v2_scale(0.5, rugo_v2_add(contacts[k].c.point_a, contacts[k].c.point_b));
        rugo_real u = rugo_v2_dot(pt, tau);
        if (u < u1) {
            u1 = u;
            p1 = pt;
        }
        if (u > u2) {
            u2 = u;
            p2 = pt;
        }
    }
    rugo_vec2 pts[2] = {p1, p2};
    rugo_real vns[2], arm_a[2], arm_b[2];
    for (int i = 0; i < 2; ++i) {
        rugo_vec2 ra = rugo_v2_sub(pts[i], ca), rb = rugo_v2_sub(pts[i], cb);
        vns[i] = rugo_v2_dot(rugo_v2_sub(point_velocity(A, ra), point_velocity(B, rb)), nba);
        arm_a[i] = rugo_v2_dot(rugo_v2_perp(ra), nba);
        arm_b[i] = rugo_v2_dot(rugo_v2_perp(rb), nba);
    }
    rugo_real vref = vns[0] < vns[1] ? vns[0] : vns[1];
    bool micro = false;
    rugo_real eps = contact_restitution(w, A, B, vref, lam, la, lb, delta, base_eps, &micro);
    rugo_real im = A->inv_mass + B->inv_mass;
    rugo_real m11 = im + A->inv_inertia * arm_a[0] * arm_a[0] + B->inv_inertia * arm_b[0] * arm_b[0];
    rugo_real m22 = im + A->inv_inertia * arm_a[1] * arm_a[1] + B->inv_inertia * arm_b[1] * arm_b[1];
    rugo_real m12 = im + A->inv_inertia * arm_a[0] * arm_a[1] + B->inv_inertia * arm_b[0] * arm_b[1];
    rugo_real t1 = vns[0] < 0.0 ? -(1.0 + eps) * vns[0] : 0.0;
    rugo_real t2 = vns[1] < 0.0 ? -(1.0 + eps) * vns[1] : 0.0;
    rugo_real det = m11 * m22 - m12 * m12;
    rugo_real l1 = -1.0, l2 = -1.0;
    if (u2 - u1 > 1e-9 * (A->size < B->size ? A->size : B->size) && det > 1e-12 * m11 * m22) {
        l1 = (m22 * t1 - m12 * t2) / det;
        l2 = (m11 * t2 - m12 * t1) / det;
    }
    rugo_vec2 point;
    if (l1 >= 0.0 && l2 >= 0.0 && l1 + l2 > 0.0) {
        point = rugo_v2_add(rugo_v2_scale(l1 / (l1 + l2), p1), rugo_v2_scale(l2 / (l1 + l2), p2));
    } else {
        /* one end alone: the one whose own impulse leaves the other end not approaching, else the
         * more approaching one */
        int i = vns[0] <= vns[1] ? 0 : 1;
        rugo_real li = (i == 0 ? t1 : t2) / (i == 0 ? m11 : m22);
        rugo_real other = vns[1 - i] + m12 * li;
        if (other < 0.0 && vns[1 - i] < 0.0) i = 1 - i;
        point = pts[i];
    }

    rugo__impulse_input in;
    in.inv_mass_a = A->inv_mass;
    in.inv_inertia_a = A->inv_inertia;
    in.inv_mass_b = B->inv_mass;
    in.inv_inertia_b = B->inv_inertia;
    in.r_a = rugo_v2_sub(point, ca);
    in.r_b = rugo_v2_sub(point, cb);
    in.v_a = A->v;
    in.v_b = B->v;
    in.w_a = A->w;
    in.w_b = B->w;
    in.normal = nba;
    rugo_real vn = rugo_v2_dot(rugo_v2_sub(point_velocity(A, in.r_a), point_velocity(B, in.r_b)), in.normal);
    if (!(vn < 0.0)) return 0;
    eps = contact_restitution(w, A, B, vn, lam, la, lb, delta, base_eps, &micro);
    in.restitution = eps;
    in.friction = w->def.friction && mu >= 0.0 && isfinite(mu) ? mu : 0.0;
    rugo__impulse_result r;
    if (rugo__collision_impulse(&in, &r) != RUGO_OK || r.branch == 0) return 0;
    A->v = rugo_v2_add(A->v, rugo_v2_scale(A->inv_mass, r.impulse));
    A->w += A->inv_inertia * rugo_v2_cross(in.r_a, r.impulse);
    B->v = rugo_v2_sub(B->v, rugo_v2_scale(B->inv_mass, r.impulse));
    B->w -= B->inv_inertia * rugo_v2_cross(in.r_b, r.impulse);
    resist_rolling(A, B, r.impulse_normal, lam);
    w->stats.impulses++;
    if (!rugo__world_reserve(w, &w->records, w->record_count + 1, sizeof(rugo_contact_record))) {
        *status = RUGO_ERR_OUT_OF_MEMORY;
        return 1;
    }
    rugo_contact_record* rec = &rugo__world_records(w)[w->record_count++];
    rec->body_a = lead->a;
    rec->body_b = lead->b;
    rec->point = point;
    rec->normal = normal;
    rec->separation = sep;
    rec->tolerance = lam;
    rec->friction = in.friction;
    rec->restitution = eps;
    rec->normal_velocity_before = vn;
    rec->normal_velocity_after =
        rugo_v2_dot(rugo_v2_sub(point_velocity(A, in.r_a), point_velocity(B, in.r_b)), in.normal);
    rec->impulse_normal = r.impulse_normal;
    rec->impulse_tangent = r.impulse_tangent;
    rec->sticking = r.branch == 1;
    rec->micro = micro;
    return 1;
}

/* Impulses at every contact group of the world's contacts, one after another (7.4), in up to CONTACT_SWEEPS
 * sweeps (a sweep after the first only acts where points approach again). */
rugo_status rugo__resolve_contacts(rugo_world* w) {
    w->stats.contacts += w->contact_count;
    rugo__group_contacts(w);
    for (int sweep = 0; sweep < CONTACT_SWEEPS; ++sweep) {
        int applied = 0;
        for (int k = 0; k < w->contact_count; ++k) {
            if (rugo__world_contacts(w)[k].group != k) continue;
            rugo_status st = RUGO_OK;
            applied += resolve_group(w, k, &st);
            if (st != RUGO_OK) return st;
        }
        if (applied == 0) break;
    }
    return RUGO_OK;
}
