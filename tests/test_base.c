#include "core/internal.h"
#include "test_util.h"

#include <stdlib.h>
#include <string.h>

START_TEST(status_strings_distinct) {
    /* Every status has its own non-empty message: tools print them. */
    for (int a = 0; a < RUGO_STATUS_COUNT; ++a) {
        const char* sa = rugo_status_string((rugo_status)a);
        ck_assert_ptr_nonnull(sa);
        ck_assert_int_gt((int)strlen(sa), 0);
        ck_assert_str_ne(sa, "unknown status");
        for (int b = a + 1; b < RUGO_STATUS_COUNT; ++b)
            ck_assert_str_ne(sa, rugo_status_string((rugo_status)b));
    }
    ck_assert_str_eq(rugo_status_string((rugo_status)9999), "unknown status");
}
END_TEST

START_TEST(version_matches_header) { ck_assert_str_eq(rugo_version_string(), RUGO_VERSION_STRING); }
END_TEST

static int g_allocs, g_frees;
static void* counting_alloc(size_t n, void* ctx) {
    ++*(int*)ctx;
    ++g_allocs;
    return malloc(n);
}
static void counting_free(void* p, void* ctx) {
    (void)ctx;
    ++g_frees;
    free(p);
}

START_TEST(allocator_hooks_and_overflow) {
    int calls = 0;
    rugo_allocator a = {counting_alloc, counting_free, &calls};
    void* p = rugo__alloc_array(&a, 10, 8);
    ck_assert_ptr_nonnull(p);
    rugo__free(&a, p);
    ck_assert_int_eq(calls, 1);
    ck_assert_int_eq(g_frees, 1);
    /* count * size overflowing size_t is refused, not wrapped. */
    ck_assert_ptr_null(rugo__alloc_array(&a, SIZE_MAX / 2, 4));
    ck_assert_int_eq(calls, 1);
    /* A zeroed allocator means malloc/free. */
    rugo_allocator z;
    memset(&z, 0, sizeof z);
    p = rugo__alloc_array(&z, 3, 3);
    ck_assert_ptr_nonnull(p);
    rugo__free(&z, p);
}
END_TEST

START_TEST(wrap_and_power_of_two) {
    ck_assert_int_eq(rugo__wrap(-1, 8), 7);
    ck_assert_int_eq(rugo__wrap(-9, 8), 7);
    ck_assert_int_eq(rugo__wrap(8, 8), 0);
    ck_assert_int_eq(rugo__is_power_of_two(64), 1);
    ck_assert_int_eq(rugo__is_power_of_two(48), 0);
    ck_assert_int_eq(rugo__is_power_of_two(0), 0);
    ck_assert_int_eq(rugo__is_power_of_two(-4), 0);
}
END_TEST

int main(void) {
    Suite* s = suite_create("base");
    TCase* tc = tcase_create("base");
    tcase_add_test(tc, status_strings_distinct);
    tcase_add_test(tc, version_matches_header);
    tcase_add_test(tc, allocator_hooks_and_overflow);
    tcase_add_test(tc, wrap_and_power_of_two);
    suite_add_tcase(s, tc);
    return test_run_suite(s);
}
