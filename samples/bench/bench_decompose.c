/* Benchmark: full wavelet decomposition (down to 4 points) and reconstruction of a 4096-point contour,
 * for every filter. Prints CSV (filter, n, operation, ns per call, points per microsecond) and a summary
 * with ratios against CDF(4,2) measured in the same run. --quick: few repetitions (used by the tests). */
#define _POSIX_C_SOURCE 200809L
#include "rugo/rugo.h"
#include "sample_shapes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

int main(int argc, char** argv) {
    int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
    enum { N = 4096, LEVELS = 10 }; /* 4096 -> 4 points */
    const int reps = quick ? 5 : 2000;
    rugo_vec2* src = malloc(sizeof *src * N);
    rugo_vec2* data = malloc(sizeof *data * N);
    rugo_vec2* scratch = malloc(sizeof *scratch * N);
    if (!src || !data || !scratch) return 1;
    sample_object(N, rugo_v2(0.0, 0.0), 1.0, src);
    double analysis_ns[RUGO_FILTER_COUNT], synthesis_ns[RUGO_FILTER_COUNT];
    double checksum = 0.0, worst_error = 0.0;
    printf("filter,n,operation,ns_per_call,points_per_us\n");
    for (int f = 0; f < RUGO_FILTER_COUNT; ++f) {
        /* Best of 5 batches: the least disturbed measurement on a shared machine. */
        double best_a = 1e300, best_s = 1e300;
        for (int batch = 0; batch < 5; ++batch) {
            double ta = 0.0, ts = 0.0;
            for (int r = 0; r < reps; ++r) {
                memcpy(data, src, sizeof *data * N);
                double t0 = now_ns();
                rugo_wavelet_analyze_levels((rugo_filter)f, data, N, LEVELS, scratch, NULL);
                double t1 = now_ns();
                rugo_wavelet_synthesize_levels((rugo_filter)f, data, N, LEVELS, scratch, NULL);
                double t2 = now_ns();
                ta += t1 - t0;
                ts += t2 - t1;
                checksum += data[r % N].x;
            }
            if (ta / reps < best_a) best_a = ta / reps;
            if (ts / reps < best_s) best_s = ts / reps;
        }
        /* What was timed must also be right: the last round trip reproduces the input. */
        for (int i = 0; i < N; ++i) {
            double e = fabs(data[i].x - src[i].x) + fabs(data[i].y - src[i].y);
            if (!(e <= worst_error)) worst_error = e;
        }
        analysis_ns[f] = best_a;
        synthesis_ns[f] = best_s;
        printf("%s,%d,analysis,%.0f,%.1f\n", rugo_filter_name((rugo_filter)f), N, best_a,
               N / (best_a / 1000.0));
        printf("%s,%d,synthesis,%.0f,%.1f\n", rugo_filter_name((rugo_filter)f), N, best_s,
               N / (best_s / 1000.0));
    }
    printf("summary: full decomposition of %d points with %s: %.1f points/us; time relative to cdf4.2:", N,
           rugo_filter_name(RUGO_FILTER_DEFAULT), N / (analysis_ns[RUGO_FILTER_DEFAULT] / 1000.0));
    for (int f = 0; f < RUGO_FILTER_COUNT; ++f)
        printf(" %s %.2fx", rugo_filter_name((rugo_filter)f), analysis_ns[f] / analysis_ns[0]);
    printf("; synthesis/analysis (cdf4.8) %.2f (checksum %.3g)\n",
           synthesis_ns[RUGO_FILTER_DEFAULT] / analysis_ns[RUGO_FILTER_DEFAULT], checksum);
    free(src);
    free(data);
    free(scratch);
    if (!(worst_error <= 1e-12)) {
        fprintf(stderr, "bench_decompose: round trip error %.3g > 1e-12\n", worst_error);
        return 1;
    }
    return 0;
}
