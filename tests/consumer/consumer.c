/* Uses the installed headers and library: builds a pyramid of a circle-like outline and checks
 * its area against pi r^2 within the B-spline's known shrinkage. Exit code 0 on success. */
#include <rugo/rugo.h>
#ifdef RUGO_HAVE_FIT
#include <rugo/fit.h>
#endif

#include <math.h>
#include <stdio.h>
#include <string.h>

int main(void) {
    enum { N = 64 };
    rugo_vec2 pts[N];
    for (int k = 0; k < N; ++k) {
        double th = 6.283185307179586 * k / N;
        pts[k] = rugo_v2(cos(th), sin(th));
    }
    if (strcmp(rugo_version_string(), RUGO_VERSION_STRING) != 0) return 1;
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
