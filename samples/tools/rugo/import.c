/* `rugo import`: an outline from an SVG path or a point list, sampled by arc length and fitted with the
 * Eigen shim, written atomically (docs/import.md). */
#include "cli.h"
#ifdef RUGO_HAVE_FIT
#include "rugo/fit.h"
#endif

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef RUGO_HAVE_FIT
/* A JSON string literal of s (quotes, backslashes and control characters escaped). */
static void print_json_string(FILE* f, const char* s) {
    fputc('"', f);
    for (; *s; ++s) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

/* Writes a shape description to `path` atomically: into PATH.tmp next to it, renamed over PATH only
 * when complete, so that a failure leaves PATH as it was. Returns 0 or EXIT_INPUT. */
static int write_desc_atomic(const char* path, const rugo_shape_desc* d) {
    const size_t n = strlen(path);
    char* tmp = malloc(n + 5);
    if (tmp == NULL) return fail("writing the shape", RUGO_ERR_OUT_OF_MEMORY);
    memcpy(tmp, path, n);
    memcpy(tmp + n, ".tmp", 5);
    int rc = write_desc(tmp, d, NULL);
    if (rc == 0 && rename(tmp, path) != 0) {
        fprintf(stderr, "rugo %s: %s: cannot rename the temporary file over it\n", g_command, path);
        rc = EXIT_INPUT;
    }
    if (rc != 0) (void)remove(tmp);
    free(tmp);
    return rc;
}

/* 1 if the text's first non-blank character (after a UTF-8 byte order mark) is '<': an SVG document. */
static int looks_like_xml(const char* text, size_t len) {
    size_t i = 0;
    if (len >= 3 && (unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB && (unsigned char)text[2] == 0xBF)
        i = 3;
    while (i < len && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n'))
        ++i;
    return i < len && text[i] == '<';
}
#endif

int cmd_import(int argc, char** argv) {
#ifdef RUGO_HAVE_FIT
    static const char* const vals[] = {"--path-id", "--control-points", "--tolerance", "--samples", "-o", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, NULL, &a);
    if (rc) return rc;
    if (a.positional_count != 1) return usage_error("expects one SVG or points file%s", "");
    const char *id = opt(&a, "--path-id", NULL), *nv = opt(&a, "--control-points", NULL),
               *tv = opt(&a, "--tolerance", NULL), *mv = opt(&a, "--samples", NULL), *out = opt(&a, "-o", NULL);
    if (out == NULL) return usage_error("needs -o OUT.json%s", "");
    int n = 0, m = 0;
    double tol = 0.0;
    if (nv && (parse_int(nv, 4, RUGO_MAX_CONTROL_POINTS, &n) != 0 || (n & (n - 1)) != 0))
        return usage_error("--control-points must be a power of two >= 4, got '%s'", nv);
    if (tv && (parse_real(tv, &tol) != 0 || !(tol > 0.0)))
        return usage_error("--tolerance must be a number > 0, got '%s'", tv);
    if (nv && tv) return usage_error("--control-points and --tolerance exclude each other%s", "");
    if (mv && parse_int(mv, 3, RUGO_MAX_CONTROL_POINTS, &m) != 0)
        return usage_error("--samples must be an integer from 3 to 1048576, got '%s'", mv);
    const char* file = a.positional[0];
    rugo_text text;
    rugo_status st = rugo_read_file(file, NULL, &text);
    if (st != RUGO_OK) return fail(file, st);
    const int svg = looks_like_xml(text.data, text.length);
    if (!svg && id) {
        rugo_text_free(&text);
        return usage_error("--path-id applies to SVG input; %s is a points file", file);
    }
    rugo_outline_samples s;
    memset(&s, 0, sizeof s);
    rugo_parse_error err;
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    /* SVG: the default sampling, raised to 8 samples per control point for large explicit counts. */
    sd.sample_count = m ? m : (n > RUGO_DEFAULT_OUTLINE_SAMPLES / 8 ? (n > RUGO_MAX_CONTROL_POINTS / 8 ? RUGO_MAX_CONTROL_POINTS : 8 * n) : 0);
    if (svg) {
        st = rugo_svg_import_outline(text.data, text.length, id, &sd, &s, &err);
        rugo_text_free(&text);
    } else {
        /* A point list: its points are the samples, unless --samples resamples the polygon through them. */
        rugo_point_list pts;
        st = rugo_points_text_parse(text.data, text.length, NULL, &pts, &err);
        rugo_text_free(&text);
        rugo_path poly;
        memset(&poly, 0, sizeof poly);
        if (st == RUGO_OK) {
            st = rugo_path_from_points(pts.points, pts.count, NULL, &poly);
            if (st != RUGO_OK) {
                memset(&err, 0, sizeof err);
                snprintf(err.message, sizeof err.message, "%d points do not make an outline", pts.count);
            }
        }
        if (st == RUGO_OK) {
            sd.path = &poly;
            sd.sample_count = m ? m : pts.count;
            st = rugo_outline_sample(&sd, &s, &err);
        }
        rugo_path_free(&poly);
        rugo_point_list_free(&pts);
    }
    if (st != RUGO_OK) {
        report_parse_error(file, st, &err);
        return EXIT_INPUT;
    }
    rugo_vec2 lo = s.points[0], hi = s.points[0];
    for (int i = 1; i < s.count; ++i) {
        lo.x = fmin(lo.x, s.points[i].x);
        lo.y = fmin(lo.y, s.points[i].y);
        hi.x = fmax(hi.x, s.points[i].x);
        hi.y = fmax(hi.y, s.points[i].y);
    }
    if (!nv && !tv) tol = 1e-3 * hypot(hi.x - lo.x, hi.y - lo.y); /* 0.1% of the outline's size */
    rugo_outline_fit_def fd = rugo_default_outline_fit_def();
    fd.samples = s.points;
    fd.sample_count = s.count;
    fd.control_count = n;
    fd.tolerance = n ? 0.0 : tol;
    rugo_outline_fit f;
    st = rugo_fit_outline(&fd, &f);
    if (st != RUGO_OK) {
        rugo_outline_samples_free(&s);
        return fail("fit", st);
    }
    rugo_shape_desc d;
    memset(&d, 0, sizeof d);
    d.control_points = f.control_points;
    d.count = f.control_count;
    d.filter = RUGO_FILTER_DEFAULT;
    if (!f.tolerance_met) {
        fprintf(stderr,
                "rugo %s: %s: max_error %.6g at %d control points (the most tried for %d samples) is above the "
                "tolerance %.6g; give --control-points, a larger --tolerance or more --samples\n",
                g_command, file, f.max_error, f.control_count, s.count, tol);
        rc = EXIT_INPUT;
    } else {
        rc = check_outline(file, &d, RUGO_CHECK_ALL);
    }
    if (rc == 0) rc = write_desc_atomic(out, &d);
    if (rc == 0) {
        rugo_contour c = {f.control_points, f.control_count};
        printf("{\"output\": ");
        print_json_string(stdout, out);
        printf(", \"source\": \"%s\", \"path_id\": ", svg ? "svg" : "points");
        if (svg && id)
            print_json_string(stdout, id);
        else
            printf("null");
        printf(", \"samples\": %d, \"perimeter\": %.17g, \"control_points\": %d, \"tolerance\": ", s.count,
               s.perimeter, f.control_count);
        if (n)
            printf("null");
        else
            printf("%.17g", tol);
        printf(", \"max_error\": %.17g, \"rms_error\": %.17g, \"max_error_at_parameter\": %.17g, \"area\": %.17g}\n",
               f.max_error, f.rms_error, f.max_error_at_parameter, rugo_contour_signed_area(c));
    }
    rugo_outline_fit_free(&f);
    rugo_outline_samples_free(&s);
    return rc;
#else
    (void)argc;
    (void)argv;
    return fail("import", RUGO_ERR_UNSUPPORTED);
#endif
}
