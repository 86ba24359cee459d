/* Uses the installed headers and library: checks the version macros against the package's version
 * (RUGO_EXPECTED_VERSION, given by the build: the CMake package's or pkg-config's), builds a pyramid
 * of a circle-like outline and checks its area against pi r^2 within the B-spline's known shrinkage.
 * Exit code 0 on success. */
#include <rugo/rugo.h>
#ifdef RUGO_HAVE_FIT
#include <rugo/fit.h>
#endif

#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef RUGO_EXPECTED_VERSION
#error "build with -DRUGO_EXPECTED_VERSION=\"x.y.z\" (the installed package's version)"
#endif
/* The macros work in the preprocessor. */
#if !RUGO_VERSION_AT_LEAST(0, 2, 0) || RUGO_VERSION_AT_LEAST(RUGO_VERSION_MAJOR + 1, 0, 0)
#error "RUGO_VERSION_AT_LEAST is wrong"
#endif

/* The four version macros, the runtime string and the package agree; AT_LEAST orders versions. */
static int check_version(void) {
    char text[64];
    snprintf(text, sizeof text, "%d.%d.%d", RUGO_VERSION_MAJOR, RUGO_VERSION_MINOR, RUGO_VERSION_PATCH);
    int ok = strcmp(text, RUGO_VERSION_STRING) == 0 &&
             strcmp(RUGO_VERSION_STRING, RUGO_EXPECTED_VERSION) == 0 &&
             strcmp(rugo_version_string(), RUGO_VERSION_STRING) == 0;
    ok &= RUGO_VERSION_NUMBER == RUGO_VERSION_MAJOR * 10000 + RUGO_VERSION_MINOR * 100 + RUGO_VERSION_PATCH;
    ok &= RUGO_VERSION_AT_LEAST(RUGO_VERSION_MAJOR, RUGO_VERSION_MINOR, RUGO_VERSION_PATCH);
    ok &= !RUGO_VERSION_AT_LEAST(RUGO_VERSION_MAJOR, RUGO_VERSION_MINOR, RUGO_VERSION_PATCH + 1);
    ok &= !RUGO_VERSION_AT_LEAST(RUGO_VERSION_MAJOR, RUGO_VERSION_MINOR + 1, 0);
    ok &= RUGO_VERSION_AT_LEAST(RUGO_VERSION_MAJOR - 1, 99, 99);
    if (!ok)
        fprintf(stderr, "version mismatch: macros %s, library %s, package %s\n", text, rugo_version_string(),
                RUGO_EXPECTED_VERSION);
    return ok;
}

int main(void) {
    enum { N = 64 };
    rugo_vec2 pts[N];
    for (int k = 0; k < N; ++k) {
        double th = 6.283185307179586 * k / N;
        pts[k] = rugo_v2(cos(th), sin(th));
    }
    if (!check_version()) return 1;
    rugo_pyramid_def def = rugo_default_pyramid_def();
    def.points = pts;
    def.count = N;
    rugo_pyramid* p = NULL;
    rugo_status st = rugo_pyramid_create(&def, &p, NULL);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo_pyramid_create: %s\n", rugo_status_string(st));
        return 1;
    }
    rugo_contour c;
    rugo_pyramid_level(p, rugo_pyramid_finest_level(p), &c);
    rugo_mass_properties mp = rugo_contour_mass_properties(c);
    rugo_pyramid_destroy(p);
    /* The B-spline of points on the unit circle lies slightly inside it. */
    if (!(mp.area < 3.14159266 && mp.area > 3.13)) {
        fprintf(stderr, "area %.17g out of range\n", mp.area);
        return 1;
    }
#ifdef RUGO_HAVE_FIT
    rugo_vec2 ctrl[16];
    rugo_fit_def fd = rugo_default_fit_def();
    fd.samples = pts;
    fd.sample_count = N;
    fd.control_count = 16;
    rugo_fit_result fr;
    if (rugo_fit_contour(&fd, ctrl, &fr) != RUGO_OK || !(fr.max_error < 1e-2)) return 1;
#endif
    printf("consumer ok: area %.9f, librugo %s\n", mp.area, rugo_version_string());
    return 0;
}
