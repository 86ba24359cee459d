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

#endif

int cmd_import(int argc, char** argv) {
#ifdef RUGO_HAVE_FIT
    static const char* const vals[] = {"--path-id",      "--control-points", "--tolerance", "--samples", "-o",
                                       "--px-per-metre", "--scale",          "--max-size",  NULL};
    static const char* const flags[] = {"--viewbox", "--recentre", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, flags, &a);
    if (rc) return rc;
    if (a.positional_count != 1) return usage_error("expects one SVG or points file%s", "");
    int viewbox = 0, recentre = 0;
    opt(&a, "--viewbox", &viewbox);
    opt(&a, "--recentre", &recentre);
    const char *id = opt(&a, "--path-id", NULL), *nv = opt(&a, "--control-points", NULL),
               *tv = opt(&a, "--tolerance", NULL), *mv = opt(&a, "--samples", NULL),
               *out = opt(&a, "-o", NULL), *ppm = opt(&a, "--px-per-metre", NULL),
               *sv = opt(&a, "--scale", NULL), *xv = opt(&a, "--max-size", NULL);
    if (out == NULL) return usage_error("needs -o OUT.json%s", "");
    int n = 0, m = 0;
    double tol = 0.0, scale = 1.0, max_size = RUGO_DEFAULT_IMPORT_MAX_SIZE;
    if (nv && (parse_int(nv, 4, RUGO_MAX_CONTROL_POINTS, &n) != 0 || (n & (n - 1)) != 0))
        return usage_error(
            "--control-points must be a power of two from 4 to 1048576 (4, 8, 16, ...), got '%s'", nv);
    if (tv && (parse_real(tv, &tol) != 0 || !(tol > 0.0)))
        return usage_error("--tolerance must be a number > 0 (output units), got '%s'", tv);
    if (nv && tv) return usage_error("--control-points and --tolerance exclude each other%s", "");
    if (mv && parse_int(mv, 3, RUGO_MAX_CONTROL_POINTS, &m) != 0)
        return usage_error("--samples must be an integer from 3 to 1048576, got '%s'", mv);
    if (ppm && sv)
        return usage_error("--px-per-metre and --scale exclude each other (scale = 1 / px-per-metre)%s", "");
    double v = 0.0;
    if (ppm && (parse_real(ppm, &v) != 0 || !(v > 0.0)))
        return usage_error(
            "--px-per-metre must be a number > 0 (drawing units per metre, e.g. 100), got '%s'", ppm);
    if (ppm) scale = 1.0 / v;
    if (sv && (parse_real(sv, &scale) != 0 || !(scale > 0.0)))
        return usage_error("--scale must be a number > 0 (output units per drawing unit), got '%s'", sv);
    if (xv && (parse_real(xv, &max_size) != 0 || !(max_size > 0.0)))
        return usage_error("--max-size must be a number > 0 (output units), got '%s'", xv);
    const char* file = a.positional[0];
    rugo_text text;
    rugo_status st = rugo_read_file(file, NULL, &text);
    if (st != RUGO_OK) return fail(file, st);
    rugo_import_def def = rugo_default_import_def();
    def.text = text.data;
    def.length = text.length;
    def.path_id = id;
    def.use_viewbox = viewbox;
    def.scale = scale;
    def.recentre = recentre;
    def.control_count = n;
    def.tolerance = tol;
    def.max_size = max_size;
    /* The default sampling, raised to 8 samples per control point for large explicit counts. */
    def.sample_count = m ? m
                         : (n > RUGO_DEFAULT_OUTLINE_SAMPLES / 8
                                ? (n > RUGO_MAX_CONTROL_POINTS / 8 ? RUGO_MAX_CONTROL_POINTS : 8 * n)
                                : 0);
    rugo_import_result r;
    rugo_parse_error err;
    st = rugo_import_outline(&def, &r, &err);
    rugo_text_free(&text);
    if (st == RUGO_ERR_BAD_ARGUMENT &&
        (strcmp(err.path, "path_id") == 0 || strcmp(err.path, "use_viewbox") == 0))
        return usage_error("--path-id and --viewbox apply to SVG input; %s is a points file", file);
    if (st != RUGO_OK) {
        report_parse_error(file, st, &err);
        return EXIT_INPUT;
    }
    const rugo_outline_fit* f = &r.fit;
    rugo_shape_desc d;
    memset(&d, 0, sizeof d);
    d.control_points = f->control_points;
    d.count = f->control_count;
    d.filter = RUGO_FILTER_DEFAULT;
    rc = 0;
    if (!f->tolerance_met) {
        fprintf(
            stderr,
            "rugo %s: %s: max_error %.6g at %d control points (the most tried for %d samples) is above the "
            "tolerance %.6g (output units); give --control-points, a larger --tolerance or more --samples\n",
            g_command, file, f->max_error, f->control_count, r.sample_count, r.tolerance);
        rc = EXIT_INPUT;
    }
    if (rc == 0) rc = write_desc_atomic(out, &d);
    if (rc == 0) {
        rugo_contour c = {f->control_points, f->control_count};
        printf("{\"output\": ");
        print_json_string(stdout, out);
        printf(", \"source\": \"%s\", \"path_id\": ", r.from_svg ? "svg" : "points");
        if (r.from_svg && id)
            print_json_string(stdout, id);
        else
            printf("null");
        printf(", \"scale\": %.17g, \"viewbox\": %s, \"recentred\": %s, \"offset\": [%.17g, %.17g], "
               "\"size\": %.17g, ",
               scale, viewbox ? "true" : "false", recentre ? "true" : "false", r.offset.x, r.offset.y,
               r.size);
        printf("\"samples\": %d, \"perimeter\": %.17g, \"control_points\": %d, \"tolerance\": ",
               r.sample_count, r.perimeter, f->control_count);
        if (n)
            printf("null");
        else
            printf("%.17g", r.tolerance);
        printf(", \"max_error\": %.17g, \"rms_error\": %.17g, \"max_error_at_parameter\": %.17g, \"area\": "
               "%.17g}\n",
               f->max_error, f->rms_error, f->max_error_at_parameter, rugo_contour_signed_area(c));
    }
    rugo_import_result_free(&r);
    return rc;
#else
    (void)argc;
    (void)argv;
    return fail("import", RUGO_ERR_UNSUPPORTED);
#endif
}
