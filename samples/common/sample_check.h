/* Assertions for samples that run as tests: print what was checked, count failures. */
#ifndef RUGO_SAMPLE_CHECK_H
#define RUGO_SAMPLE_CHECK_H

#include <stddef.h>
#include <stdint.h>

/* Records "name: value <= limit" as a pass or a failure and prints it. Returns 1 if it passed. */
int sample_expect_le(const char* name, double value, double limit);
/* Records a condition. */
int sample_expect(const char* name, int ok);
/* 0 if every expectation passed, 1 otherwise; prints a summary line "N passed, M failed". */
int sample_finish(void);
/* max(a, b) that keeps NaN (fmax drops it): error accumulators must not hide a NaN. */
double sample_max(double a, double b);
/* Creates a directory and its parents (like mkdir -p); 0 on success. */
int sample_mkdir(const char* path);
/* FNV-1a 64 of n bytes, continuing from h (start from SAMPLE_FNV_OFFSET): the determinism hashes. */
#define SAMPLE_FNV_OFFSET 14695981039346656037ull
uint64_t sample_fnv1a(uint64_t h, const void* p, size_t n);

#endif
