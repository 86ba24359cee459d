/* Roughness: the tolerances a shape file's roughness description gives each finest segment (shared by
 * the commands that build shapes), and the commands roughen and tolerances. */
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char* estimator_name(rugo_tolerance_estimator e) {
    return e == RUGO_ESTIMATOR_COEFFICIENTS ? "coefficients" : "detail";
}

/* The roughness settings of a shape: its own, or the defaults when it has none. */
rugo_roughness_desc roughness_of(const rugo_shape_desc* d) {
    return d->has_roughness ? d->roughness : rugo_default_roughness_desc();
}

/* The tolerance of every finest segment (n values, malloc'd into *out) as `r` gives them, or 0 when r
 * is NULL (a shape without roughness is smooth). In the file's own segment numbering, or, when
 * `reversed`, in that of the reversed (counter-clockwise) points, where the file's segment j is
 * segment n-2-j. `points` are the n control points in the numbering of the result (arc-length
 * roughness is resolved on them, in the file's order). Returns 0 or EXIT_INPUT after a message. */
int finest_tolerances(const char* path, const rugo_roughness_desc* r, const rugo_vec2* points, int n,
                      int reversed, rugo_real** out) {
    *out = NULL;
    rugo_real* in = calloc((size_t)n, sizeof *in);
    rugo_real* res = calloc((size_t)n, sizeof *res);
    rugo_vec2* file_order = reversed ? malloc(sizeof *file_order * (size_t)n) : NULL;
    if (in == NULL || res == NULL || (reversed && file_order == NULL)) {
        free(in);
        free(res);
        free(file_order);
        return fail("tolerances", RUGO_ERR_OUT_OF_MEMORY);
    }
    for (int k = 0; reversed && k < n; ++k)
        file_order[k] = points[n - 1 - k]; /* undo the reversal */
    rugo_contour fc = {reversed ? file_order : points, n};
    rugo_status st = r ? rugo_roughness_tolerances_on_contour(r, fc, NULL, in) : RUGO_OK;
    free(file_order);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo %s: %s: roughness: %s (status %d)\n", g_command, path, rugo_status_string(st),
                (int)st);
        free(in);
        free(res);
        return EXIT_INPUT;
    }
    for (int k = 0; k < n; ++k)
        res[k] = reversed ? in[((n - 2 - k) % n + n) % n] : in[k];
    free(in);
    *out = res;
    return 0;
}

/* The roughness to write with the (counter-clockwise) points of a shape whose geometry an edit changed:
 * the input's, re-numbered if the points were reversed (a list then, since presets start at segment 0),
 * without the perturbation, which belonged to the old geometry. *tol receives an array to free. */
int carried_roughness(const char* path, const rugo_shape_desc* in, int reversed, const rugo_vec2* points,
                      rugo_roughness_desc* out, rugo_real** tol) {
    *tol = NULL;
    *out = in->roughness;
    out->has_perturbation = false;
    out->perturbation_points = NULL;
    out->perturbation_count = 0;
    out->perturbation_levels = 0;
    if (!reversed || in->roughness.kind == RUGO_ROUGHNESS_CONSTANT) return 0;
    int rc = finest_tolerances(path, &in->roughness, points, in->count, 1, tol);
    if (rc) return rc;
    out->kind = RUGO_ROUGHNESS_TOLERANCES;
    out->tolerances = *tol;
    out->tolerance_count = in->count;
    return 0;
}

static void print_reals(FILE* f, const rugo_real* v, int n) {
    fputc('[', f);
    for (int i = 0; i < n; ++i)
        fprintf(f, "%s%.17g", i ? ", " : "", v[i]);
    fputc(']', f);
}

/* Reads a CSV roughness profile (docs/roughness.md); 0, or EXIT_INPUT after a message naming the file,
 * line, column and sample. */
static int load_profile_csv(const char* file, rugo_roughness_profile* profile) {
    rugo_text text;
    rugo_status st = rugo_read_file(file, NULL, &text);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo %s: %s: cannot read: %s (status %d)\n", g_command, file, rugo_status_string(st),
                (int)st);
        return EXIT_INPUT;
    }
    rugo_parse_error err;
    st = rugo_roughness_profile_parse_csv(text.data, text.length, NULL, profile, &err);
    rugo_text_free(&text);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo %s: %s:%d:%d: %s%s%s (status %d: %s)\n", g_command, file, err.line, err.column,
                err.path, err.path[0] ? ": " : "", err.message, (int)st, rugo_status_string(st));
        return EXIT_INPUT;
    }
    return 0;
}

int cmd_roughen(int argc, char** argv) {
    static const char* const vals[] = {"--method",  "--preset",   "--seed",     "--levels",
                                       "--profile", "--constant", "--friction", "--max-band-fraction",
                                       "-o",        NULL};
    static const char* const flag_opts[] = {"--absolute", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, flag_opts, &a);
    if (rc) return rc;
    if (a.positional_count != 1) return usage_error("expects one shape file%s", "");
    const char *mv = opt(&a, "--method", NULL), *pv = opt(&a, "--preset", NULL),
               *sv = opt(&a, "--seed", NULL), *lv = opt(&a, "--levels", NULL),
               *fv = opt(&a, "--profile", NULL), *cv = opt(&a, "--constant", NULL),
               *muv = opt(&a, "--friction", NULL), *bfv = opt(&a, "--max-band-fraction", NULL);
    int absolute = 0;
    opt(&a, "--absolute", &absolute);
    double constant = 0.0, band_fraction = 0.05;
    rugo_vec2 mu_range = {0.0, 0.0};
    if ((pv != NULL) + (fv != NULL) + (cv != NULL) > 1)
        return usage_error("--constant, --preset and --profile exclude each other%s", "");
    if (cv && (parse_real(cv, &constant) != 0 || !(constant >= 0.0)))
        return usage_error("--constant must be a band >= 0 in the shape's length units (e.g. 0.002 for 2 mm "
                           "in metres), got '%s'",
                           cv);
    if (absolute && !pv) return usage_error("--absolute applies to --preset%s", "");
    if (muv) {
        char buf[128];
        const char* colon = strchr(muv, ':');
        size_t k = colon ? (size_t)(colon - muv) : 0;
        int ok = colon != NULL && k < sizeof buf;
        if (ok) {
            memcpy(buf, muv, k);
            buf[k] = '\0';
            ok = parse_real(buf, &mu_range.x) == 0 && parse_real(colon + 1, &mu_range.y) == 0 &&
                 mu_range.x >= 0.0 && mu_range.y >= mu_range.x;
        }
        if (!ok)
            return usage_error("--friction must be MIN:MAX with 0 <= MIN <= MAX (e.g. 0.3:0.9), got '%s'",
                               muv);
    }
    if (bfv && (parse_real(bfv, &band_fraction) != 0 || !(band_fraction > 0.0)))
        return usage_error("--max-band-fraction must be a number > 0 (e.g. 0.05), got '%s'", bfv);
    int method = -1; /* -1: the tolerance library only; else a rugo_roughen_method */
    int levels = 2;
    rugo_tolerance_preset preset = RUGO_PRESET_TIPO_1;
    uint64_t seed = 0;
    if (mv && strcmp(mv, "wavelet") == 0)
        method = RUGO_ROUGHEN_WAVELET;
    else if (mv && strcmp(mv, "local") == 0)
        method = RUGO_ROUGHEN_LOCAL;
    else if (mv && strcmp(mv, "library") != 0)
        return usage_error("--method must be wavelet, local or library, got '%s'", mv);
    if (pv && rugo_preset_from_name(pv, &preset) != RUGO_OK)
        return usage_error("--preset must be tipo_1, tipo_2, tipo_3 or tipo_5, got '%s'", pv);
    if (sv && parse_seed(sv, &seed) != 0)
        return usage_error("--seed must be an integer from 0 to 9007199254740992 (2^53), got '%s'", sv);
    if (lv && method < 0) return usage_error("--levels applies to --method wavelet or local%s", "");
    if (lv && parse_int(lv, 1, RUGO_MAX_PERTURBATION_LEVELS, &levels) != 0)
        return usage_error("--levels must be an integer from 1 to 20, got '%s'", lv);
    rugo_shape_desc desc;
    if ((rc = load_shape(a.positional[0], &desc))) return rc;
    const char* path = a.positional[0];
    int flags = RUGO_CHECK_SELF_INTERSECTION | (method >= 0 ? RUGO_CHECK_POWER_OF_TWO : 0);
    rugo_contour_problem pr;
    rugo_status st = rugo_contour_check(desc.control_points, desc.count, flags, &pr, NULL);
    if (st == RUGO_OK && method >= 0 && ((long long)desc.count << levels) > RUGO_MAX_CONTROL_POINTS)
        st = RUGO_ERR_TOO_MANY_POINTS;
    if (st != RUGO_OK) {
        report_problem(path, st, &pr, &desc);
        rugo_shape_desc_free(&desc);
        return EXIT_INPUT;
    }
    rugo_roughness_profile profile;
    memset(&profile, 0, sizeof profile);
    if (fv && (rc = load_profile_csv(fv, &profile))) {
        rugo_shape_desc_free(&desc);
        return rc;
    }
    int n = desc.count;
    int reversed = rugo_contour_orient_ccw(desc.control_points, n);
    rugo_roughness_desc r = roughness_of(&desc);
    if (pv) {
        r.kind = RUGO_ROUGHNESS_PRESET;
        r.preset = preset;
    }
    if (fv) { /* resolved on the input's points, in its own order, below */
        r.kind = RUGO_ROUGHNESS_PROFILE;
        r.profile = profile.samples;
        r.profile_count = profile.count;
    }
    if (cv) {
        r.kind = RUGO_ROUGHNESS_CONSTANT;
        r.constant = constant;
    }
    if (sv) r.seed = seed;
    rugo_real* tol = NULL;
    rugo_vec2* pert = NULL;
    if ((rc = finest_tolerances(path, &r, desc.control_points, n, reversed, &tol))) goto done;
    /* The shape's size: the larger side of its curve's bounds. */
    rugo_vec2 lo, hi;
    rugo_contour_bounds((rugo_contour){desc.control_points, n}, &lo, &hi);
    const double size = fmax(hi.x - lo.x, hi.y - lo.y);
    if (pv && !absolute) { /* the thesis' values are per RUGO_PRESET_REFERENCE_SIZE units of size */
        for (int k = 0; k < n; ++k)
            tol[k] *= size / RUGO_PRESET_REFERENCE_SIZE;
    }
    double band_hi = 0.0;
    for (int k = 0; k < n; ++k)
        band_hi = fmax(band_hi, tol[k]);
    if (band_hi > band_fraction * size)
        fprintf(stderr,
                "rugo %s: warning: %s: the largest band, %.6g, is %.3g%% of the shape's size %.6g (more than "
                "--max-band-fraction %.3g): the surface is terrain rather than a finish; give a smaller "
                "--constant%s\n",
                g_command, path, band_hi, 100.0 * band_hi / size, size, band_fraction,
                pv && absolute ? " or drop --absolute" : "");
    if (muv) {
        /* μ MIN at the smallest band, MAX at the largest; one band: MIN at 0, MAX at the band. The
         * band at a point, λ(t), interpolates the segments' bands by a cubic that can overshoot them
         * where they jump (SPEC 6.3), so the range is that of λ(t), sampled densely: μ at any point
         * of the finest level then stays within MIN..MAX. */
        double l0 = HUGE_VAL, l1 = 0.0;
        for (int k = 0; k < n; ++k)
            for (int i = 0; i <= 64; ++i) {
                const double lam = rugo_tolerance_at(tol, n, k, i / 64.0, 0.0);
                l0 = fmin(l0, lam);
                l1 = fmax(l1, lam);
            }
        if (!(l0 < l1)) l0 = 0.0;
        if (!(l1 > 0.0)) l1 = 1.0;
        rugo_status fst = mu_range.x == mu_range.y
                              ? rugo_friction_calibrate(0.0, 1.0, mu_range.x, mu_range.x, &r.friction)
                              : rugo_friction_calibrate(l0, l1, mu_range.x, mu_range.y, &r.friction);
        if (fst != RUGO_OK) {
            rc = fail("--friction", fst);
            goto done;
        }
    }
    /* The resolved values are written, not the preset: the file then says exactly what the shape is,
     * in the numbering of the points written (counter-clockwise), whatever later versions of the
     * presets do. */
    rugo_roughness_desc out = r;
    out.kind = RUGO_ROUGHNESS_TOLERANCES;
    out.tolerances = tol;
    out.tolerance_count = n;
    out.has_perturbation = false;
    out.perturbation_points = NULL;
    out.perturbation_count = 0;
    out.perturbation_levels = 0;
    if (method >= 0) {
        int m = n << levels;
        pert = malloc(sizeof *pert * (size_t)m);
        if (pert == NULL) {
            rc = fail("roughen", RUGO_ERR_OUT_OF_MEMORY);
            goto done;
        }
        rugo_roughen_def def = rugo_default_roughen_def();
        def.points = desc.control_points;
        def.count = n;
        def.tolerances = tol;
        def.q = r.q;
        def.method = (rugo_roughen_method)method;
        def.levels = levels;
        def.filter = desc.filter;
        def.seed = r.seed;
        st = rugo_roughen(&def, pert);
        if (st != RUGO_OK) {
            rc = fail("roughen", st);
            goto done;
        }
        out.has_perturbation = true;
        out.perturbation_method = (rugo_roughen_method)method;
        out.perturbation_levels = levels;
        out.perturbation_points = pert;
        out.perturbation_count = m;
    }
    rugo_shape_desc w;
    memset(&w, 0, sizeof w);
    w.control_points = desc.control_points;
    w.count = n;
    w.filter = desc.filter;
    w.has_roughness = true;
    w.roughness = out;
    rc = write_desc(opt(&a, "-o", NULL), &w, NULL);
done:
    free(pert);
    free(tol);
    rugo_roughness_profile_free(&profile);
    rugo_shape_desc_free(&desc);
    return rc;
}

int cmd_tolerances(int argc, char** argv) {
    static const char* const vals[] = {"--estimator", "--at", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, NULL, &a);
    if (rc) return rc;
    if (a.positional_count != 1) return usage_error("expects one shape file%s", "");
    const char *ev = opt(&a, "--estimator", NULL), *at = opt(&a, "--at", NULL);
    rugo_tolerance_estimator est = RUGO_ESTIMATOR_DETAIL;
    if (ev && strcmp(ev, "coefficients") == 0)
        est = RUGO_ESTIMATOR_COEFFICIENTS;
    else if (ev && strcmp(ev, "detail") != 0)
        return usage_error("--estimator must be detail or coefficients, got '%s'", ev);
    rugo_vec2 st_pair = {0.0, 0.0};
    if (at && (parse_pair(at, &st_pair) != 0 || st_pair.x != floor(st_pair.x) || st_pair.x < 0.0 ||
               st_pair.x > (double)RUGO_MAX_CONTROL_POINTS || !(st_pair.y >= 0.0 && st_pair.y <= 1.0)))
        return usage_error("--at SEGMENT,T needs an integer segment >= 0 and 0 <= T <= 1, got '%s'", at);
    const char* path = a.positional[0];
    rugo_shape_desc desc;
    rugo_shape* baked = NULL;
    if ((rc = load_shape_any(path, &desc, ev == NULL && at == NULL ? &baked : NULL))) return rc;
    if (baked != NULL) { /* the levels stored in the file, exactly; q and estimator are not stored */
        printf("{\"q\": null, \"estimator\": null, \"reversed\": %s, \"baked\": true, \"levels\": [",
               rugo_shape_was_reversed(baked) ? "true" : "false");
        for (int j = rugo_shape_finest_level(baked); j >= rugo_shape_coarsest_level(baked); --j) {
            rugo_tolerance_level L;
            rugo_shape_tolerance_level(baked, j, &L);
            printf("%s\n  {\"level\": %d, \"tolerance\": ", j == rugo_shape_finest_level(baked) ? "" : ",",
                   j);
            print_reals(stdout, L.total, L.count);
            printf(", \"own\": ");
            print_reals(stdout, L.own, L.count);
            printf(", \"bound\": ");
            print_reals(stdout, L.bound, L.count);
            printf("}");
        }
        printf("\n]}\n");
        rugo_shape_destroy(baked);
        rugo_shape_desc_free(&desc);
        return 0;
    }
    rugo_roughness_desc r = roughness_of(&desc);
    const rugo_roughness_desc* source = desc.has_roughness ? &desc.roughness : NULL;
    rugo_real* tol = NULL;
    if (at) {
        /* A point query needs only the finest tolerances: any count, the file's own numbering (the
         * interpolation is symmetric, so the reversed curve gives the same value at the same point). */
        if ((rc = check_outline(path, &desc, RUGO_CHECK_SELF_INTERSECTION))) goto done;
        int seg = (int)st_pair.x;
        if (seg >= desc.count) {
            fprintf(stderr, "rugo tolerances: --at segment must be below the control point count %d\n",
                    desc.count);
            rc = EXIT_USAGE;
            goto done;
        }
        if ((rc = finest_tolerances(path, source, desc.control_points, desc.count, 0, &tol))) goto done;
        rugo_real lambda = rugo_tolerance_at(tol, desc.count, seg, st_pair.y, 0.0);
        printf("{\"segment\": %d, \"t\": %.17g, \"tolerance\": %.17g, \"friction\": %.17g, \"restitution\": "
               "%.17g}\n",
               seg, st_pair.y, lambda, rugo_friction(&r.friction, lambda), r.restitution.epsilon);
        goto done;
    }
    rugo_pyramid* p = NULL;
    if ((rc = build_pyramid(path, &desc, desc.filter, 0, &p))) goto done;
    int reversed = rugo_pyramid_was_reversed(p);
    rugo_contour ccw; /* the pyramid's finest level: the points, counter-clockwise */
    rugo_pyramid_level(p, rugo_pyramid_finest_level(p), &ccw);
    if ((rc = finest_tolerances(path, source, ccw.points, desc.count, reversed, &tol))) {
        rugo_pyramid_destroy(p);
        goto done;
    }
    rugo_tolerance_def def = rugo_default_tolerance_def();
    def.pyramid = p;
    def.finest = tol;
    def.count = desc.count;
    def.q = r.q;
    def.estimator = ev ? est : r.estimator;
    rugo_tolerances* t = NULL;
    rugo_status st = rugo_tolerances_create(&def, &t);
    rugo_pyramid_destroy(p);
    if (st != RUGO_OK) {
        rc = fail("tolerances", st);
        goto done;
    }
    printf("{\"q\": %.17g, \"estimator\": \"%s\", \"reversed\": %s, \"levels\": [", def.q,
           estimator_name(def.estimator), reversed ? "true" : "false");
    int finest = rugo_tolerances_finest_level(t), coarsest = rugo_tolerances_coarsest_level(t);
    for (int j = finest; j >= coarsest; --j) {
        rugo_tolerance_level L;
        rugo_tolerances_level(t, j, &L);
        printf("%s\n  {\"level\": %d, \"tolerance\": ", j == finest ? "" : ",", j);
        print_reals(stdout, L.total, L.count);
        printf(", \"own\": ");
        print_reals(stdout, L.own, L.count);
        printf(", \"bound\": ");
        print_reals(stdout, L.bound, L.count);
        printf("}");
    }
    printf("\n]}\n");
    rugo_tolerances_destroy(t);
done:
    free(tol);
    rugo_shape_desc_free(&desc);
    return rc;
}
