#include "scenes.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const double PI2 = 6.283185307179586;
enum { MAXP = 512 };

rugo_friction_map scene_friction_map(void) {
    rugo_friction_map m;
    m.base = 0.1; /* smooth surfaces still slide with some friction */
    m.lambda_min = 0.04 * SCENE_ROUGHNESS_SCALE;
    m.alpha = 0.8 / (0.61 * SCENE_ROUGHNESS_SCALE); /* μ = 0.9 at the library's largest λ (0.65) */
    return m;
}

void scene_ball_pair(int variant, rugo_tolerance_preset* ball, rugo_tolerance_preset* block) {
    static const rugo_tolerance_preset pairs[6][2] = {
        {RUGO_PRESET_TIPO_1, RUGO_PRESET_TIPO_1}, {RUGO_PRESET_TIPO_1, RUGO_PRESET_TIPO_2},
        {RUGO_PRESET_TIPO_1, RUGO_PRESET_TIPO_3}, {RUGO_PRESET_TIPO_2, RUGO_PRESET_TIPO_2},
        {RUGO_PRESET_TIPO_2, RUGO_PRESET_TIPO_3}, {RUGO_PRESET_TIPO_3, RUGO_PRESET_TIPO_3}};
    if (variant < 0 || variant > 5) variant = 0;
    *ball = pairs[variant][0];
    *block = pairs[variant][1];
}

int scene_variant_count(scene_id id) {
    static const int counts[SCENE_COUNT] = {6, 2, 1, 2, 3, 1};
    return (int)id >= 0 && id < SCENE_COUNT ? counts[id] : 0;
}

rugo_real scene_max_band(const rugo_shape* shape, int level) {
    int j = rugo_shape_finest_level(shape) + level;
    if (j < rugo_shape_coarsest_level(shape)) j = rugo_shape_coarsest_level(shape);
    rugo_tolerance_level tl;
    if (rugo_shape_tolerance_level(shape, j, &tl) != RUGO_OK) return 0.0;
    double m = 0.0;
    for (int k = 0; k < tl.count; ++k)
        m = fmax(m, tl.total[k]);
    return m;
}

/* ---- outlines ------------------------------------------------------------------------------- */

/* Resamples a closed polygon to n points equally spaced by arc length, starting at vertex 0. */
static void resample(const rugo_vec2* poly, int m, int n, rugo_vec2* out) {
    double len[MAXP + 1];
    len[0] = 0.0;
    for (int i = 0; i < m; ++i) {
        rugo_vec2 d = rugo_v2_sub(poly[(i + 1) % m], poly[i]);
        len[i + 1] = len[i] + sqrt(d.x * d.x + d.y * d.y);
    }
    int e = 0;
    for (int k = 0; k < n; ++k) {
        double s = len[m] * k / n;
        while (e < m - 1 && len[e + 1] <= s)
            ++e;
        double f = (s - len[e]) / (len[e + 1] - len[e]);
        rugo_vec2 a = poly[e], b = poly[(e + 1) % m];
        out[k] = rugo_v2(a.x + f * (b.x - a.x), a.y + f * (b.y - a.y));
    }
}

/* A fixed block: [-length/2, length/2] x [-height, top(x)] with top(x) = a1 sin(2π x / w1 + p1) +
 * a2 sin(2π x / w2 + p2) (0 for a flat block); n control points equally spaced along the outline. */
typedef struct wave {
    double a1, w1, p1, a2, w2, p2;
} wave;
static double wave_at(const wave* w, double x) {
    if (w == NULL) return 0.0;
    return w->a1 * sin(PI2 * x / w->w1 + w->p1) + w->a2 * sin(PI2 * x / w->w2 + w->p2);
}
static void block_outline(double length, double height, const wave* w, int n, rugo_vec2* out) {
    static rugo_vec2 poly[MAXP];
    int m = 0, top = 200; /* dense polyline of the top, then the three straight sides */
    double h = length / 2.0;
    poly[m++] = rugo_v2(-h, -height);
    poly[m++] = rugo_v2(h, -height);
    for (int i = 0; i <= top; ++i) {
        double x = h - length * i / top;
        poly[m++] = rugo_v2(x, wave_at(w, x));
    }
    resample(poly, m, n, out);
}

/* Star-shaped irregular outline: radius r(θ) = radius (1 + Σ_k amp_k sin(k θ + phase_k)), k = 2..7,
 * with seeded amplitudes (scaled by `rough`) and phases; x stretched by `aspect`. */
static void blob(uint64_t seed, double radius, double aspect, double rough, int n, rugo_vec2* out) {
    rugo_rng rng;
    rugo_rng_seed(&rng, seed);
    double amp[8], ph[8];
    for (int k = 2; k < 8; ++k) {
        amp[k] = rough * rugo_rng_range(&rng, 0.02, 0.12) / (double)(k - 1);
        ph[k] = rugo_rng_range(&rng, 0.0, PI2);
    }
    for (int i = 0; i < n; ++i) {
        double th = PI2 * i / n, r = 1.0;
        for (int k = 2; k < 8; ++k)
            r += amp[k] * sin(k * th + ph[k]);
        out[i] = rugo_v2(aspect * radius * r * cos(th), radius * r * sin(th));
    }
}

/* A gear: teeth as a smoothed square wave on the radius. */
static void gear(int teeth, double radius, double depth, int n, rugo_vec2* out) {
    for (int i = 0; i < n; ++i) {
        double th = PI2 * i / n;
        double r = radius * (1.0 + depth * tanh(3.0 * sin(teeth * th)));
        out[i] = rugo_v2(r * cos(th), r * sin(th));
    }
}

/* The outline of a stroke of width w along an open polyline (square caps, mitred corners). */
static int stroke(const rugo_vec2* path, int m, double w, rugo_vec2* out) {
    rugo_vec2 p[32], off[32];
    double h = 0.5 * w;
    for (int i = 0; i < m; ++i)
        p[i] = path[i];
    for (int i = 0; i < m; ++i) {
        rugo_vec2 d0 = rugo_v2_sub(p[i > 0 ? i : 1], p[i > 0 ? i - 1 : 0]);
        rugo_vec2 d1 = rugo_v2_sub(p[i < m - 1 ? i + 1 : m - 1], p[i < m - 1 ? i : m - 2]);
        d0 = rugo_v2_scale(1.0 / sqrt(rugo_v2_dot(d0, d0)), d0);
        d1 = rugo_v2_scale(1.0 / sqrt(rugo_v2_dot(d1, d1)), d1);
        rugo_vec2 n0 = rugo_v2_perp(d0), n1 = rugo_v2_perp(d1);
        off[i] = rugo_v2_scale(h / (1.0 + rugo_v2_dot(n0, n1)), rugo_v2_add(n0, n1));
        if (i == 0) p[0] = rugo_v2_sub(p[0], rugo_v2_scale(h, d1));
        if (i == m - 1) p[i] = rugo_v2_add(p[i], rugo_v2_scale(h, d0));
    }
    int k = 0;
    for (int i = 0; i < m; ++i)
        out[k++] = rugo_v2_add(p[i], off[i]);
    for (int i = m - 1; i >= 0; --i)
        out[k++] = rugo_v2_sub(p[i], off[i]);
    return k;
}

/* ---- building ------------------------------------------------------------------------------- */

static rugo_shape* add_shape(scene* s, const rugo_vec2* pts, int n, const double* lam, double eps,
                             double eps_max, rugo_status* st) {
    if (*st != RUGO_OK) return NULL;
    if (s->shape_count >= SCENE_MAX_SHAPES) {
        *st = RUGO_ERR_BAD_ARGUMENT;
        return NULL;
    }
    rugo_shape_def d = rugo_default_shape_def();
    d.points = pts;
    d.count = n;
    d.tolerances = lam;
    d.friction = scene_friction_map();
    d.restitution.epsilon = eps;
    d.restitution.epsilon_max = eps_max;
    rugo_shape* sh = NULL;
    rugo_contour_problem pr;
    *st = rugo_shape_create(&d, &sh, &pr);
    if (*st != RUGO_OK) {
        fprintf(stderr, "scenes: shape %d of scene %d: %s\n", s->shape_count, (int)s->id,
                rugo_status_string(*st));
        return NULL;
    }
    s->shapes[s->shape_count++] = sh;
    return sh;
}

/* λ per segment in metres from a preset (library units times the scale). */
static void preset(rugo_tolerance_preset p, uint64_t seed, int n, double* out) {
    rugo_tolerances_preset(p, seed, n, out);
    for (int i = 0; i < n; ++i)
        out[i] *= SCENE_ROUGHNESS_SCALE;
}

static scene_body* add_body(scene* s, const char* name, scene_role role, const rugo_shape* shape,
                            int is_static, double x, double y, double angle) {
    if (s->body_count >= SCENE_MAX_BODIES) return NULL;
    scene_body* b = &s->bodies[s->body_count++];
    memset(b, 0, sizeof *b);
    snprintf(b->name, sizeof b->name, "%s", name);
    b->kind = SCENE_ROUGH;
    b->role = role;
    b->shape = shape;
    b->is_static = is_static;
    b->transform = rugo_make_transform(x, y, angle);
    b->density = 1.0;
    b->friction = 0.5;
    b->restitution = 0.2;
    b->level = s->level;
    return b;
}

/* Lowest local y of a shape's finest curve: bodies are placed so that it rests just above a surface. */
static double bottom_of(const rugo_shape* sh) {
    rugo_contour c;
    rugo_shape_level(sh, rugo_shape_finest_level(sh), &c);
    rugo_vec2 lo, hi;
    rugo_contour_bounds(c, &lo, &hi);
    return lo.y;
}

/* Height at which a body rests on a block: its lowest point above the top (plus both bands). */
static double rest_y(const rugo_shape* body, const rugo_shape* block, int level, double top) {
    return top - bottom_of(body) + scene_max_band(body, level) + scene_max_band(block, level) + 0.005;
}

static rugo_status build_ball(scene* s) {
    enum { NB = 256, NS = 64 };
    static rugo_vec2 bp[NB], sp[NS];
    double lb[NB], ls[NS];
    rugo_tolerance_preset pb, ps;
    scene_ball_pair(s->variant, &ps, &pb);
    snprintf(s->label, sizeof s->label, "%s-%s", rugo_preset_name(ps), rugo_preset_name(pb));
    s->name = "ball rolling on a fixed horizontal block";
    s->figure = "Fig. 7.4-7.6";
    s->measures = "friction at each contact over time (7.5) and the ball's speed over time (7.6)";
    s->duration = 3.5;
    block_outline(12.0, 0.6, NULL, NB, bp);
    preset(pb, 12, NB, lb);
    for (int i = 0; i < NS; ++i)
        sp[i] = rugo_v2(0.4 * cos(PI2 * i / NS), 0.4 * sin(PI2 * i / NS));
    preset(ps, 11, NS, ls);
    rugo_status st = RUGO_OK;
    rugo_shape* block = add_shape(s, bp, NB, lb, 0.5, 0.9, &st);
    rugo_shape* ball = add_shape(s, sp, NS, ls, 0.5, 0.9, &st);
    if (st != RUGO_OK) return st;
    add_body(s, "block", SCENE_ROLE_GROUND, block, 1, 0.0, 0.0, 0.0);
    /* Thrown sliding without spin: friction turns sliding into rolling, faster for larger μ. */
    scene_body* b = add_body(s, "ball", SCENE_ROLE_MOVER, ball, 0, -5.0, rest_y(ball, block, 0, 0.0), 0.0);
    b->linear_velocity = rugo_v2(3.0, 0.0);
    s->view_lo = rugo_v2(-6.2, -0.8);
    s->view_hi = rugo_v2(6.2, 1.2);
    return RUGO_OK;
}

/* The squat irregular slider of Fig. 7.7: a rounded slab with a bumpy top; low enough not to tip. */
static void slider(int n, rugo_vec2* out) {
    for (int i = 0; i < n; ++i) {
        double th = PI2 * i / n, c = cos(th), sn = sin(th);
        double x = 0.6 * (c < 0 ? -1.0 : 1.0) * pow(fabs(c), 0.4);
        double y = 0.2 * (sn < 0 ? -1.0 : 1.0) * pow(fabs(sn), 0.4);
        if (sn > 0) y += 0.04 * sin(5.0 * th) * sn;
        out[i] = rugo_v2(x, y);
    }
}

static rugo_status build_thrown(scene* s) {
    enum { NB = 256, NS = 64 };
    static rugo_vec2 bp[NB], sp[NS];
    double lb[NB], ls[NS];
    const double rough = 0.60 * SCENE_ROUGHNESS_SCALE, smooth = 0.04 * SCENE_ROUGHNESS_SCALE;
    s->name = "irregular body thrown at 10 m/s on a fixed block";
    s->figure = "Fig. 7.7-7.8";
    s->measures = "tangential contact speed over time; deceleration on each stretch of the block";
    s->duration = 4.0;
    block_outline(20.0, 0.6, NULL, NB, bp);
    slider(NS, sp);
    const double* mover_lam = ls;
    if (s->variant == 0) {
        snprintf(s->label, sizeof s->label, "a-both-tipo_2");
        preset(RUGO_PRESET_TIPO_2, 22, NB, lb);
        preset(RUGO_PRESET_TIPO_2, 21, NS, ls);
    } else {
        snprintf(s->label, sizeof s->label, "b-rough-smooth-rough");
        s->stretch[0] = -4.0;
        s->stretch[1] = 5.0;
        rugo_friction_map fm = scene_friction_map();
        s->stretch_mu[0] = rugo_friction(&fm, rough);
        s->stretch_mu[1] = rugo_friction(&fm, smooth);
        rugo_contour c = {bp, NB};
        for (int j = 0; j < NB; ++j) {
            rugo_vec2 m = rugo_contour_point(c, j, 0.5);
            int on_top = m.y > -0.05;
            lb[j] = on_top && m.x >= s->stretch[0] && m.x < s->stretch[1] ? smooth : rough;
        }
        mover_lam = NULL; /* "rugosidade nula": μ of the pair is the block's */
    }
    rugo_status st = RUGO_OK;
    rugo_shape* block = add_shape(s, bp, NB, lb, 0.5, 0.9, &st);
    rugo_shape* mover = add_shape(s, sp, NS, mover_lam, 0.2, 0.9, &st);
    if (st != RUGO_OK) return st;
    add_body(s, "block", SCENE_ROLE_GROUND, block, 1, 0.0, 0.0, 0.0);
    scene_body* b =
        add_body(s, "slider", SCENE_ROLE_MOVER, mover, 0, -8.5, rest_y(mover, block, 0, 0.0), 0.0);
    b->linear_velocity = rugo_v2(10.0, 0.0);
    s->view_lo = rugo_v2(-10.2, -0.8);
    s->view_hi = rugo_v2(10.2, 1.5);
    return RUGO_OK;
}

static rugo_status build_four(scene* s) {
    enum { NB = 256, NS = 64 };
    static rugo_vec2 bp[NB], op[NS], sp[4][NS];
    double lb[NB], lo[NS], ls[4][NS];
    static const double eps[4] = {0.1, 0.35, 0.6, 0.85};
    static const double xs[4] = {-3.0, -1.5, 0.0, 1.4};
    const wave w = {0.12, 3.0, 0.3, 0.05, 1.1, 1.0};
    snprintf(s->label, sizeof s->label, "tipo_2");
    s->name = "four bodies on a fixed irregular block";
    s->figure = "Fig. 7.9";
    s->measures = "heights and energy over time; rebound against each body's restitution";
    s->duration = 8.0;
    block_outline(8.0, 0.8, &w, NB, bp);
    preset(RUGO_PRESET_TIPO_2, 40, NB, lb);
    blob(41, 0.45, 0.8, 1.0, NS, op);
    preset(RUGO_PRESET_TIPO_2, 42, NS, lo);
    rugo_status st = RUGO_OK;
    /* The block is fully elastic so that each body's own ε decides (pairs take the minimum, 7.2). */
    rugo_shape* block = add_shape(s, bp, NB, lb, 1.0, 1.0, &st);
    rugo_shape* obst = add_shape(s, op, NS, lo, 1.0, 1.0, &st);
    rugo_shape* sh[4];
    for (int i = 0; i < 4; ++i) {
        blob(50 + (uint64_t)i, 0.28, 1.0 + 0.15 * i, 1.0, NS, sp[i]);
        preset(RUGO_PRESET_TIPO_2, 60 + (uint64_t)i, NS, ls[i]);
        sh[i] = add_shape(s, sp[i], NS, ls[i], eps[i], fmax(eps[i], 0.9), &st);
    }
    if (st != RUGO_OK) return st;
    add_body(s, "block", SCENE_ROLE_GROUND, block, 1, 0.0, 0.0, 0.0);
    /* Two fixed rocks near the ends keep the bouncing bodies on the block (the thesis' second fixed body). */
    add_body(s, "rock", SCENE_ROLE_OBSTACLE, obst, 1, 3.6, wave_at(&w, 3.6) + 0.3, 0.3);
    add_body(s, "rock2", SCENE_ROLE_OBSTACLE, obst, 1, -3.6, wave_at(&w, -3.6) + 0.3, 2.0);
    for (int i = 0; i < 4; ++i) {
        char name[24];
        snprintf(name, sizeof name, "body_e%.2f", eps[i]);
        add_body(s, name, SCENE_ROLE_OBJECT, sh[i], 0, xs[i], 1.8, 0.4 * i);
    }
    s->ground_top = -0.2; /* lowest valley of the wavy top */
    s->view_lo = rugo_v2(-4.2, -1.0);
    s->view_hi = rugo_v2(4.2, 2.5);
    return RUGO_OK;
}

/* The letters of "gráfica" as stroke outlines in a 0.4 m x-height, stroke 0.1 m; baseline y = 0. */
typedef struct letter {
    const char* name;
    rugo_vec2 path[8];
    int m;        /* path points; 0 = explicit polygon in path */
    double width; /* stroke width (path) */
    int poly_count;
} letter;

static int letter_outline(int which, rugo_vec2* poly) {
    static const rugo_vec2 g[] = {{0.15, 0.12}, {0.0, 0.12}, {0.0, 0.4}, {0.3, 0.4},
                                  {0.3, -0.2},  {0.0, -0.2}, {0.0, -0.1}};
    static const rugo_vec2 r[] = {{0.0, 0.0}, {0.0, 0.4}, {0.25, 0.4}, {0.25, 0.3}};
    static const rugo_vec2 a[] = {{0.0, 0.4}, {0.3, 0.4}, {0.3, 0.0}, {0.0, 0.0}, {0.0, 0.2}, {0.12, 0.2}};
    static const rugo_vec2 c[] = {{0.3, 0.4}, {0.0, 0.4}, {0.0, 0.0}, {0.3, 0.0}};
    static const rugo_vec2 accent[] = {{0.0, 0.0}, {0.1, 0.12}};
    static const rugo_vec2 f[] = {{0, 0},      {0.1, 0},      {0.1, 0.3},   {0.22, 0.3}, {0.22, 0.38},
                                  {0.1, 0.38}, {0.1, 0.5},    {0.28, 0.5},  {0.28, 0.6}, {0, 0.6},
                                  {0, 0.38},   {-0.08, 0.38}, {-0.08, 0.3}, {0, 0.3}};
    static const rugo_vec2 i_stem[] = {{0, 0}, {0.1, 0}, {0.1, 0.4}, {0, 0.4}};
    static const rugo_vec2 dot[] = {{0, 0}, {0.1, 0}, {0.1, 0.1}, {0, 0.1}};
    switch (which) {
    case 0:
        return stroke(g, 7, 0.1, poly);
    case 1:
        return stroke(r, 4, 0.1, poly);
    case 2:
        return stroke(a, 6, 0.1, poly);
    case 3:
        return stroke(accent, 2, 0.06, poly);
    case 4:
        memcpy(poly, f, sizeof f);
        return 14;
    case 5:
        memcpy(poly, i_stem, sizeof i_stem);
        return 4;
    case 6:
        memcpy(poly, dot, sizeof dot);
        return 4;
    default:
        return stroke(c, 4, 0.1, poly);
    }
}

static rugo_status build_grafica(scene* s) {
    enum { NB = 256, NL = 128, ND = 32, NBALL = 64 };
    /* Glyph outlines (shared by both a's); bodies in reading order, accent and dot after their letter. */
    static const char* glyph_names[8] = {"g", "r", "a", "accent", "f", "i", "i_dot", "c"};
    static rugo_vec2 bp[NB], gp[8][NL], ballp[NBALL];
    double lb[NB], lg[8][NL], lball[NBALL];
    const wave w = {0.02, 1.3, 0.0, 0.01, 0.45, 0.7};
    const rugo_tolerance_preset p = s->variant == 0 ? RUGO_PRESET_TIPO_2 : RUGO_PRESET_TIPO_3;
    snprintf(s->label, sizeof s->label, "%s", rugo_preset_name(p));
    s->name = "the word \"grafica\" as free letters on a fixed irregular block, hit by a ball";
    s->figure = "Fig. 7.10-7.11";
    s->measures = "letters' positions over time; final arrangement for tipo_2 vs tipo_3";
    s->duration = 5.0;
    block_outline(8.0, 0.6, &w, NB, bp);
    preset(p, 70, NB, lb);
    rugo_status st = RUGO_OK;
    rugo_shape* block = add_shape(s, bp, NB, lb, 0.5, 0.9, &st);
    rugo_shape* gs[8];
    for (int k = 0; k < 8; ++k) {
        static rugo_vec2 poly[64];
        int m = letter_outline(k, poly);
        int n = (k == 3 || k == 6) ? ND : NL;
        resample(poly, m, n, gp[k]);
        preset(p, 80 + (uint64_t)k, n, lg[k]);
        /* "diferentes coeficientes de restituição" (7.10): ε from 0.1 (g) to 0.66 (c), by glyph. */
        gs[k] = add_shape(s, gp[k], n, lg[k], 0.1 + 0.08 * k, 0.9, &st);
    }
    for (int i = 0; i < NBALL; ++i)
        ballp[i] = rugo_v2(0.25 * cos(PI2 * i / NBALL), 0.25 * sin(PI2 * i / NBALL));
    preset(p, 90, NBALL, lball);
    rugo_shape* ball = add_shape(s, ballp, NBALL, lball, 0.5, 0.9, &st);
    if (st != RUGO_OK) return st;
    add_body(s, "block", SCENE_ROLE_GROUND, block, 1, 0.0, 0.0, 0.0);
    /* g r á f i c a: glyph index per letter; the accent rides above the first a, the dot above the i. */
    static const int word[7] = {0, 1, 2, 4, 5, 7, 2};
    double x = -1.2;
    for (int l = 0; l < 7; ++l) {
        rugo_shape* sh = gs[word[l]];
        rugo_contour c;
        rugo_shape_level(sh, rugo_shape_finest_level(sh), &c);
        rugo_vec2 lo, hi;
        rugo_contour_bounds(c, &lo, &hi);
        double top = -1.0; /* highest point of the wavy top under the letter */
        for (double u = x; u <= x + hi.x - lo.x; u += 0.01)
            top = fmax(top, wave_at(&w, u));
        double bx = x - lo.x, by = rest_y(sh, block, 0, top);
        add_body(s, glyph_names[word[l]], SCENE_ROLE_OBJECT, sh, 0, bx, by, 0.0);
        if (l == 2) add_body(s, "accent", SCENE_ROLE_OBJECT, gs[3], 0, bx + 0.12, by + 0.53, 0.0);
        if (l == 4) add_body(s, "i_dot", SCENE_ROLE_OBJECT, gs[6], 0, bx, by + 0.47, 0.0);
        x += hi.x - lo.x + 0.12;
    }
    scene_body* b =
        add_body(s, "ball", SCENE_ROLE_MOVER, ball, 0, -3.0, rest_y(ball, block, 0, 0.03) + 0.1, 0.0);
    b->density = 4.0; /* a heavy ball, so that the hit carries through several letters */
    b->linear_velocity = rugo_v2(6.0, 0.0);
    s->ground_top = -0.04;
    s->view_lo = rugo_v2(-4.2, -0.8);
    s->view_hi = rugo_v2(4.2, 1.6);
    return RUGO_OK;
}

/* Fig. 7.12's "objects of arbitrary geometry" with fine geometric detail, so that coarse levels must
 * absorb real detail into λ (5.3): a rounded slab |x/hx|^2.5 + |y/hy|^2.5 = 1 (flat enough to slide
 * rather than roll), resampled to n points equally spaced by arc length (~9 mm apart for the scene's
 * slabs), each then moved along the slab's outward normal by h_k (metres), k = control point, with
 * `amp` the detail's scale:
 *   kind 0, toothed: square-wave teeth of period 8 points, depth ±amp (their fundamental is what level
 *           -2 cannot represent), knurled by a ripple of period 4 points, ±amp (what level -1 cannot);
 *   kind 1, wavy: ripples of period 3.5 points (±amp, lost at -1 and -2) and 5 points (±amp/2, lost
 *           at -2);
 *   kind 2, noisy: seeded Gaussian noise, σ = amp, clamped to ±2 amp: detail at every scale.
 * Measured with the detail estimator (q = 0.95) on such slabs: a sine of amplitude A and period 4 points
 * gives own^{-1} = 0.45 A (own^{-2} ~ 0); period 8 gives own^{-2} = 0.61 A (own^{-1} ~ 0); period 3.5
 * gives 0.38 A and 0.40 A; period 5 gives 0.11 A and 0.63 A; noise of σ gives 0.34 σ and 0.43 σ. */
static void detailed(int kind, uint64_t seed, double hx, double hy, double amp, int n, rugo_vec2* out) {
    enum { DENSE = 400 };
    static rugo_vec2 dense[DENSE], base[MAXP];
    for (int i = 0; i < DENSE; ++i) {
        double th = PI2 * i / DENSE, c = cos(th), sn = sin(th);
        dense[i] = rugo_v2(hx * (c < 0 ? -1.0 : 1.0) * pow(fabs(c), 0.8),
                           hy * (sn < 0 ? -1.0 : 1.0) * pow(fabs(sn), 0.8));
    }
    resample(dense, DENSE, n, base);
    rugo_rng rng;
    rugo_rng_seed(&rng, seed);
    for (int k = 0; k < n; ++k) {
        rugo_vec2 d = rugo_v2_sub(base[(k + 1) % n], base[(k + n - 1) % n]);
        double len = sqrt(rugo_v2_dot(d, d));
        rugo_vec2 nrm = rugo_v2(d.y / len, -d.x / len); /* outward for a counter-clockwise outline */
        double h;
        if (kind == 0)
            h = amp * (tanh(3.0 * sin(PI2 * k / 8.0)) + sin(PI2 * k / 4.0 + 0.5));
        else if (kind == 1)
            h = amp * (sin(PI2 * k / 3.5) + 0.5 * sin(PI2 * k / 5.0 + 1.0));
        else
            h = amp * fmax(-2.0, fmin(2.0, rugo_rng_gaussian(&rng)));
        out[k] = rugo_v2_add(base[k], rugo_v2_scale(h, nrm));
    }
}

static rugo_status build_levels(scene* s) {
    enum { NB = 256, NO = 256 };
    static rugo_vec2 bp[NB], op[3][NO];
    double lb[NB], lo[3][NO];
    static const int levels[3] = {-1, -2, 0};
    static const double amp[3] = {0.005, 0.006, 0.007};
    s->level = levels[s->variant];
    snprintf(s->label, sizeof s->label, "level%d", s->level);
    s->name = "three arbitrary objects with fine detail at a coarse level of detail";
    s->figure = "Fig. 7.12-7.13";
    s->measures = "friction μ at every contact and the distance each object slides";
    s->duration = 4.0;
    block_outline(14.0, 0.6, NULL, NB, bp);
    preset(RUGO_PRESET_TIPO_3, 0, NB, lb);
    rugo_status st = RUGO_OK;
    rugo_shape* block = add_shape(s, bp, NB, lb, 0.3, 0.9, &st);
    rugo_shape* sh[3];
    for (int i = 0; i < 3; ++i) {
        /* Toothed, wavy and noisy slabs: their finest curve carries detail of a few millimetres at the
         * scale of 1-8 control points (~1-8 cm), which levels -1 and -2 cannot represent. */
        detailed(i, 200 + (uint64_t)i, 0.45, 0.2, amp[i], NO, op[i]);
        preset(RUGO_PRESET_TIPO_3, 0, NO, lo[i]);
        sh[i] = add_shape(s, op[i], NO, lo[i], 0.3, 0.9, &st);
    }
    if (st != RUGO_OK) return st;
    add_body(s, "block", SCENE_ROLE_GROUND, block, 1, 0.0, 0.0, 0.0);
    static const char* names[3] = {"toothed", "wavy", "noisy"};
    for (int i = 0; i < 3; ++i) {
        scene_body* b = add_body(s, names[i], SCENE_ROLE_OBJECT, sh[i], 0, -6.0 + 2.2 * i, 0.0, 0.0);
        b->transform.p.y = rest_y(sh[i], block, s->level, 0.0) + 0.01;
        b->linear_velocity = rugo_v2(4.0, 0.0);
    }
    s->view_lo = rugo_v2(-7.2, -0.8);
    s->view_hi = rugo_v2(7.2, 1.5);
    return RUGO_OK;
}

static rugo_status build_demo(scene* s) {
    enum { NS = 7, NP = 128 };
    static rugo_vec2 pts[NS][NP];
    double lam[NS][NP];
    snprintf(s->label, sizeof s->label, "demo");
    s->name = "rough rocks, gears and blobs with ordinary boxes and circles in a container";
    s->figure = "README demo";
    s->measures = "time per step, contacts, memory per rough body, settling, determinism hash";
    s->duration = 6.0;
    /* Shapes: three rocks, two gears, two blobs; several bodies share each. */
    static const rugo_tolerance_preset rough[NS] = {
        RUGO_PRESET_TIPO_2, RUGO_PRESET_TIPO_5, RUGO_PRESET_TIPO_3, RUGO_PRESET_TIPO_1,
        RUGO_PRESET_TIPO_3, RUGO_PRESET_TIPO_2, RUGO_PRESET_TIPO_5};
    blob(300, 0.45, 1.3, 2.0, NP, pts[0]);
    blob(301, 0.35, 1.0, 2.5, NP, pts[1]);
    blob(302, 0.55, 1.5, 1.5, NP, pts[2]);
    gear(12, 0.4, 0.1, NP, pts[3]);
    gear(8, 0.3, 0.14, NP, pts[4]);
    blob(303, 0.3, 1.1, 0.6, NP, pts[5]);
    blob(304, 0.25, 1.4, 0.8, NP, pts[6]);
    rugo_status st = RUGO_OK;
    rugo_shape* sh[NS];
    for (int k = 0; k < NS; ++k) {
        preset(rough[k], 310 + (uint64_t)k, NP, lam[k]);
        sh[k] = add_shape(s, pts[k], NP, lam[k], 0.3, 0.9, &st);
    }
    if (st != RUGO_OK) return st;
    /* The container: a static chain, walls and a gently irregular floor, right wall to left wall so
     * that the open side is to the right of the direction of travel (Box2D 2.4 chains are one-sided). */
    int m = 0;
    s->chain[m++] = rugo_v2(7.0, 12.0);
    s->chain[m++] = rugo_v2(7.0, 0.6);
    for (int i = 28; i >= 0; --i) {
        double x = -7.0 + 0.5 * i;
        s->chain[m++] = rugo_v2(x, 0.15 * sin(1.3 * x) + 0.08 * sin(3.1 * x + 0.5) + 0.01 * x * x);
    }
    s->chain[m++] = rugo_v2(-7.0, 0.6);
    s->chain[m++] = rugo_v2(-7.0, 12.0);
    scene_body* g = add_body(s, "container", SCENE_ROLE_GROUND, NULL, 1, 0.0, 0.0, 0.0);
    g->kind = SCENE_CHAIN;
    g->chain = s->chain;
    g->chain_count = m;
    g->friction = 0.6;
    g->restitution = 0.1;
    /* 48 bodies in a 8 x 6 grid: rough in every other cell, boxes and circles between. */
    rugo_rng rng;
    rugo_rng_seed(&rng, 2000);
    int nr = 0, nb = 0, nc = 0;
    for (int row = 0; row < 6; ++row)
        for (int col = 0; col < 8; ++col) {
            double x = -5.6 + 1.6 * col + rugo_rng_range(&rng, -0.15, 0.15), y = 2.0 + 1.55 * row;
            double ang = rugo_rng_range(&rng, 0.0, PI2);
            char name[24];
            scene_body* b;
            if ((row + col) % 2 == 0) {
                snprintf(name, sizeof name, "rough%d", nr);
                b = add_body(s, name, SCENE_ROLE_OBJECT, sh[nr % NS], 0, x, y, ang);
                ++nr;
            } else if (col % 4 == 1 || col % 4 == 2) {
                snprintf(name, sizeof name, "box%d", nb++);
                b = add_body(s, name, SCENE_ROLE_OBJECT, NULL, 0, x, y, ang);
                b->kind = SCENE_BOX;
                b->half_extents = rugo_v2(rugo_rng_range(&rng, 0.18, 0.4), rugo_rng_range(&rng, 0.15, 0.3));
            } else {
                snprintf(name, sizeof name, "circle%d", nc++);
                b = add_body(s, name, SCENE_ROLE_OBJECT, NULL, 0, x, y, ang);
                b->kind = SCENE_CIRCLE;
                b->radius = rugo_rng_range(&rng, 0.15, 0.32);
            }
            if (b == NULL) return RUGO_ERR_BAD_ARGUMENT;
            b->linear_velocity = rugo_v2(rugo_rng_range(&rng, -1.0, 1.0), rugo_rng_range(&rng, -1.0, 0.0));
            b->angular_velocity = rugo_rng_range(&rng, -2.0, 2.0);
        }
    s->ground_top = -0.5;
    s->view_lo = rugo_v2(-7.5, -0.5);
    s->view_hi = rugo_v2(7.5, 12.0);
    return RUGO_OK;
}

rugo_status scene_create(scene_id id, int variant, scene* out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    memset(out, 0, sizeof *out);
    if (variant < 0 || variant >= scene_variant_count(id)) return RUGO_ERR_BAD_ARGUMENT;
    out->id = id;
    out->variant = variant;
    out->gravity = rugo_v2(0.0, -9.81);
    out->time_step = 1.0 / 60.0;
    out->ground_top = 0.0;
    rugo_status st;
    switch (id) {
    case SCENE_BALL:
        st = build_ball(out);
        break;
    case SCENE_THROWN:
        st = build_thrown(out);
        break;
    case SCENE_FOUR_BODIES:
        st = build_four(out);
        break;
    case SCENE_GRAFICA:
        st = build_grafica(out);
        break;
    case SCENE_LEVELS:
        st = build_levels(out);
        break;
    default:
        st = build_demo(out);
        break;
    }
    if (st != RUGO_OK) {
        scene_destroy(out);
        memset(out, 0, sizeof *out);
    }
    return st;
}

void scene_destroy(scene* s) {
    if (s == NULL) return;
    for (int i = 0; i < s->shape_count; ++i)
        rugo_shape_destroy(s->shapes[i]);
    s->shape_count = 0;
    s->body_count = 0;
}
