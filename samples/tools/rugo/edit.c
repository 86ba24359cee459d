/* The commands that edit a shape's geometry: decompose (the wavelet pyramid), refine, deform (a point
 * moved in multiresolution) and fit (a contour through points, with the Eigen shim). */
#include "cli.h"
#ifdef RUGO_HAVE_FIT
#include "rugo/fit.h"
#endif

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void print_points(FILE* f, const rugo_vec2* p, int n) {
    fputc('[', f);
    for (int i = 0; i < n; ++i)
        fprintf(f, "%s[%.17g, %.17g]", i ? ", " : "", p[i].x, p[i].y);
    fputc(']', f);
}

static int filter_option(const args* a, const rugo_shape_desc* desc, rugo_filter* f) {
    const char* name = opt(a, "--filter", NULL);
    *f = desc->filter;
    if (name && rugo_filter_from_name(name, f) != RUGO_OK)
        return usage_error("unknown filter '%s' (cdf4.2, cdf4.4, cdf4.6, cdf4.8, cdf4.12)", name);
    return 0;
}

int cmd_decompose(int argc, char** argv) {
    static const char* const vals[] = {"--filter", "--levels", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, NULL, &a);
    if (rc) return rc;
    if (a.positional_count != 1) return usage_error("expects one shape file%s", "");
    rugo_shape_desc desc;
    if ((rc = load_shape(a.positional[0], &desc))) return rc;
    rugo_filter filter;
    if ((rc = filter_option(&a, &desc, &filter))) goto done;
    int J = log2_exact(desc.count);
    if (J < 2) {
        rugo_contour_problem none = {-1, -1, -1, {0.0, 0.0}};
        report_problem(a.positional[0], desc.count < 4 ? RUGO_ERR_TOO_FEW_POINTS : RUGO_ERR_NOT_POWER_OF_TWO,
                       &none, &desc);
        rc = EXIT_INPUT;
        goto done;
    }
    int levels = J - 2;
    const char* lv = opt(&a, "--levels", NULL);
    if (lv && parse_int(lv, 1, J - 2 > 0 ? J - 2 : 1, &levels) != 0) {
        fprintf(stderr, "rugo decompose: --levels must be an integer from 1 to %d for %d control points\n",
                J - 2, desc.count);
        rc = EXIT_USAGE;
        goto done;
    }
    if (levels < 1) {
        fprintf(stderr, "rugo decompose: %d control points cannot be decomposed (a level needs >= 4)\n",
                desc.count);
        rc = EXIT_INPUT;
        goto done;
    }
    rugo_pyramid* p = NULL;
    if ((rc = build_pyramid(a.positional[0], &desc, filter, J - levels, &p))) goto done;
    printf("{\"filter\": \"%s\", \"levels\": [", rugo_filter_name(filter));
    for (int j = J - 1; j >= J - levels; --j) {
        rugo_contour c;
        const rugo_vec2 *dw, *dl;
        rugo_pyramid_level(p, j, &c);
        rugo_pyramid_details(p, j, &dw, &dl);
        printf("%s\n  {\"level\": %d, \"control_points\": ", j == J - 1 ? "" : ",", j);
        print_points(stdout, c.points, c.count);
        printf(", \"details\": ");
        print_points(stdout, dw, c.count);
        printf("}");
    }
    printf("\n]}\n");
    rugo_pyramid_destroy(p);
done:
    rugo_shape_desc_free(&desc);
    return rc;
}

int cmd_refine(int argc, char** argv) {
    static const char* const vals[] = {"--times", "-o", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, NULL, &a);
    if (rc) return rc;
    if (a.positional_count != 1) return usage_error("expects one shape file%s", "");
    int times = 1;
    const char* tv = opt(&a, "--times", NULL);
    if (tv && parse_int(tv, 1, 10, &times) != 0) return usage_error("--times must be 1..10, got '%s'", tv);
    rugo_shape_desc desc;
    if ((rc = load_shape(a.positional[0], &desc))) return rc;
    rugo_contour_problem pr;
    rugo_status st =
        rugo_contour_check(desc.control_points, desc.count, RUGO_CHECK_SELF_INTERSECTION, &pr, NULL);
    if (st == RUGO_OK && ((long)desc.count << times) > RUGO_MAX_CONTROL_POINTS) st = RUGO_ERR_TOO_MANY_POINTS;
    if (st != RUGO_OK) {
        report_problem(a.positional[0], st, &pr, &desc);
        rugo_shape_desc_free(&desc);
        return EXIT_INPUT;
    }
    rugo_contour_orient_ccw(desc.control_points, desc.count);
    int n = desc.count;
    rugo_vec2* cur = malloc(sizeof *cur * (size_t)n);
    if (cur == NULL) {
        rugo_shape_desc_free(&desc);
        return fail("refine", RUGO_ERR_OUT_OF_MEMORY);
    }
    memcpy(cur, desc.control_points, sizeof *cur * (size_t)n);
    for (int i = 0; i < times && rc == 0; ++i) {
        rugo_vec2* next = malloc(sizeof *next * (size_t)n * 2);
        if (next == NULL) {
            rc = fail("refine", RUGO_ERR_OUT_OF_MEMORY);
            break;
        }
        st = rugo_wavelet_refine(cur, n, next);
        free(cur);
        cur = next;
        n *= 2;
        if (st != RUGO_OK) rc = fail("refine", st);
    }
    if (rc == 0) rc = write_shape(opt(&a, "-o", NULL), cur, n, desc.filter, NULL);
    free(cur);
    rugo_shape_desc_free(&desc);
    return rc;
}

int cmd_deform(int argc, char** argv) {
    static const char* const vals[] = {"--at", "--delta", "--levels", "--w", "--details", "-o", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, NULL, &a);
    if (rc) return rc;
    if (a.positional_count != 1) return usage_error("expects one shape file%s", "");
    const char *at = opt(&a, "--at", NULL), *dv = opt(&a, "--delta", NULL);
    double u = 0.0, w = 0.0;
    rugo_vec2 delta;
    int spread = 1;
    rugo_detail_mode mode = RUGO_DETAILS_FIXED;
    if (at == NULL || parse_real(at, &u) != 0 || u < 0.0)
        return usage_error("--at U (curve parameter >= 0) is required%s", "");
    if (dv == NULL || parse_pair(dv, &delta) != 0) return usage_error("--delta DX,DY is required%s", "");
    const char *lv = opt(&a, "--levels", NULL), *wv = opt(&a, "--w", NULL), *mv = opt(&a, "--details", NULL);
    if (lv && parse_int(lv, 1, 30, &spread) != 0)
        return usage_error("--levels must be a positive integer, got '%s'", lv);
    if (wv && parse_real(wv, &w) != 0) return usage_error("--w must be a number, got '%s'", wv);
    if (mv && strcmp(mv, "fixed") != 0 && strcmp(mv, "local") != 0)
        return usage_error("--details must be fixed or local, got '%s'", mv);
    if (mv && strcmp(mv, "local") == 0) mode = RUGO_DETAILS_LOCAL;
    rugo_shape_desc desc;
    if ((rc = load_shape(a.positional[0], &desc))) return rc;
    rugo_pyramid* p = NULL;
    if ((rc = build_pyramid(a.positional[0], &desc, desc.filter, 0, &p))) goto done;
    int J = rugo_pyramid_finest_level(p);
    if (u >= (double)(1 << J)) {
        fprintf(stderr, "rugo deform: --at must be below the control point count %d\n", 1 << J);
        rc = EXIT_USAGE;
        goto free_pyramid;
    }
    if (spread > J - rugo_pyramid_coarsest_level(p) + 1) {
        fprintf(stderr, "rugo deform: --levels at most %d for this shape\n",
                J - rugo_pyramid_coarsest_level(p) + 1);
        rc = EXIT_USAGE;
        goto free_pyramid;
    }
    int seg = (int)floor(u);
    double t = u - seg;
    if (rugo_pyramid_was_reversed(p)) { /* the input was clockwise: map its parameter onto the stored curve */
        seg = (1 << J) - 2 - seg;
        t = 1.0 - t;
        if (t >= 1.0) {
            t -= 1.0;
            seg += 1;
        }
        seg = (seg % (1 << J) + (1 << J)) % (1 << J);
    }
    rugo_contour c;
    rugo_pyramid_level(p, J, &c);
    rugo_vec2 before = rugo_contour_point(c, seg, t);
    double weights[32];
    rugo_status st = rugo_pyramid_deform(p, seg, t, delta, spread, w, mode, weights);
    if (st != RUGO_OK) {
        rc = fail("deform", st);
        goto free_pyramid;
    }
    rugo_pyramid_level(p, J, &c);
    rugo_vec2 after = rugo_contour_point(c, seg, t);
    char extra[2048];
    int len = snprintf(extra, sizeof extra,
                       "\"deformation\": {\"point_before\": [%.17g, %.17g], \"point_after\": [%.17g, %.17g], "
                       "\"moved\": [%.17g, %.17g], \"weights\": [",
                       before.x, before.y, after.x, after.y, after.x - before.x, after.y - before.y);
    for (int i = 0; i < spread && len < (int)sizeof extra; ++i)
        len += snprintf(extra + len, sizeof extra - (size_t)len, "%s%.17g", i ? ", " : "", weights[i]);
    if (len < (int)sizeof extra) snprintf(extra + len, sizeof extra - (size_t)len, "]}");
    rugo_shape_desc shape_out;
    memset(&shape_out, 0, sizeof shape_out);
    shape_out.control_points = (rugo_vec2*)c.points;
    shape_out.count = c.count;
    shape_out.filter = desc.filter;
    rugo_real* carried = NULL;
    if (desc.has_roughness) {
        shape_out.has_roughness = true;
        rc = carried_roughness(a.positional[0], &desc, rugo_pyramid_was_reversed(p), c.points,
                               &shape_out.roughness, &carried);
    }
    if (rc == 0) rc = write_desc(opt(&a, "-o", NULL), &shape_out, extra);
    free(carried);
free_pyramid:
    rugo_pyramid_destroy(p);
done:
    rugo_shape_desc_free(&desc);
    return rc;
}

#ifdef RUGO_HAVE_FIT
/* Reads a points file for `fit` (the point lists `import` also reads): JSON {"points": [...]} or plain text,
 * one "x,y" or "x y" per line (rugo_points_text_parse). Returns 0, or EXIT_INPUT after a message. */
static int load_points(const char* path, rugo_point_list* pts) {
    rugo_text text;
    rugo_status st = rugo_read_file(path, NULL, &text);
    if (st != RUGO_OK) return fail(path, st);
    rugo_parse_error err;
    st = rugo_points_text_parse(text.data, text.length, NULL, pts, &err);
    rugo_text_free(&text);
    if (st != RUGO_OK) {
        report_parse_error(path, st, &err);
        return EXIT_INPUT;
    }
    return 0;
}
#endif

int cmd_fit(int argc, char** argv) {
#ifdef RUGO_HAVE_FIT
    static const char* const vals[] = {"--control-points", "--param", "-o", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, NULL, &a);
    if (rc) return rc;
    if (a.positional_count != 1) return usage_error("expects one points file%s", "");
    int n = 32;
    const char *nv = opt(&a, "--control-points", NULL), *pv = opt(&a, "--param", NULL);
    if (nv && parse_int(nv, 4, RUGO_MAX_CONTROL_POINTS, &n) != 0)
        return usage_error("--control-points must be a power of two >= 4, got '%s'", nv);
    rugo_parameterization param = RUGO_PARAM_CHORD_LENGTH;
    if (pv && strcmp(pv, "uniform") == 0)
        param = RUGO_PARAM_UNIFORM;
    else if (pv && strcmp(pv, "chord") != 0)
        return usage_error("--param must be chord or uniform, got '%s'", pv);
    rugo_point_list pts;
    if ((rc = load_points(a.positional[0], &pts))) return rc;
    const int count = pts.count;
    rugo_status st;
    rugo_vec2* ctrl = malloc(sizeof *ctrl * (size_t)n);
    if (ctrl == NULL) {
        rugo_point_list_free(&pts);
        return fail("fit", RUGO_ERR_OUT_OF_MEMORY);
    }
    rugo_fit_def def = rugo_default_fit_def();
    def.samples = pts.points;
    def.sample_count = count;
    def.control_count = n;
    def.parameterization = param;
    rugo_fit_result res;
    st = rugo_fit_contour(&def, ctrl, &res);
    if (st == RUGO_OK) {
        rugo_contour_orient_ccw(ctrl, n);
        char extra[256];
        snprintf(extra, sizeof extra,
                 "\"fit\": {\"samples\": %d, \"parameterization\": \"%s\", \"max_error\": %.17g, "
                 "\"rms_error\": %.17g}",
                 count, param == RUGO_PARAM_UNIFORM ? "uniform" : "chord", res.max_error, res.rms_error);
        rc = write_shape(opt(&a, "-o", NULL), ctrl, n, RUGO_FILTER_DEFAULT, extra);
    } else {
        rc = fail("fit", st);
    }
    free(ctrl);
    rugo_point_list_free(&pts);
    return rc;
#else
    (void)argc;
    (void)argv;
    return fail("fit", RUGO_ERR_UNSUPPORTED);
#endif
}
