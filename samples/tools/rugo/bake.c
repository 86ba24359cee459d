/* `rugo bake`: a shape built once and stored as a baked binary file (docs/baked.md). */
#include "cli.h"

int cmd_bake(int argc, char** argv) {
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
        fprintf(stderr, "rugo bake: %s: %s (status %d: %s)\n", out, err.message, (int)st,
                rugo_status_string(st));
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
               rugo_shape_is_rough(shape) ? "true" : "false",
               rugo_shape_was_reversed(shape) ? "true" : "false");
    }
    rugo_shape_destroy(shape);
    rugo_shape_desc_free(&desc);
    return rc;
}
