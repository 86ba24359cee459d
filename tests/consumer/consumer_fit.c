/* Uses the installed import and fit shim through pkg-config rugo-fit from C: a 250 px pebble drawn in
 * SVG becomes a 2.5 m outline at 100 px per metre, centred on its centroid. */
#include <rugo/fit.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

int main(void) {
    static const char svg[] = "<svg xmlns='http://www.w3.org/2000/svg'>"
                              "<path d='M 0 125 A 125 125 0 0 1 250 125 A 125 125 0 0 1 0 125 Z'/></svg>";
    rugo_import_def def = rugo_default_import_def();
    def.text = svg;
    def.length = strlen(svg);
    def.scale = 1.0 / 100.0;
    def.recentre = 1;
    rugo_import_result r;
    rugo_parse_error err;
    rugo_status st = rugo_import_outline(&def, &r, &err);
    if (st != RUGO_OK) {
        fprintf(stderr, "rugo_import_outline: %s: %s\n", err.path, err.message);
        return 1;
    }
    rugo_contour c = {r.fit.control_points, r.fit.control_count};
    rugo_mass_properties mp = rugo_contour_mass_properties(c);
    const double expected = 3.14159265358979 * 1.25 * 1.25;
    int ok = fabs(mp.area - expected) < 1e-3 * expected && fabs(mp.centroid.x) < 1e-9 &&
             fabs(mp.centroid.y) < 1e-9;
    printf("consumer_fit: %d control points, area %.6f m^2 (expected %.6f), max_error %.3g m\n", c.count,
           mp.area, expected, r.fit.max_error);
    rugo_import_result_free(&r);
    return ok ? 0 : 1;
}
