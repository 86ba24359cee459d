/* libFuzzer target: the JSON shape reader, then a shape build from what it accepts, then the
 * round trips the tool relies on (JSON write/parse, bake/load). */
#include "fuzz_common.h"

#include <stdint.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    rugo_shape_desc desc;
    rugo_parse_error err;
    rugo_status st = rugo_shape_desc_parse((const char*)data, size, NULL, &desc, &err);
    FUZZ_CHECK(memchr(err.path, '\0', sizeof err.path) != NULL);
    FUZZ_CHECK(memchr(err.message, '\0', sizeof err.message) != NULL);
    if (st != RUGO_OK) return 0;
    /* Writing what was read and reading it back gives the same description. */
    rugo_text text;
    if (rugo_shape_desc_write(&desc, NULL, &text) == RUGO_OK) {
        rugo_shape_desc again;
        FUZZ_CHECK(rugo_shape_desc_parse(text.data, text.length, NULL, &again, &err) == RUGO_OK);
        FUZZ_CHECK(again.count == desc.count && again.filter == desc.filter);
        if (desc.count > 0)
            FUZZ_CHECK(memcmp(again.control_points, desc.control_points,
                              (size_t)desc.count * sizeof(rugo_vec2)) == 0);
        rugo_shape_desc_free(&again);
        rugo_text_free(&text);
    }
    rugo_real* lambda = NULL;
    rugo_shape_def def = rugo_default_shape_def();
    def.points = desc.control_points;
    def.count = desc.count;
    def.filter = desc.filter;
    if (desc.has_roughness && desc.count >= 1 && desc.count <= RUGO_MAX_CONTROL_POINTS) {
        lambda = (rugo_real*)malloc((size_t)desc.count * sizeof(rugo_real));
        rugo_contour file_order = {desc.control_points, desc.count}; /* ranges and profiles need the curve */
        if (lambda == NULL ||
            rugo_roughness_tolerances_on_contour(&desc.roughness, file_order, NULL, lambda) != RUGO_OK) {
            free(lambda);
            rugo_shape_desc_free(&desc);
            return 0;
        }
        for (int j = 0; j < desc.count; ++j)
            FUZZ_CHECK(isfinite(lambda[j]) && lambda[j] >= 0.0);
        def.tolerances = lambda;
        def.q = desc.roughness.q;
        def.estimator = desc.roughness.estimator;
        def.friction = desc.roughness.friction;
        def.restitution = desc.roughness.restitution;
    }
    rugo_shape* shape = NULL;
    rugo_contour_problem problem;
    st = rugo_shape_create(&def, &shape, &problem);
    if (st == RUGO_OK) {
        size_t need = 0;
        FUZZ_CHECK(rugo_shape_bake_size(shape, &need) == RUGO_OK);
        unsigned char* bytes = (unsigned char*)malloc(need);
        size_t written = 0;
        if (bytes != NULL) {
            FUZZ_CHECK(rugo_shape_bake(shape, bytes, need, &written) == RUGO_OK && written == need);
            rugo_shape* loaded = NULL;
            rugo_baked_error be;
            st = rugo_shape_load_baked(bytes, written, NULL, &loaded, &be);
            if (st != RUGO_OK)
                fprintf(stderr, "load: %s: %s %s\n", rugo_status_string(st), be.field, be.message);
            FUZZ_CHECK(st == RUGO_OK);
            unsigned char* again = (unsigned char*)malloc(need);
            if (again != NULL) {
                FUZZ_CHECK(rugo_shape_bake(loaded, again, need, &written) == RUGO_OK);
                FUZZ_CHECK(memcmp(bytes, again, need) == 0);
                free(again);
            }
            rugo_shape_destroy(loaded);
            free(bytes);
        }
        if (desc.count <= 256)
            fuzz_query_shape(shape, shape, rugo_identity_transform(), rugo_make_transform(0.1, 0.0, 0.3));
        rugo_shape_destroy(shape);
    }
    free(lambda);
    rugo_shape_desc_free(&desc);
    return 0;
}
