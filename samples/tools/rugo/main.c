/* rugo — librugo's command-line tool for asset pipelines, debugging and black-box tests.
 *
 * JSON in, JSON out on stdout; errors on stderr with a non-zero exit status (1: the input or the
 * operation failed, 2: the command line is wrong). docs/cli.md documents every subcommand and format. */
#include "rugo/rugo.h"
#ifdef RUGO_HAVE_FIT
#include "rugo/fit.h"
#endif
#include "svg.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { EXIT_INPUT = 1, EXIT_USAGE = 2 };

static const char* g_command = "rugo";

static int usage_error(const char* fmt, const char* arg) {
    fprintf(stderr, "rugo %s: ", g_command);
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\n(run 'rugo help' for usage)\n");
    return EXIT_USAGE;
}

static int fail(const char* what, rugo_status st) {
    fprintf(stderr, "rugo %s: %s: %s (status %d)\n", g_command, what, rugo_status_string(st), (int)st);
    return EXIT_INPUT;
}

/* ---- argument parsing ---------------------------------------------------------------------- */

static int parse_real(const char* s, double* out) {
    char* end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v)) return -1;
    *out = v;
    return 0;
}

static int parse_int(const char* s, int lo, int hi, int* out) {
    char* end = NULL;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE || v < lo || v > hi) return -1;
    *out = (int)v;
    return 0;
}

/* "X,Y" */
static int parse_pair(const char* s, rugo_vec2* out) {
    char buf[128];
    const char* comma = strchr(s, ',');
    if (comma == NULL || (size_t)(comma - s) >= sizeof buf) return -1;
    memcpy(buf, s, (size_t)(comma - s));
    buf[comma - s] = '\0';
    if (parse_real(buf, &out->x) != 0 || parse_real(comma + 1, &out->y) != 0) return -1;
    return 0;
}

/* A seed: plain decimal digits, at most 2^53 (what a shape file can carry; see docs/roughness.md). */
static int parse_seed(const char* s, uint64_t* out) {
    uint64_t x = 0;
    if (*s == '\0') return -1;
    for (; *s; ++s) {
        if (*s < '0' || *s > '9') return -1;
        uint64_t d = (uint64_t)(*s - '0');
        if (x > (RUGO_MAX_FILE_SEED - d) / 10) return -1;
        x = x * 10 + d;
    }
    *out = x;
    return 0;
}

/* Options: a flat table of "--name" -> value (NULL for flags). Positional arguments in order. */
typedef struct args {
    const char* positional[4];
    int positional_count;
    const char* names[16];
    const char* values[16];
    int count;
} args;

/* Parses argv against the allowed option names; value_options take a value. */
static int parse_args(int argc, char** argv, const char* const* value_options, const char* const* flag_options,
                      args* a) {
    memset(a, 0, sizeof *a);
    for (int i = 0; i < argc; ++i) {
        const char* s = argv[i];
        if (s[0] == '-' && s[1] != '\0' && !(s[1] >= '0' && s[1] <= '9')) {
            int known = 0;
            for (const char* const* o = value_options; o && *o; ++o)
                if (strcmp(s, *o) == 0) {
                    if (i + 1 >= argc) return usage_error("option %s needs a value", s);
                    if (a->count >= 16) return usage_error("too many options%s", "");
                    a->names[a->count] = s;
                    a->values[a->count++] = argv[++i];
                    known = 1;
                    break;
                }
            for (const char* const* o = flag_options; !known && o && *o; ++o)
                if (strcmp(s, *o) == 0) {
                    if (a->count >= 16) return usage_error("too many options%s", "");
                    a->names[a->count] = s;
                    a->values[a->count++] = NULL;
                    known = 1;
                }
            if (!known) return usage_error("unknown option %s", s);
        } else {
            if (a->positional_count >= 4) return usage_error("unexpected argument %s", s);
            a->positional[a->positional_count++] = s;
        }
    }
    return 0;
}

/* Last value given for an option (NULL if absent); *present for flags. */
static const char* opt(const args* a, const char* name, int* present) {
    const char* v = NULL;
    if (present) *present = 0;
    for (int i = 0; i < a->count; ++i)
        if (strcmp(a->names[i], name) == 0) {
            v = a->values[i];
            if (present) *present = 1;
        }
    return v;
}

/* ---- shapes in and out ----------------------------------------------------------------------- */

/* 1 if the file starts with the magic bytes of a baked shape (the format is told by content, never by
 * the file name), 0 otherwise (including unreadable files: the JSON reader then reports them). */
static int is_baked_file(const char* path) {
    unsigned char head[RUGO_BAKED_MAGIC_SIZE];
    FILE* f = fopen(path, "rb");
    if (f == NULL) return 0;
    size_t n = fread(head, 1, sizeof head, f);
    fclose(f);
    return rugo_is_baked(head, n);
}

static int load_baked(const char* path, rugo_shape** out) {
    rugo_baked_error err;
    rugo_status st = rugo_shape_read_baked_file(path, NULL, out, &err);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo %s: %s: byte %lu: %s%s%s (status %d: %s)\n", g_command, path, (unsigned long)err.offset,
                err.field, err.field[0] ? ": " : "", err.message, (int)st, rugo_status_string(st));
        return EXIT_INPUT;
    }
    return 0;
}

/* The description of a baked shape, for the commands that work on descriptions: its finest control
 * points (counter-clockwise, as the shape stores them), filter, finest tolerances as a list, friction
 * and restitution. q and the estimator are not part of a shape, so they take their defaults. */
static int desc_of_baked(const char* path, const rugo_shape* s, rugo_shape_desc* desc) {
    memset(desc, 0, sizeof *desc);
    rugo_contour c;
    rugo_shape_level(s, rugo_shape_finest_level(s), &c);
    rugo_tolerance_level t;
    rugo_shape_tolerance_level(s, rugo_shape_finest_level(s), &t);
    desc->allocator = rugo_default_allocator();
    desc->filter = rugo_pyramid_filter(rugo_shape_pyramid(s));
    desc->control_points = malloc(sizeof(rugo_vec2) * (size_t)c.count);
    desc->roughness = rugo_default_roughness_desc();
    desc->roughness.kind = RUGO_ROUGHNESS_TOLERANCES;
    desc->roughness.tolerances = malloc(sizeof(rugo_real) * (size_t)c.count);
    if (desc->control_points == NULL || desc->roughness.tolerances == NULL) {
        rugo_shape_desc_free(desc);
        return fail(path, RUGO_ERR_OUT_OF_MEMORY);
    }
    memcpy(desc->control_points, c.points, sizeof(rugo_vec2) * (size_t)c.count);
    memcpy(desc->roughness.tolerances, t.total, sizeof(rugo_real) * (size_t)c.count);
    desc->count = c.count;
    desc->has_roughness = 1;
    desc->roughness.tolerance_count = c.count;
    desc->roughness.friction = rugo_shape_friction_map(s);
    desc->roughness.restitution = rugo_shape_restitution(s);
    return 0;
}

/* Reads a shape file, JSON or baked. With `baked` non-NULL a baked file's shape is handed back there
 * (the caller destroys it) for commands that can use the stored shape as it is. */
static int load_shape_any(const char* path, rugo_shape_desc* desc, rugo_shape** baked) {
    if (baked != NULL) *baked = NULL;
    if (is_baked_file(path)) {
        rugo_shape* s = NULL;
        int rc = load_baked(path, &s);
        if (rc) return rc;
        rc = desc_of_baked(path, s, desc);
        if (rc == 0 && baked != NULL)
            *baked = s;
        else
            rugo_shape_destroy(s);
        return rc;
    }
    char* text = NULL;
    size_t len = 0;
    rugo_status st = rugo_read_file(path, NULL, &text, &len);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo %s: %s: cannot read: %s (status %d)\n", g_command, path, rugo_status_string(st), (int)st);
        return EXIT_INPUT;
    }
    rugo_parse_error err;
    st = rugo_shape_desc_parse(text, len, NULL, desc, &err);
    rugo_text_free(NULL, text);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo %s: %s:%d:%d: %s%s%s (status %d: %s)\n", g_command, path, err.line, err.column,
                err.path, err.path[0] ? ": " : "", err.message, (int)st, rugo_status_string(st));
        return EXIT_INPUT;
    }
    return 0;
}

static int load_shape(const char* path, rugo_shape_desc* desc) { return load_shape_any(path, desc, NULL); }

static void report_problem(const char* path, rugo_status st, const rugo_contour_problem* pr) {
    fprintf(stderr, "rugo %s: %s: %s (status %d)", g_command, path, rugo_status_string(st), (int)st);
    if (st == RUGO_ERR_SELF_INTERSECTING)
        fprintf(stderr, ": segments %d and %d cross near (%.9g, %.9g)", pr->segment_a, pr->segment_b, pr->where.x,
                pr->where.y);
    else if (st == RUGO_ERR_NOT_FINITE && pr->index >= 0)
        fprintf(stderr, ": control point %d", pr->index);
    fprintf(stderr, "\n");
}

/* Validates a loaded outline; on failure reports it (naming the crossing segments or the bad point)
 * and returns EXIT_INPUT. The caller still owns and frees desc. */
static int check_outline(const char* path, const rugo_shape_desc* desc, int flags) {
    rugo_contour_problem pr;
    rugo_status st = rugo_contour_check(desc->control_points, desc->count, flags, &pr, NULL);
    if (st == RUGO_OK) return 0;
    report_problem(path, st, &pr);
    return EXIT_INPUT;
}

static int build_pyramid(const char* path, const rugo_shape_desc* desc, rugo_filter filter, int coarsest,
                         rugo_pyramid** out) {
    rugo_pyramid_def def = rugo_default_pyramid_def();
    def.points = desc->control_points;
    def.count = desc->count;
    def.filter = filter;
    def.coarsest_level = coarsest;
    rugo_contour_problem pr;
    rugo_status st = rugo_pyramid_create(&def, out, &pr);
    if (st != RUGO_OK) {
        report_problem(path, st, &pr);
        return EXIT_INPUT;
    }
    return 0;
}

static void print_points(FILE* f, const rugo_vec2* p, int n) {
    fputc('[', f);
    for (int i = 0; i < n; ++i) fprintf(f, "%s[%.17g, %.17g]", i ? ", " : "", p[i].x, p[i].y);
    fputc(']', f);
}

/* Writes a shape description (the library's writer) to `path` or stdout, with an optional extra member
 * (`"name": {...}`) spliced in before the closing brace. Returns 0 or EXIT_INPUT. */
static int write_desc(const char* path, const rugo_shape_desc* d, const char* extra) {
    char* text = NULL;
    size_t len = 0;
    rugo_status st = rugo_shape_desc_write(d, NULL, &text, &len);
    if (st != RUGO_OK) return fail("writing the shape", st);
    FILE* f = path ? fopen(path, "w") : stdout;
    if (f == NULL) {
        rugo_text_free(NULL, text);
        fprintf(stderr, "rugo %s: %s: cannot open for writing\n", g_command, path);
        return EXIT_INPUT;
    }
    char* close = strrchr(text, '}');
    if (extra && close) {
        fwrite(text, 1, (size_t)(close - text), f);
        fprintf(f, ", %s}\n", extra);
    } else {
        fputs(text, f);
        if (len == 0 || text[len - 1] != '\n') fputc('\n', f);
    }
    rugo_text_free(NULL, text);
    int bad = ferror(f);
    if (path) bad |= fclose(f) != 0;
    if (bad) {
        fprintf(stderr, "rugo %s: %s: write failed\n", g_command, path ? path : "stdout");
        return EXIT_INPUT;
    }
    return 0;
}

/* A shape without roughness. */
static int write_shape(const char* path, const rugo_vec2* points, int count, rugo_filter filter,
                       const char* extra) {
    rugo_shape_desc d;
    memset(&d, 0, sizeof d);
    d.control_points = (rugo_vec2*)points;
    d.count = count;
    d.filter = filter;
    return write_desc(path, &d, extra);
}

static int log2_exact(int n) {
    int j = 0;
    while ((1 << j) < n) ++j;
    return (1 << j) == n ? j : -1;
}

/* ---- roughness ------------------------------------------------------------------------------ */

static const char* estimator_name(rugo_tolerance_estimator e) {
    return e == RUGO_ESTIMATOR_COEFFICIENTS ? "coefficients" : "detail";
}

/* The roughness settings of a shape: its own, or the defaults when it has none. */
static rugo_roughness_desc roughness_of(const rugo_shape_desc* d) {
    return d->has_roughness ? d->roughness : rugo_default_roughness_desc();
}

/* The tolerance of every finest segment (n values, malloc'd into *out) as `r` gives them, or 0 when r
 * is NULL (a shape without roughness is smooth). In the file's own segment numbering, or, when
 * `reversed`, in that of the reversed (counter-clockwise) points, where the file's segment j is
 * segment n-2-j. `points` are the n control points in the numbering of the result (arc-length
 * roughness is resolved on them, in the file's order). Returns 0 or EXIT_INPUT after a message. */
static int finest_tolerances(const char* path, const rugo_roughness_desc* r, const rugo_vec2* points, int n,
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
static int carried_roughness(const char* path, const rugo_shape_desc* in, int reversed,
                             const rugo_vec2* points, rugo_roughness_desc* out, rugo_real** tol) {
    *tol = NULL;
    *out = in->roughness;
    out->has_perturbation = 0;
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

/* ---- subcommands ---------------------------------------------------------------------------- */

static int cmd_info(int argc, char** argv) {
    args a;
    int rc = parse_args(argc, argv, NULL, NULL, &a);
    if (rc) return rc;
    if (a.positional_count != 1) return usage_error("expects one shape file%s", "");
    rugo_shape_desc desc;
    if ((rc = load_shape(a.positional[0], &desc))) return rc;
    if ((rc = check_outline(a.positional[0], &desc, RUGO_CHECK_SELF_INTERSECTION))) {
        rugo_shape_desc_free(&desc);
        return rc;
    }
    rugo_contour_orient_ccw(desc.control_points, desc.count);
    rugo_contour c = {desc.control_points, desc.count};
    rugo_mass_properties mp = rugo_contour_mass_properties(c);
    int levels = log2_exact(desc.count);
    printf("{\"control_points\": %d, \"levels\": ", desc.count);
    if (levels >= 0)
        printf("%d", levels);
    else
        printf("null");
    printf(", \"area\": %.17g, \"centroid\": [%.17g, %.17g], \"inertia\": %.17g, \"perimeter\": %.17g}\n", mp.area,
           mp.centroid.x, mp.centroid.y, mp.inertia, rugo_contour_perimeter(c));
    rugo_shape_desc_free(&desc);
    return 0;
}

static int filter_option(const args* a, const rugo_shape_desc* desc, rugo_filter* f) {
    const char* name = opt(a, "--filter", NULL);
    *f = desc->filter;
    if (name && rugo_filter_from_name(name, f) != RUGO_OK)
        return usage_error("unknown filter '%s' (cdf4.2, cdf4.4, cdf4.6, cdf4.8, cdf4.12)", name);
    return 0;
}

static int cmd_decompose(int argc, char** argv) {
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
        fail(a.positional[0], desc.count < 4 ? RUGO_ERR_TOO_FEW_POINTS : RUGO_ERR_NOT_POWER_OF_TWO);
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
        fprintf(stderr, "rugo decompose: %d control points cannot be decomposed (a level needs >= 4)\n", desc.count);
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

static int cmd_refine(int argc, char** argv) {
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
    rugo_status st = rugo_contour_check(desc.control_points, desc.count, RUGO_CHECK_SELF_INTERSECTION, &pr, NULL);
    if (st == RUGO_OK && ((long)desc.count << times) > RUGO_MAX_CONTROL_POINTS) st = RUGO_ERR_TOO_MANY_POINTS;
    if (st != RUGO_OK) {
        report_problem(a.positional[0], st, &pr);
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

static int cmd_deform(int argc, char** argv) {
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
    if (at == NULL || parse_real(at, &u) != 0 || u < 0.0) return usage_error("--at U (curve parameter >= 0) is required%s", "");
    if (dv == NULL || parse_pair(dv, &delta) != 0) return usage_error("--delta DX,DY is required%s", "");
    const char *lv = opt(&a, "--levels", NULL), *wv = opt(&a, "--w", NULL), *mv = opt(&a, "--details", NULL);
    if (lv && parse_int(lv, 1, 30, &spread) != 0) return usage_error("--levels must be a positive integer, got '%s'", lv);
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
        fprintf(stderr, "rugo deform: --levels at most %d for this shape\n", J - rugo_pyramid_coarsest_level(p) + 1);
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
        shape_out.has_roughness = 1;
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

/* ---- import (docs/import.md) ------------------------------------------------------------------- */

#ifdef RUGO_HAVE_FIT
/* Prints a parse error with the file, line and column (when known), the field and the message. */
static void report_parse_error(const char* file, rugo_status st, const rugo_parse_error* err) {
    fprintf(stderr, "rugo %s: %s", g_command, file);
    if (err->line > 0) fprintf(stderr, ":%d:%d", err->line, err->column);
    fprintf(stderr, ": %s%s%s (status %d: %s)\n", err->path, err->path[0] ? ": " : "",
            err->message[0] ? err->message : rugo_status_string(st), (int)st, rugo_status_string(st));
}

/* Reads a points file for `fit` and `import`: JSON {"points": [...]} or plain text, one "x,y" or "x y"
 * per line (rugo_points_text_parse). Returns 0, or EXIT_INPUT after a message. */
static int load_points(const char* path, rugo_vec2** pts, int* count) {
    char* text = NULL;
    size_t len = 0;
    rugo_status st = rugo_read_file(path, NULL, &text, &len);
    if (st != RUGO_OK) return fail(path, st);
    rugo_parse_error err;
    st = rugo_points_text_parse(text, len, NULL, pts, count, &err);
    rugo_text_free(NULL, text);
    if (st != RUGO_OK) {
        report_parse_error(path, st, &err);
        return EXIT_INPUT;
    }
    return 0;
}

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

static int cmd_import(int argc, char** argv) {
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
    char* text = NULL;
    size_t len = 0;
    rugo_status st = rugo_read_file(file, NULL, &text, &len);
    if (st != RUGO_OK) return fail(file, st);
    const int svg = looks_like_xml(text, len);
    if (!svg && id) {
        rugo_text_free(NULL, text);
        return usage_error("--path-id applies to SVG input; %s is a points file", file);
    }
    rugo_outline_samples s;
    memset(&s, 0, sizeof s);
    rugo_parse_error err;
    rugo_outline_sample_def sd = rugo_default_outline_sample_def();
    /* SVG: the default sampling, raised to 8 samples per control point for large explicit counts. */
    sd.sample_count = m ? m : (n > RUGO_DEFAULT_OUTLINE_SAMPLES / 8 ? (n > RUGO_MAX_CONTROL_POINTS / 8 ? RUGO_MAX_CONTROL_POINTS : 8 * n) : 0);
    if (svg) {
        st = rugo_svg_import_outline(text, len, id, &sd, &s, &err);
        rugo_text_free(NULL, text);
    } else {
        /* A point list: its points are the samples, unless --samples resamples the polygon through them. */
        rugo_vec2* pts = NULL;
        int count = 0;
        st = rugo_points_text_parse(text, len, NULL, &pts, &count, &err);
        rugo_text_free(NULL, text);
        rugo_path poly;
        memset(&poly, 0, sizeof poly);
        if (st == RUGO_OK) {
            st = rugo_path_from_points(pts, count, NULL, &poly);
            if (st != RUGO_OK) {
                memset(&err, 0, sizeof err);
                snprintf(err.message, sizeof err.message, "%d points do not make an outline", count);
            }
        }
        if (st == RUGO_OK) {
            sd.path = &poly;
            sd.sample_count = m ? m : count;
            st = rugo_outline_sample(&sd, &s, &err);
        }
        rugo_path_free(&poly);
        rugo_points_free(NULL, pts);
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

static int cmd_fit(int argc, char** argv) {
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
    rugo_vec2* pts = NULL;
    int count = 0;
    if ((rc = load_points(a.positional[0], &pts, &count))) return rc;
    rugo_status st;
    rugo_vec2* ctrl = malloc(sizeof *ctrl * (size_t)n);
    if (ctrl == NULL) {
        rugo_points_free(NULL, pts);
        return fail("fit", RUGO_ERR_OUT_OF_MEMORY);
    }
    rugo_fit_def def = rugo_default_fit_def();
    def.samples = pts;
    def.sample_count = count;
    def.control_count = n;
    def.parameterization = param;
    rugo_fit_result res;
    st = rugo_fit_contour(&def, ctrl, &res);
    if (st == RUGO_OK) {
        rugo_contour_orient_ccw(ctrl, n);
        char extra[256];
        snprintf(extra, sizeof extra,
                 "\"fit\": {\"samples\": %d, \"parameterization\": \"%s\", \"max_error\": %.17g, \"rms_error\": %.17g}",
                 count, param == RUGO_PARAM_UNIFORM ? "uniform" : "chord", res.max_error, res.rms_error);
        rc = write_shape(opt(&a, "-o", NULL), ctrl, n, RUGO_FILTER_DEFAULT, extra);
    } else {
        rc = fail("fit", st);
    }
    free(ctrl);
    rugo_points_free(NULL, pts);
    return rc;
#else
    (void)argc;
    (void)argv;
    return fail("fit", RUGO_ERR_UNSUPPORTED);
#endif
}

/* Reads a CSV roughness profile (docs/roughness.md); 0, or EXIT_INPUT after a message naming the file,
 * line, column and sample. */
static int load_profile_csv(const char* file, rugo_profile_sample** samples, int* count) {
    char* text = NULL;
    size_t len = 0;
    rugo_status st = rugo_read_file(file, NULL, &text, &len);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo %s: %s: cannot read: %s (status %d)\n", g_command, file, rugo_status_string(st),
                (int)st);
        return EXIT_INPUT;
    }
    rugo_parse_error err;
    st = rugo_roughness_profile_parse_csv(text, len, NULL, samples, count, &err);
    rugo_text_free(NULL, text);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo %s: %s:%d:%d: %s%s%s (status %d: %s)\n", g_command, file, err.line, err.column,
                err.path, err.path[0] ? ": " : "", err.message, (int)st, rugo_status_string(st));
        return EXIT_INPUT;
    }
    return 0;
}

static int cmd_roughen(int argc, char** argv) {
    static const char* const vals[] = {"--method", "--preset", "--seed", "--levels", "--profile", "-o", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, NULL, &a);
    if (rc) return rc;
    if (a.positional_count != 1) return usage_error("expects one shape file%s", "");
    const char *mv = opt(&a, "--method", NULL), *pv = opt(&a, "--preset", NULL),
               *sv = opt(&a, "--seed", NULL), *lv = opt(&a, "--levels", NULL),
               *fv = opt(&a, "--profile", NULL);
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
    if (pv && fv) return usage_error("--preset and --profile exclude each other%s", "");
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
        report_problem(path, st, &pr);
        rugo_shape_desc_free(&desc);
        return EXIT_INPUT;
    }
    rugo_profile_sample* profile = NULL;
    int profile_count = 0;
    if (fv && (rc = load_profile_csv(fv, &profile, &profile_count))) {
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
        r.profile = profile;
        r.profile_count = profile_count;
    }
    if (sv) r.seed = seed;
    rugo_real* tol = NULL;
    rugo_vec2* pert = NULL;
    if ((rc = finest_tolerances(path, &r, desc.control_points, n, reversed, &tol))) goto done;
    /* The resolved values are written, not the preset: the file then says exactly what the shape is,
     * in the numbering of the points written (counter-clockwise), whatever later versions of the
     * presets do. */
    rugo_roughness_desc out = r;
    out.kind = RUGO_ROUGHNESS_TOLERANCES;
    out.tolerances = tol;
    out.tolerance_count = n;
    out.has_perturbation = 0;
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
        out.has_perturbation = 1;
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
    w.has_roughness = 1;
    w.roughness = out;
    rc = write_desc(opt(&a, "-o", NULL), &w, NULL);
done:
    free(pert);
    free(tol);
    rugo_roughness_profile_free(NULL, profile);
    rugo_shape_desc_free(&desc);
    return rc;
}

static int cmd_tolerances(int argc, char** argv) {
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
            printf("%s\n  {\"level\": %d, \"tolerance\": ", j == rugo_shape_finest_level(baked) ? "" : ",", j);
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

/* "X,Y,THETA" (THETA in radians). */
static int parse_pose(const char* s, rugo_transform* out) {
    char buf[256];
    size_t n = strlen(s);
    if (n >= sizeof buf) return -1;
    memcpy(buf, s, n + 1);
    char* last = strrchr(buf, ',');
    if (last == NULL) return -1;
    *last = '\0';
    rugo_vec2 xy;
    double theta;
    if (parse_pair(buf, &xy) != 0 || parse_real(last + 1, &theta) != 0) return -1;
    *out = rugo_make_transform(xy.x, xy.y, theta);
    return 0;
}

/* Builds the immutable shape (pyramid, tolerances, tree, mass) of a shape file. */
static int make_shape(const char* path, const rugo_shape_desc* desc, rugo_shape** out) {
    *out = NULL;
    rugo_roughness_desc r = roughness_of(desc);
    rugo_real* tol = NULL;
    int rc = finest_tolerances(path, desc->has_roughness ? &desc->roughness : NULL, desc->control_points,
                               desc->count, 0, &tol);
    if (rc) return rc;
    rugo_shape_def def = rugo_default_shape_def();
    def.points = desc->control_points;
    def.count = desc->count;
    def.filter = desc->filter;
    def.tolerances = tol; /* in the file's numbering: the shape renumbers with its points */
    def.q = r.q;
    def.estimator = r.estimator;
    def.friction = r.friction;
    def.restitution = r.restitution;
    rugo_contour_problem pr;
    rugo_status st = rugo_shape_create(&def, out, &pr);
    free(tol);
    if (st != RUGO_OK) {
        report_problem(path, st, &pr);
        return EXIT_INPUT;
    }
    return 0;
}

static void print_vec(const char* name, rugo_vec2 v) { printf("\"%s\": [%.17g, %.17g]", name, v.x, v.y); }

static int cmd_contacts(int argc, char** argv) {
    static const char* const vals[] = {"--pose-a", "--pose-b", "--level", "--tolerance", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, NULL, &a);
    if (rc) return rc;
    if (a.positional_count != 2) return usage_error("expects two shape files A.json B.json%s", "");
    const char *pa = opt(&a, "--pose-a", NULL), *pb = opt(&a, "--pose-b", NULL), *lv = opt(&a, "--level", NULL),
               *tv = opt(&a, "--tolerance", NULL);
    rugo_transform xa = rugo_identity_transform(), xb = rugo_identity_transform();
    if (pa && parse_pose(pa, &xa) != 0) return usage_error("--pose-a must be X,Y,THETA, got '%s'", pa);
    if (pb && parse_pose(pb, &xb) != 0) return usage_error("--pose-b must be X,Y,THETA, got '%s'", pb);
    rugo_contact_query q = rugo_default_contact_query();
    if (lv && parse_int(lv, -30, 30, &q.level) != 0) return usage_error("--level must be an integer, got '%s'", lv);
    if (tv && (parse_real(tv, &q.tolerance) != 0 || q.tolerance < 0.0))
        return usage_error("--tolerance must be a number >= 0, got '%s'", tv);
    rugo_shape_desc da, db;
    rugo_shape *sa = NULL, *sb = NULL;
    if ((rc = load_shape_any(a.positional[0], &da, &sa))) return rc;
    if ((rc = load_shape_any(a.positional[1], &db, &sb))) {
        rugo_shape_destroy(sa);
        rugo_shape_desc_free(&da);
        return rc;
    }
    rugo_collide_context* ctx = NULL;
    rugo_contact* contacts = NULL;
    /* A baked shape is used as stored (bit-identical to the shape that was baked). */
    if ((sa == NULL && (rc = make_shape(a.positional[0], &da, &sa))) ||
        (sb == NULL && (rc = make_shape(a.positional[1], &db, &sb))))
        goto done;
    rugo_status st = rugo_collide_context_create(NULL, &ctx);
    int capacity = 64, count = 0;
    rugo_contact_state state = RUGO_STATE_APART;
    rugo_query_stats stats;
    for (int attempt = 0; st == RUGO_OK && attempt < 2; ++attempt) {
        free(contacts);
        contacts = malloc(sizeof *contacts * (size_t)capacity);
        if (contacts == NULL) {
            st = RUGO_ERR_OUT_OF_MEMORY;
            break;
        }
        st = rugo_collide_shapes(ctx, sa, xa, sb, xb, &q, contacts, capacity, &count, &state, &stats);
        if (st != RUGO_OK || stats.contacts_found <= capacity) break;
        capacity = stats.contacts_found; /* every contact, not a truncated list */
    }
    if (st != RUGO_OK) {
        rc = fail("contacts", st);
        goto done;
    }
    printf("{\"state\": \"%s\", \"contacts\": [", rugo_contact_state_name(state));
    for (int i = 0; i < count; ++i) {
        const rugo_contact* c = &contacts[i];
        printf("%s\n  {", i ? "," : "");
        print_vec("point_a", c->point_a);
        printf(", ");
        print_vec("point_b", c->point_b);
        printf(", ");
        print_vec("normal", c->normal);
        printf(", \"separation\": %.17g, \"segment_a\": %d, \"segment_b\": %d, \"t_a\": %.17g, \"t_b\": %.17g, "
               "\"tolerance\": %.17g, \"friction\": %.17g, \"tolerance_a\": %.17g, \"tolerance_b\": %.17g, "
               "\"restitution\": %.17g, \"level_a\": %d, \"level_b\": %d, \"region\": %d, \"id\": \"%016llx\"}",
               c->separation, c->segment_a, c->segment_b, c->t_a, c->t_b, c->tolerance_a + c->tolerance_b,
               c->friction, c->tolerance_a, c->tolerance_b, c->restitution, c->level_a, c->level_b, c->region,
               (unsigned long long)c->id);
    }
    printf("%s], \"stats\": {\"box_tests\": %ld, \"segment_pairs\": %ld, \"newton_iterations\": %ld, "
           "\"fallbacks\": %ld}, \"reversed_a\": %s, \"reversed_b\": %s}\n",
           count ? "\n" : "", stats.box_tests, stats.segment_pairs, stats.newton_iterations, stats.fallbacks,
           rugo_shape_was_reversed(sa) ? "true" : "false", rugo_shape_was_reversed(sb) ? "true" : "false");
done:
    free(contacts);
    rugo_collide_context_destroy(ctx);
    rugo_shape_destroy(sa);
    rugo_shape_destroy(sb);
    rugo_shape_desc_free(&da);
    rugo_shape_desc_free(&db);
    return rc;
}

/* One side of the tolerance band: the curve offset by sign * λ(t) along its outward normal, as a thin
 * closed line (the contour is counter-clockwise, tol in its numbering). */
static void svg_band(svg_canvas* svg, rugo_contour c, const rugo_real* tol, int per_segment, double sign) {
    fprintf(svg->file,
            "<polygon class=\"band\" fill=\"none\" stroke=\"#1b9e77\" stroke-width=\"0.6\" points=\"");
    for (int j = 0; j < c.count; ++j)
        for (int i = 0; i < per_segment; ++i) {
            rugo_real t = (rugo_real)i / per_segment;
            rugo_vec2 q = rugo_v2_add(rugo_contour_point(c, j, t),
                                      rugo_v2_scale(sign * rugo_tolerance_at(tol, c.count, j, t, 0.0),
                                                    rugo_contour_normal(c, j, t)));
            fprintf(svg->file, "%.2f,%.2f ", (q.x - svg->ox) * svg->scale,
                    svg->height - (q.y - svg->oy) * svg->scale);
        }
    fprintf(svg->file, "\"/>\n");
}

static int cmd_render(int argc, char** argv) {
    static const char* const vals[] = {"-o", "--levels", "--samples", NULL};
    static const char* const flags[] = {"--no-control-polygon", "--band", "--perturbation", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, flags, &a);
    if (rc) return rc;
    const char* out = opt(&a, "-o", NULL);
    if (a.positional_count != 1 || out == NULL) return usage_error("expects SHAPE.json -o OUT.svg%s", "");
    int levels = 0, samples = 16, no_polygon = 0, band = 0, perturbation = 0;
    const char *lv = opt(&a, "--levels", NULL), *sv = opt(&a, "--samples", NULL);
    opt(&a, "--no-control-polygon", &no_polygon);
    opt(&a, "--band", &band);
    opt(&a, "--perturbation", &perturbation);
    if (lv && parse_int(lv, 0, 30, &levels) != 0) return usage_error("--levels must be >= 0, got '%s'", lv);
    if (sv && parse_int(sv, 1, 256, &samples) != 0) return usage_error("--samples must be 1..256, got '%s'", sv);
    rugo_shape_desc desc;
    if ((rc = load_shape(a.positional[0], &desc))) return rc;
    if ((rc = check_outline(a.positional[0], &desc, RUGO_CHECK_SELF_INTERSECTION))) {
        rugo_shape_desc_free(&desc);
        return rc;
    }
    int reversed = rugo_contour_orient_ccw(desc.control_points, desc.count);
    rugo_real* tol = NULL;
    if (band && (rc = finest_tolerances(a.positional[0], desc.has_roughness ? &desc.roughness : NULL,
                                        desc.control_points, desc.count, reversed, &tol))) {
        rugo_shape_desc_free(&desc);
        return rc;
    }
    rugo_pyramid* p = NULL;
    int J = log2_exact(desc.count);
    if (levels > 0) {
        if (J < 2 || levels > J - 2) {
            fprintf(stderr, "rugo render: --levels needs a power-of-two count with %d coarser levels of >= 4 points\n",
                    levels);
            free(tol);
            rugo_shape_desc_free(&desc);
            return EXIT_USAGE;
        }
        if ((rc = build_pyramid(a.positional[0], &desc, desc.filter, J - levels, &p))) {
            free(tol);
            rugo_shape_desc_free(&desc);
            return rc;
        }
    }
    rugo_contour c = {desc.control_points, desc.count};
    rugo_vec2 lo, hi;
    svg_contour_extent(c, &lo, &hi);
    if (band) { /* the band reaches at most the largest tolerance away from the curve */
        rugo_real widest = 0.0;
        for (int k = 0; k < desc.count; ++k)
            widest = fmax(widest, tol[k]);
        lo = rugo_v2(lo.x - widest, lo.y - widest);
        hi = rugo_v2(hi.x + widest, hi.y + widest);
    }
    const rugo_roughness_desc* rd = &desc.roughness;
    int draw_perturbation = perturbation && desc.has_roughness && rd->has_perturbation;
    rugo_contour pc = {rd->perturbation_points, rd->perturbation_count};
    if (draw_perturbation) {
        rugo_vec2 plo, phi;
        svg_contour_extent(pc, &plo, &phi);
        lo = rugo_v2(fmin(lo.x, plo.x), fmin(lo.y, plo.y));
        hi = rugo_v2(fmax(hi.x, phi.x), fmax(hi.y, phi.y));
    }
    svg_canvas svg;
    if (svg_open(&svg, out, lo, hi, 800.0) != 0) {
        fprintf(stderr, "rugo render: %s: cannot open for writing\n", out);
        rugo_pyramid_destroy(p);
        free(tol);
        rugo_shape_desc_free(&desc);
        return EXIT_INPUT;
    }
    static const char* const level_colours[] = {"#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02"};
    for (int k = 1; k <= levels; ++k) {
        rugo_contour ck;
        rugo_pyramid_level(p, J - k, &ck);
        svg_contour(&svg, ck, samples, level_colours[(k - 1) % 5], 1.2, "6,4");
    }
    if (!no_polygon) svg_control_polygon(&svg, c, "#999999");
    if (band) {
        svg_band(&svg, c, tol, samples, 1.0);
        svg_band(&svg, c, tol, samples, -1.0);
    }
    if (draw_perturbation) {
        /* Each perturbation segment is 2^-levels of a shape segment: fewer samples keep the file small. */
        int per = samples >> rd->perturbation_levels;
        fprintf(svg.file, "<g class=\"perturbation\">\n");
        svg_contour(&svg, pc, per < 2 ? 2 : per, "#a6761d", 0.8, NULL);
        fprintf(svg.file, "</g>\n");
    } else if (perturbation) {
        fprintf(svg.file, "<!-- no perturbation stored in the shape -->\n");
    }
    svg_contour(&svg, c, samples, "#1b9e77", 2.0, NULL);
    rc = svg_close(&svg) == 0 ? 0 : EXIT_INPUT;
    if (rc) fprintf(stderr, "rugo render: %s: write failed\n", out);
    rugo_pyramid_destroy(p);
    free(tol);
    rugo_shape_desc_free(&desc);
    return rc;
}

static int cmd_bake(int argc, char** argv) {
    static const char* const vals[] = {"-o", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, NULL, &a);
    if (rc) return rc;
    const char* out = opt(&a, "-o", NULL);
    if (a.positional_count != 1 || out == NULL) return usage_error("expects SHAPE.json -o OUT.rugo%s", "");
    const char* path = a.positional[0];
    rugo_shape_desc desc;
    rugo_shape* shape = NULL;
    if ((rc = load_shape_any(path, &desc, &shape))) return rc;
    if (shape == NULL && (rc = make_shape(path, &desc, &shape))) {
        rugo_shape_desc_free(&desc);
        return rc;
    }
    rugo_baked_error err;
    rugo_status st = rugo_shape_write_baked_file(shape, out, NULL, NULL, &err);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo bake: %s: %s (status %d: %s)\n", out, err.message, (int)st, rugo_status_string(st));
        rc = EXIT_INPUT;
    } else {
        size_t bytes = 0;
        rugo_shape_bake_size(shape, &bytes);
        printf("{\"output\": \"");
        for (const char* c = out; *c; ++c) /* a JSON string: escape what JSON requires */
            if (*c == '"' || *c == '\\')
                printf("\\%c", *c);
            else if ((unsigned char)*c < 0x20)
                printf("\\u%04x", (unsigned)(unsigned char)*c);
            else
                putchar(*c);
        printf("\", \"bytes\": %lu, \"version\": %d, \"control_points\": %d, \"finest_level\": %d, "
               "\"coarsest_level\": %d, \"rough\": %s, \"reversed\": %s}\n",
               (unsigned long)bytes, RUGO_BAKED_VERSION, 1 << rugo_shape_finest_level(shape),
               rugo_shape_finest_level(shape), rugo_shape_coarsest_level(shape),
               rugo_shape_is_rough(shape) ? "true" : "false", rugo_shape_was_reversed(shape) ? "true" : "false");
    }
    rugo_shape_destroy(shape);
    rugo_shape_desc_free(&desc);
    return rc;
}

static void usage(FILE* f) {
    fprintf(
        f,
        "usage: rugo COMMAND [ARGS]\n"
        "  info SHAPE.json                      control points, levels, area, centroid, inertia, perimeter\n"
        "  decompose SHAPE.json [--filter F] [--levels K]\n"
        "                                       wavelet pyramid from level J-1 down (F: cdf4.2 cdf4.4\n"
        "                                       cdf4.6 cdf4.8 cdf4.12)\n"
        "  refine SHAPE.json [--times K] [-o OUT.json]\n"
        "                                       double the control points K times; same curve\n"
        "  deform SHAPE.json --at U --delta DX,DY [--levels R] [--w W] [--details fixed|local] [-o "
        "OUT.json]\n"
        "                                       move the curve point at parameter U by (DX, DY), spread\n"
        "                                       over R levels with weights e^(-W s)\n"
        "  fit POINTS.json [--control-points N] [--param chord|uniform] [-o OUT.json]\n"
        "                                       least-squares closed contour through {\"points\": [...]}\n"
        "  import FILE.svg|POINTS [--path-id ID] [--control-points N | --tolerance T] [--samples M] -o OUT.json\n"
        "                                       outline from an SVG <path> (y flipped up) or a point list,\n"
        "                                       sampled and fitted; prints the fit error (docs/import.md)\n"
        "  render SHAPE.json -o OUT.svg [--levels K] [--samples N] [--no-control-polygon] [--band]\n"
        "         [--perturbation]              SVG picture; --band: the tolerance band, --perturbation:\n"
        "                                       the stored perturbation geometry\n"
        "  roughen SHAPE.json [--method wavelet|local|library] [--preset tipo_1|tipo_2|tipo_3|tipo_5]\n"
        "          [--profile PROFILE.csv] [--seed N] [--levels M] [-o OUT.json]\n"
        "                                       the shape with per-segment tolerances (and, for wavelet\n"
        "                                       or local, display perturbations M levels finer)\n"
        "  tolerances SHAPE.json [--estimator detail|coefficients] [--at SEGMENT,T]\n"
        "                                       tolerance of every segment at every level, or tolerance,\n"
        "                                       friction and restitution at one point\n"
        "  contacts A.json B.json [--pose-a X,Y,THETA] [--pose-b X,Y,THETA] [--level L] [--tolerance LAMBDA]\n"
        "                                       contact points between the placed shapes (THETA in radians;\n"
        "                                       L: 0 finest, -1, -2 coarser; LAMBDA: constant band for both)\n"
        "  bake SHAPE.json -o OUT.rugo          build the shape once and store it as a baked binary file\n"
        "                                       (docs/baked.md); loads >20x faster than building\n"
        "  help                                 this text\n"
        "Every SHAPE argument may be a JSON shape file or a baked file (told apart by content).\n"
        "Output is JSON on stdout (or the -o file); errors go to stderr with exit status 1 (bad input)\n"
        "or 2 (bad command line). See docs/cli.md.\n");
}

int main(int argc, char** argv) {
    if (argc < 2) {
        usage(stderr);
        return EXIT_USAGE;
    }
    g_command = argv[1];
    static const struct {
        const char* name;
        int (*run)(int, char**);
    } commands[] = {{"info", cmd_info},       {"decompose", cmd_decompose},
                    {"refine", cmd_refine},   {"deform", cmd_deform},
                    {"fit", cmd_fit},         {"import", cmd_import},         {"render", cmd_render}, {"contacts", cmd_contacts},
                    {"roughen", cmd_roughen}, {"tolerances", cmd_tolerances},
                    {"bake", cmd_bake}};
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; ++i)
        if (strcmp(argv[1], commands[i].name) == 0) return commands[i].run(argc - 2, argv + 2);
    if (strcmp(argv[1], "help") == 0 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        usage(stdout);
        return 0;
    }
    fprintf(stderr, "rugo: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return EXIT_USAGE;
}
