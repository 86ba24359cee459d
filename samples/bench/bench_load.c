/* Benchmark: loading a baked shape against building it from its JSON file (parse, tolerances, shape
 * build: pyramid, λ/β, MOBBtree, mass), both from memory, for rough shapes of 64..4096 control points.
 * Prints CSV (n, json_bytes, baked_bytes, build_us, load_us, ratio: medians of interleaved batches)
 * and a summary with the ratios measured in the same run (absolute times on a shared machine are
 * noise). Exits 1 if a loaded shape does not bake back to the same bytes. --quick: few repetitions
 * (used by the tests). */
#define _POSIX_C_SOURCE 200809L
#include "rugo/rugo.h"
#include "sample_shapes.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_us(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e6 + (double)ts.tv_nsec / 1e3;
}

/* Median of v[0..n-1] (n <= 9; sorts v). */
static double median(double* v, int n) {
    for (int i = 1; i < n; ++i)
        for (int k = i; k > 0 && v[k - 1] > v[k]; --k) {
            const double t = v[k];
            v[k] = v[k - 1];
            v[k - 1] = t;
        }
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* What a game does without baking: parse the file, resolve the roughness, build the shape. */
static rugo_status build_from_json(const char* text, size_t length, rugo_shape** out) {
    rugo_shape_desc desc;
    rugo_status st = rugo_shape_desc_parse(text, length, NULL, &desc, NULL);
    if (st != RUGO_OK) return st;
    rugo_real* lambda = malloc(sizeof *lambda * (size_t)desc.count);
    st = lambda ? rugo_roughness_tolerances(&desc.roughness, desc.count, lambda) : RUGO_ERR_OUT_OF_MEMORY;
    if (st == RUGO_OK) {
        rugo_shape_def def = rugo_default_shape_def();
        def.points = desc.control_points;
        def.count = desc.count;
        def.filter = desc.filter;
        def.tolerances = lambda;
        def.q = desc.roughness.q;
        def.estimator = desc.roughness.estimator;
        def.friction = desc.roughness.friction;
        def.restitution = desc.roughness.restitution;
        st = rugo_shape_create(&def, out, NULL);
    }
    free(lambda);
    rugo_shape_desc_free(&desc);
    return st;
}

int main(int argc, char** argv) {
    const int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
    static const int sizes[] = {64, 256, 1024, 4096};
    const int nsizes = quick ? 2 : 4;
    double ratio_min = 1e300, ratio_max = 0.0;
    int bad = 0;
    printf("n,json_bytes,baked_bytes,build_us,load_us,ratio\n");
    for (int si = 0; si < nsizes; ++si) {
        const int n = sizes[si];
        rugo_vec2* pts = malloc(sizeof *pts * (size_t)n);
        rugo_real* tol = malloc(sizeof *tol * (size_t)n);
        if (!pts || !tol) return 1;
        sample_object(n, rugo_v2(0.0, 0.0), 1.0, pts);
        for (int i = 0; i < n; ++i)
            tol[i] = 0.002 + 0.001 * (double)(i % 5);
        rugo_shape_desc d;
        memset(&d, 0, sizeof d);
        d.control_points = pts;
        d.count = n;
        d.filter = RUGO_FILTER_DEFAULT;
        d.has_roughness = true;
        d.roughness = rugo_default_roughness_desc();
        d.roughness.kind = RUGO_ROUGHNESS_TOLERANCES;
        d.roughness.tolerances = tol;
        d.roughness.tolerance_count = n;
        rugo_text json;
        rugo_shape* built = NULL;
        if (rugo_shape_desc_write(&d, NULL, &json) != RUGO_OK ||
            build_from_json(json.data, json.length, &built) != RUGO_OK) {
            fprintf(stderr, "bench_load: cannot build the %d-point shape\n", n);
            return 1;
        }
        size_t size = 0, written = 0;
        rugo_shape_bake_size(built, &size);
        unsigned char* baked = malloc(size);
        unsigned char* again = malloc(size);
        if (!baked || !again || rugo_shape_bake(built, baked, size, &written) != RUGO_OK) return 1;
        /* Median of batches for each side, batches of the two interleaved so that both see the same
         * machine load; the ratio is taken within this run. Build is slower, so fewer reps. */
        const int reps_build = quick ? 2 : (n <= 256 ? 100 : 20),
                  reps_load = quick ? 10 : (n <= 256 ? 2000 : 200);
        enum { MAX_BATCHES = 9 };
        const int batches = quick ? 3 : MAX_BATCHES;
        double build_us[MAX_BATCHES], load_us[MAX_BATCHES];
        for (int batch = 0; batch < batches; ++batch) {
            double t0 = now_us();
            for (int r = 0; r < reps_build; ++r) {
                rugo_shape* s = NULL;
                if (build_from_json(json.data, json.length, &s) != RUGO_OK) return 1;
                rugo_shape_destroy(s);
            }
            double t1 = now_us();
            for (int r = 0; r < reps_load; ++r) {
                rugo_shape* s = NULL;
                if (rugo_shape_load_baked(baked, size, NULL, &s, NULL) != RUGO_OK) return 1;
                rugo_shape_destroy(s);
            }
            double t2 = now_us();
            build_us[batch] = (t1 - t0) / reps_build;
            load_us[batch] = (t2 - t1) / reps_load;
        }
        const double med_build = median(build_us, batches), med_load = median(load_us, batches);
        /* What was timed must also be right: the loaded shape bakes back to the same bytes. */
        rugo_shape* loaded = NULL;
        if (rugo_shape_load_baked(baked, size, NULL, &loaded, NULL) != RUGO_OK ||
            rugo_shape_bake(loaded, again, size, &written) != RUGO_OK || memcmp(baked, again, size) != 0)
            bad = 1;
        rugo_shape_destroy(loaded);
        const double ratio = med_build / med_load;
        if (ratio < ratio_min) ratio_min = ratio;
        if (ratio > ratio_max) ratio_max = ratio;
        printf("%d,%lu,%lu,%.1f,%.1f,%.1f\n", n, (unsigned long)json.length, (unsigned long)size, med_build,
               med_load, ratio);
        rugo_text_free(&json);
        rugo_shape_destroy(built);
        free(baked);
        free(again);
        free(pts);
        free(tol);
    }
    printf("# summary: loading a baked shape is %.1fx to %.1fx faster than building it from JSON (target "
           "20x)%s\n",
           ratio_min, ratio_max, bad ? "; ROUND TRIP MISMATCH" : "");
    return bad ? 1 : 0;
}
