/* Shapes in and out: reading a shape file (JSON or baked, told apart by content), checking and building
 * its outline, pyramid and shape, writing a description, reporting a bad input; and `rugo info`. */
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

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
        fprintf(stderr, "rugo %s: %s: byte %lu: %s%s%s (status %d: %s)\n", g_command, path,
                (unsigned long)err.offset, err.field, err.field[0] ? ": " : "", err.message, (int)st,
                rugo_status_string(st));
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
    desc->has_roughness = true;
    desc->roughness.tolerance_count = c.count;
    desc->roughness.friction = rugo_shape_friction_map(s);
    desc->roughness.restitution = rugo_shape_restitution(s);
    return 0;
}

/* Reads a shape file, JSON or baked. With `baked` non-NULL a baked file's shape is handed back there
 * (the caller destroys it) for commands that can use the stored shape as it is. */
int load_shape_any(const char* path, rugo_shape_desc* desc, rugo_shape** baked) {
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
    rugo_text text;
    rugo_status st = rugo_read_file(path, NULL, &text);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo %s: %s: cannot read: %s (status %d)\n", g_command, path, rugo_status_string(st),
                (int)st);
        return EXIT_INPUT;
    }
    rugo_parse_error err;
    st = rugo_shape_desc_parse(text.data, text.length, NULL, desc, &err);
    rugo_text_free(&text);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo %s: %s:%d:%d: %s%s%s (status %d: %s)\n", g_command, path, err.line, err.column,
                err.path, err.path[0] ? ": " : "", err.message, (int)st, rugo_status_string(st));
        return EXIT_INPUT;
    }
    return 0;
}

int load_shape(const char* path, rugo_shape_desc* desc) { return load_shape_any(path, desc, NULL); }

/* Reports an invalid outline: the status, then the field, the value and a way out where the status
 * has them. desc (may be NULL) gives the control points for the messages that quote them. */
void report_problem(const char* path, rugo_status st, const rugo_contour_problem* pr,
                    const rugo_shape_desc* desc) {
    fprintf(stderr, "rugo %s: %s: %s (status %d)", g_command, path, rugo_status_string(st), (int)st);
    if (st == RUGO_ERR_SELF_INTERSECTING) {
        fprintf(stderr, ": segments %d and %d cross near (%.9g, %.9g)", pr->segment_a, pr->segment_b,
                pr->where.x, pr->where.y);
    } else if (st == RUGO_ERR_NOT_FINITE && pr->index >= 0) {
        fprintf(stderr, ": control_points[%d]", pr->index);
        if (desc != NULL && pr->index < desc->count)
            fprintf(stderr, " is (%.17g, %.17g); give finite coordinates", desc->control_points[pr->index].x,
                    desc->control_points[pr->index].y);
    } else if (st == RUGO_ERR_NOT_FINITE && desc != NULL) {
        double big = 0.0;
        for (int i = 0; i < desc->count; ++i)
            big = fmax(big, fmax(fabs(desc->control_points[i].x), fabs(desc->control_points[i].y)));
        fprintf(stderr,
                ": control_points: coordinates up to %.6g make the area overflow (they must stay below about "
                "1e150); scale the outline down, e.g. to metres (rugo import --px-per-metre)",
                big);
    } else if (st == RUGO_ERR_NOT_POWER_OF_TWO && desc != NULL) {
        int lo = 4;
        while (lo * 2 <= desc->count && lo < RUGO_MAX_CONTROL_POINTS / 2)
            lo *= 2;
        fprintf(
            stderr,
            ": control_points has %d points; the wavelet levels need a power of two (4, 8, 16, ...): refit "
            "the outline with 'rugo fit --control-points %d' (or %d), or import it with 'rugo import "
            "--control-points %d'",
            desc->count, lo, lo * 2, lo * 2);
    } else if (st == RUGO_ERR_BAD_SIZE && desc != NULL) {
        rugo_vec2 lo, hi;
        rugo_contour_bounds((rugo_contour){desc->control_points, desc->count}, &lo, &hi);
        fprintf(stderr, ": the outline is %.6g units across; a shape must be from %g to %g: rescale it",
                hypot(hi.x - lo.x, hi.y - lo.y), RUGO_SHAPE_MIN_SIZE, RUGO_SHAPE_MAX_SIZE);
    }
    fprintf(stderr, "\n");
}

/* Validates a loaded outline; on failure reports it (naming the crossing segments or the bad point)
 * and returns EXIT_INPUT. The caller still owns and frees desc. */
int check_outline(const char* path, const rugo_shape_desc* desc, int flags) {
    rugo_contour_problem pr;
    rugo_status st = rugo_contour_check(desc->control_points, desc->count, flags, &pr, NULL);
    if (st == RUGO_OK) return 0;
    report_problem(path, st, &pr, desc);
    return EXIT_INPUT;
}

int build_pyramid(const char* path, const rugo_shape_desc* desc, rugo_filter filter, int coarsest,
                  rugo_pyramid** out) {
    rugo_pyramid_def def = rugo_default_pyramid_def();
    def.points = desc->control_points;
    def.count = desc->count;
    def.filter = filter;
    def.coarsest_level = coarsest;
    rugo_contour_problem pr;
    rugo_status st = rugo_pyramid_create(&def, out, &pr);
    if (st != RUGO_OK) {
        report_problem(path, st, &pr, desc);
        return EXIT_INPUT;
    }
    return 0;
}

/* Writes a shape description (the library's writer) to `path` or stdout, with an optional extra member
 * (`"name": {...}`) spliced in before the closing brace. Returns 0 or EXIT_INPUT. */
int write_desc(const char* path, const rugo_shape_desc* d, const char* extra) {
    rugo_text written;
    rugo_status st = rugo_shape_desc_write(d, NULL, &written);
    if (st != RUGO_OK) return fail("writing the shape", st);
    const char* text = written.data;
    const size_t len = written.length;
    FILE* f = path ? fopen(path, "w") : stdout;
    if (f == NULL) {
        rugo_text_free(&written);
        fprintf(stderr, "rugo %s: %s: cannot open for writing\n", g_command, path);
        return EXIT_INPUT;
    }
    const char* close = strrchr(text, '}');
    if (extra && close) {
        fwrite(text, 1, (size_t)(close - text), f);
        fprintf(f, ", %s}\n", extra);
    } else {
        fputs(text, f);
        if (len == 0 || text[len - 1] != '\n') fputc('\n', f);
    }
    rugo_text_free(&written);
    int bad = ferror(f);
    if (path) bad |= fclose(f) != 0;
    if (bad) {
        fprintf(stderr, "rugo %s: %s: write failed\n", g_command, path ? path : "stdout");
        return EXIT_INPUT;
    }
    return 0;
}

/* A shape without roughness. */
int write_shape(const char* path, const rugo_vec2* points, int count, rugo_filter filter, const char* extra) {
    rugo_shape_desc d;
    memset(&d, 0, sizeof d);
    d.control_points = (rugo_vec2*)points;
    d.count = count;
    d.filter = filter;
    return write_desc(path, &d, extra);
}

int log2_exact(int n) {
    int j = 0;
    while ((1 << j) < n)
        ++j;
    return (1 << j) == n ? j : -1;
}

/* Prints a parse error with the file, line and column (when known), the field and the message. */
void report_parse_error(const char* file, rugo_status st, const rugo_parse_error* err) {
    fprintf(stderr, "rugo %s: %s", g_command, file);
    if (err->line > 0) fprintf(stderr, ":%d:%d", err->line, err->column);
    fprintf(stderr, ": %s%s%s (status %d: %s)\n", err->path, err->path[0] ? ": " : "",
            err->message[0] ? err->message : rugo_status_string(st), (int)st, rugo_status_string(st));
}

/* Builds the immutable shape (pyramid, tolerances, tree, mass) of a shape file. */
int make_shape(const char* path, const rugo_shape_desc* desc, rugo_shape** out) {
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
        report_problem(path, st, &pr, desc);
        return EXIT_INPUT;
    }
    return 0;
}

int cmd_info(int argc, char** argv) {
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
    rugo_vec2 lo, hi;
    rugo_contour_bounds(c, &lo, &hi);
    const double size = hypot(hi.x - lo.x, hi.y - lo.y);
    printf(", \"area\": %.17g, \"centroid\": [%.17g, %.17g], \"inertia\": %.17g, \"perimeter\": %.17g, "
           "\"size\": %.17g}\n",
           mp.area, mp.centroid.x, mp.centroid.y, mp.inertia, rugo_contour_perimeter(c), size);
    /* As rugo import's default --max-size: far beyond the 0.1-10 m bodies Box2D is tuned for. */
    if (size > 1e4)
        fprintf(
            stderr,
            "rugo %s: warning: %s: the outline is %.6g units across; if they are metres (Box2D's), that is "
            "far beyond the 0.1-10 m bodies a physics engine simulates well: rescale it (rugo import "
            "--px-per-metre)\n",
            g_command, a.positional[0], size);
    rugo_shape_desc_free(&desc);
    return 0;
}
