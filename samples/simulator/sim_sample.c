#include "sim_sample.h"

#include "sample_check.h"
#include "svg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { SIM_MAX_POINTS = 1024 };

static int abs_level(const rugo_shape* sh, int rel) {
    int j = rugo_shape_finest_level(sh) + rel;
    if (j < rugo_shape_coarsest_level(sh)) j = rugo_shape_coarsest_level(sh);
    return j;
}

static void hash_transforms(sim_run* r) {
    for (int i = 0; i < r->sc->body_count; ++i) {
        rugo_body_state b = sim_body(r, i);
        double v[4];
        v[0] = b.transform.p.x;
        v[1] = b.transform.p.y;
        v[2] = b.transform.q.c;
        v[3] = b.transform.q.s;
        r->hash = sample_fnv1a(r->hash, v, sizeof v); /* the doubles' bits, in memory order */
    }
}

int sim_build(sim_run* r, const scene* s, const rugo_world_def* def) {
    memset(r, 0, sizeof *r);
    r->sc = s;
    r->hash = SAMPLE_FNV_OFFSET;
    rugo_world_def wd = def ? *def : rugo_default_world_def();
    wd.gravity = s->gravity;
    wd.time_step = s->time_step;
    wd.lod = s->level;
    rugo_status st = rugo_world_create(&wd, &r->world);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo_world_create: %s\n", rugo_status_string(st));
        return -1;
    }
    for (int i = 0; i < s->body_count; ++i) {
        const scene_body* sb = &s->bodies[i];
        if (sb->kind != SCENE_ROUGH) {
            fprintf(stderr, "body %s: the simulator has rough bodies only\n", sb->name);
            return -1;
        }
        rugo_body_def bd = rugo_default_body_def();
        bd.shape = sb->shape;
        bd.type = sb->is_static ? RUGO_BODY_STATIC : RUGO_BODY_DYNAMIC;
        bd.transform = sb->transform;
        bd.linear_velocity = sb->linear_velocity;
        bd.angular_velocity = sb->angular_velocity;
        bd.density = sb->density;
        st = rugo_world_add_body(r->world, &bd, &r->id[i]);
        if (st != RUGO_OK) {
            fprintf(stderr, "rugo_world_add_body(%s): %s\n", sb->name, rugo_status_string(st));
            return -1;
        }
        r->band[i] = scene_max_band(sb->shape, sb->level);
        r->level[i] = abs_level(sb->shape, sb->level);
    }
    hash_transforms(r);
    return 0;
}

void sim_destroy(sim_run* r) {
    rugo_world_destroy(r->world);
    r->world = NULL;
}

int sim_step(sim_run* r) {
    rugo_status st = rugo_world_step(r->world, &r->last);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo_world_step at t = %.4f: %s\n", r->time, rugo_status_string(st));
        return -1;
    }
    r->time += r->sc->time_step;
    ++r->steps;
    r->impulses += r->last.impulses;
    r->bisections += r->last.bisections;
    if (r->last.unresolved) ++r->unresolved_steps;
    hash_transforms(r);
    return 0;
}

int sim_find(const scene* s, scene_role role, int nth) {
    for (int i = 0; i < s->body_count; ++i)
        if (s->bodies[i].role == role && nth-- == 0) return i;
    return -1;
}

rugo_body_state sim_body(const sim_run* r, int i) {
    rugo_body_state b;
    memset(&b, 0, sizeof b);
    if (rugo_world_body(r->world, r->id[i], &b) != RUGO_OK)
        fprintf(stderr, "rugo_world_body(%d) failed\n", i);
    return b;
}

double sim_speed(const rugo_body_state* b) {
    return sqrt(rugo_v2_dot(b->linear_velocity, b->linear_velocity));
}

static double body_kinetic(const rugo_body_state* b) {
    return 0.5 * b->mass * rugo_v2_dot(b->linear_velocity, b->linear_velocity) +
           0.5 * b->inertia * b->angular_velocity * b->angular_velocity;
}

double sim_energy(const sim_run* r) {
    double e = 0.0;
    for (int i = 0; i < r->sc->body_count; ++i) {
        rugo_body_state b = sim_body(r, i);
        if (b.type != RUGO_BODY_DYNAMIC) continue;
        e += body_kinetic(&b) - b.mass * rugo_v2_dot(r->sc->gravity, b.center);
    }
    return e;
}

double sim_kinetic(const sim_run* r) {
    double e = 0.0;
    for (int i = 0; i < r->sc->body_count; ++i) {
        rugo_body_state b = sim_body(r, i);
        if (b.type == RUGO_BODY_DYNAMIC) e += body_kinetic(&b);
    }
    return e;
}

double sim_kinetic_after_kick(const sim_run* r) {
    double e = 0.0, h = r->sc->time_step;
    for (int i = 0; i < r->sc->body_count; ++i) {
        rugo_body_state b = sim_body(r, i);
        if (b.type != RUGO_BODY_DYNAMIC) continue;
        rugo_vec2 v = rugo_v2_add(b.linear_velocity, rugo_v2_scale(h, r->sc->gravity));
        e += 0.5 * b.mass * rugo_v2_dot(v, v) + 0.5 * b.inertia * b.angular_velocity * b.angular_velocity;
    }
    return e;
}

double sim_micro_growth_bound(const sim_run* r) {
    double g = sqrt(rugo_v2_dot(r->sc->gravity, r->sc->gravity)), h = r->sc->time_step, fixed = 0.0,
           sum = 0.0;
    for (int i = 0; i < r->sc->body_count; ++i)
        if (r->sc->bodies[i].is_static) fixed = fmax(fixed, r->band[i]);
    for (int i = 0; i < r->sc->body_count; ++i) {
        if (r->sc->bodies[i].is_static) continue;
        rugo_body_state b = sim_body(r, i);
        sum += b.mass * g * h * 2.0 * sqrt(2.0 * g * (r->band[i] + fixed));
    }
    return sum;
}

/* The body's curve at its contact level placed at its transform (pts: SIM_MAX_POINTS). */
static rugo_contour world_curve(const sim_run* r, int i, rugo_vec2* pts) {
    rugo_contour k, w;
    rugo_shape_level(r->sc->bodies[i].shape, r->level[i], &k);
    rugo_body_state b = sim_body(r, i);
    int n = k.count < SIM_MAX_POINTS ? k.count : SIM_MAX_POINTS;
    for (int j = 0; j < n; ++j)
        pts[j] = rugo_transform_point(b.transform, k.points[j]);
    w.points = pts;
    w.count = n;
    return w;
}

double sim_lowest_point(const sim_run* r, int i) {
    static rugo_vec2 pts[SIM_MAX_POINTS];
    rugo_vec2 lo, hi;
    rugo_contour_bounds(world_curve(r, i, pts), &lo, &hi);
    return lo.y;
}

static const char* colour(int i) {
    static const char* colours[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a",
                                    "#66a61e", "#e6ab02", "#a6761d"};
    return colours[i % 7];
}

int sim_draw_frame(const sim_run* r, const char* path, const char* title, int show_band) {
    static rugo_vec2 pts[SIM_MAX_POINTS];
    svg_canvas c;
    if (svg_open(&c, path, r->sc->view_lo, r->sc->view_hi, 900.0) != 0) return -1;
    for (int i = 0; i < r->sc->body_count; ++i) {
        const scene_body* sb = &r->sc->bodies[i];
        rugo_contour w = world_curve(r, i, pts);
        svg_contour(&c, w, 6, sb->is_static ? "#555555" : colour(i), 1.4, NULL);
        if (show_band) {
            rugo_tolerance_level tl;
            rugo_shape_tolerance_level(sb->shape, r->level[i], &tl);
            fprintf(c.file, "<polygon fill=\"none\" stroke=\"#bbbbbb\" stroke-width=\"1\" points=\"");
            for (int j = 0; j < w.count; ++j)
                for (int q = 0; q < 4; ++q) {
                    double t = q / 4.0;
                    rugo_vec2 p = rugo_contour_point(w, j, t), n = rugo_contour_normal(w, j, t);
                    double lam = rugo_tolerance_at(tl.total, tl.count, j, t, 0.0);
                    rugo_vec2 o = rugo_v2_add(p, rugo_v2_scale(lam, n));
                    fprintf(c.file, "%.2f,%.2f ", (o.x - c.ox) * c.scale, c.height - (o.y - c.oy) * c.scale);
                }
            fprintf(c.file, "\"/>\n");
        }
    }
    int nrec = 0;
    const rugo_contact_record* rec = r->steps > 0 ? rugo_world_contact_records(r->world, &nrec) : NULL;
    for (int k = 0; k < nrec; ++k)
        svg_point(&c, rec[k].point, 2.0, rec[k].micro ? "#3182bd" : "#de2d26");
    svg_text(&c, rugo_v2(r->sc->view_lo.x, r->sc->view_hi.y), title, 14.0);
    return svg_close(&c);
}

FILE* sim_open_out(const char* dir, const char* name) {
    char p[1024];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE* f = fopen(p, "w");
    if (f == NULL) fprintf(stderr, "cannot write %s\n", p);
    return f;
}

double sim_slope(const double* x, const double* y, int n) {
    if (n < 2) return NAN;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < n; ++i) {
        sx += x[i];
        sy += y[i];
        sxx += x[i] * x[i];
        sxy += x[i] * y[i];
    }
    double dn = (double)n, d = dn * sxx - sx * sx;
    return d != 0.0 ? (dn * sxy - sx * sy) / d : NAN;
}

double sim_record_mean_mu(const sim_record* rec) {
    return rec->mu_count ? rec->mu_sum / (double)rec->mu_count : NAN;
}

static void pose_of(const sim_run* r, int i, double out[3]) {
    rugo_body_state b = sim_body(r, i);
    out[0] = b.center.x;
    out[1] = b.center.y;
    out[2] = atan2(b.transform.q.s, b.transform.q.c);
}

int sim_run_scene(sim_run* r, const char* dir, const char* prefix, const long* frames, int n_frames,
                  sim_record* rec, sim_after_step after, void* user) {
    const scene* s = r->sc;
    const int nb = s->body_count;
    memset(rec, 0, sizeof *rec);
    rec->body_count = nb;
    rec->min_y = 1e9;
    rec->min_curve_above = 1e9;
    rec->worst_overlap = -1e9;
    rec->worst_a = rec->worst_b = -1;
    rec->max_impulse_gain = -1e9;
    for (int i = 0; i < nb; ++i) {
        rec->first_contact[i] = rec->impact_y[i] = rec->rebound_y[i] = NAN;
        pose_of(r, i, rec->start[i]);
    }
    char name[512];
    snprintf(name, sizeof name, "%s.csv", prefix);
    FILE* f = sim_open_out(dir, name);
    if (f == NULL) return -1;
    fprintf(f, "t,body,name,x,y,angle,vx,vy,w\n");
    const long n = lround(s->duration / s->time_step);
    rec->e0 = sim_energy(r);
    double e_prev = rec->e0;
    for (long k = 0; k <= n; ++k) {
        int draw = k == n;
        for (int q = 0; q < n_frames; ++q)
            draw |= frames[q] == k;
        if (draw) {
            char path[1024], title[256];
            snprintf(path, sizeof path, "%s/%s_%04ld.svg", dir, prefix, k);
            snprintf(title, sizeof title, "simulator: %s %s (%s), t = %.2f s", s->figure, s->name, s->label,
                     r->time);
            sim_draw_frame(r, path, title, 0);
        }
        int nrec = 0;
        const rugo_contact_record* cr = k > 0 ? rugo_world_contact_records(r->world, &nrec) : NULL;
        for (int i = 0; i < nb; ++i) {
            rugo_body_state b = sim_body(r, i);
            if (k % 6 == 0)
                fprintf(f, "%.4f,%d,%s,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", r->time, i, s->bodies[i].name,
                        b.center.x, b.center.y, atan2(b.transform.q.s, b.transform.q.c), b.linear_velocity.x,
                        b.linear_velocity.y, b.angular_velocity);
            if (b.type != RUGO_BODY_DYNAMIC) continue;
            rec->min_y = fmin(rec->min_y, b.center.y);
            rec->min_curve_above = fmin(rec->min_curve_above, sim_lowest_point(r, i) - s->ground_top);
            if (isnan(rec->first_contact[i]))
                for (int q = 0; q < nrec; ++q)
                    if (cr[q].body_a == r->id[i] || cr[q].body_b == r->id[i]) {
                        rec->first_contact[i] = r->time;
                        rec->impact_y[i] = rec->rebound_y[i] = b.center.y;
                        break;
                    }
            if (!isnan(rec->first_contact[i]) && r->time <= rec->first_contact[i] + 1.0)
                rec->rebound_y[i] = fmax(rec->rebound_y[i], b.center.y);
        }
        if (k == n) break;
        const double ke_mid = sim_kinetic_after_kick(r);
        if (sim_step(r) != 0) {
            fclose(f);
            return -1;
        }
        cr = rugo_world_contact_records(r->world, &nrec);
        for (int q = 0; q < nrec; ++q) {
            rec->mu_sum += cr[q].friction;
            ++rec->mu_count;
            rec->micro += cr[q].micro;
            rec->sticking += cr[q].sticking;
            for (int i = 0; i < nb; ++i)
                if (cr[q].body_a == r->id[i] || cr[q].body_b == r->id[i]) {
                    rec->body_mu_sum[i] += cr[q].friction;
                    ++rec->body_mu_count[i];
                }
            if (-cr[q].separation > rec->worst_overlap) {
                rec->worst_overlap = -cr[q].separation;
                rec->worst_a = cr[q].body_a;
                rec->worst_b = cr[q].body_b;
                rec->worst_time = r->time;
                rec->worst_separation_tolerance = cr[q].tolerance;
            }
        }
        rec->impulses += nrec;
        if (after) after(r, user);
        rec->max_impulse_gain = sample_max(rec->max_impulse_gain, sim_kinetic(r) - ke_mid);
        double e = sim_energy(r);
        rec->max_growth = sample_max(rec->max_growth, (e - e_prev) / fabs(rec->e0));
        rec->max_growth_abs = sample_max(rec->max_growth_abs, e - e_prev);
        e_prev = e;
    }
    for (int i = 0; i < nb; ++i)
        pose_of(r, i, rec->final[i]);
    rec->final_kinetic = sim_kinetic(r);
    rec->steps = r->steps;
    rec->unresolved_steps = r->unresolved_steps;
    rec->hash = r->hash;
    return fclose(f) == 0 ? 0 : -1;
}
