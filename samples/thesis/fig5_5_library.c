/* Thesis Fig. 5.5 and 5.6: the tolerance library. Fig. 5.5 tabulates tipo_3 on a 32-segment contour
 * and tipo_5 on a 128-segment one (rows 0..31 printed, then "...", then row 127); Fig. 5.6 draws
 * tipo_3 on 32 segments as a bar chart. Writes fig5_5.json (both columns, every segment),
 * fig5_5.csv and fig5_5.txt (the table: segment, tipo_3, tipo_5; tipo_3 empty past segment 31 as in
 * the thesis) and fig5_6.svg (the bars). Checks every value against the thesis' printed table; the
 * rows the thesis elides (tipo_5, 32..126) must continue its 16-segment pattern. */
#include "rugo/rugo.h"
#include "sample_check.h"
#include "svg.h"

#include <math.h>
#include <stdio.h>

enum { N3 = 32, N5 = 128 };

/* Figure 5.5 as printed: rows 0..31 of both columns; row 127 of tipo_5 reads 0.04. */
static const double THESIS_TIPO_3[32] = {0.32, 0.24, 0.20, 0.24, 0.32, 0.24, 0.20, 0.24, 0.32, 0.24, 0.20,
                                         0.24, 0.32, 0.24, 0.20, 0.24, 0.32, 0.24, 0.20, 0.24, 0.32, 0.24,
                                         0.20, 0.24, 0.32, 0.24, 0.20, 0.24, 0.32, 0.24, 0.20, 0.24};
static const double THESIS_TIPO_5[32] = {0.55, 0.55, 0.55, 0.55, 0.04, 0.04, 0.04, 0.04, 0.65, 0.65, 0.65,
                                         0.65, 0.04, 0.04, 0.04, 0.04, 0.55, 0.55, 0.55, 0.55, 0.04, 0.04,
                                         0.04, 0.04, 0.65, 0.65, 0.65, 0.65, 0.04, 0.04, 0.04, 0.04};
static const double THESIS_TIPO_5_ROW_127 = 0.04;

/* Fig. 5.6: one bar per segment. World units: x = segment, y = 50 λ (so the picture is not flat). */
static int bar_chart(const char* path, const double* v, int n) {
    const double top = 22.0;
    svg_canvas c;
    if (svg_open(&c, path, rugo_v2(-3.0, -3.0), rugo_v2((double)n + 1.0, top), 640.0) != 0) return -1;
    for (int i = 0; i < n; ++i) {
        const double x0 = ((double)i + 0.15 - c.ox) * c.scale, x1 = ((double)i + 0.85 - c.ox) * c.scale;
        const double y0 = c.height - (0.0 - c.oy) * c.scale, y1 = c.height - (50.0 * v[i] - c.oy) * c.scale;
        fprintf(c.file, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"#1b9e77\"/>\n", x0,
                y1, x1 - x0, y0 - y1);
        if (i % 4 == 0) {
            char label[16];
            snprintf(label, sizeof label, "%d", i);
            svg_text(&c, rugo_v2((double)i + 0.1, -1.8), label, 11.0);
        }
    }
    /* axis and ticks at 0.1, 0.2, 0.3 */
    svg_arrow(&c, rugo_v2(0.0, 0.0), rugo_v2((double)n + 0.8, 0.0), "#333333");
    svg_arrow(&c, rugo_v2(0.0, 0.0), rugo_v2(0.0, top - 2.5), "#333333");
    for (int k = 1; k <= 3; ++k) {
        char label[16];
        snprintf(label, sizeof label, "%.1f", 0.1 * k);
        svg_text(&c, rugo_v2(-2.8, 5.0 * k - 0.4), label, 11.0);
    }
    svg_text(&c, rugo_v2(1.0, top - 0.5), "Fig. 5.6: tolerances tipo_3 on a 32-segment contour", 14.0);
    return svg_close(&c);
}

int main(int argc, char** argv) {
    const char* dir = argc > 1 ? argv[1] : "out/fig5_5_library";
    if (sample_mkdir(dir) != 0) {
        fprintf(stderr, "cannot create %s\n", dir);
        return 1;
    }
    double t3[N3], t5[N5];
    rugo_tolerance_preset p3, p5;
    if (rugo_preset_from_name("tipo_3", &p3) != RUGO_OK || rugo_preset_from_name("tipo_5", &p5) != RUGO_OK)
        return 1;
    if (rugo_tolerances_preset(p3, 0, N3, t3) != RUGO_OK || rugo_tolerances_preset(p5, 0, N5, t5) != RUGO_OK)
        return 1;

    int bad3 = 0, bad5 = 0, bad5_elided = 0;
    for (int i = 0; i < N3; ++i)
        bad3 += t3[i] != THESIS_TIPO_3[i];
    for (int i = 0; i < 32; ++i)
        bad5 += t5[i] != THESIS_TIPO_5[i];
    bad5 += t5[127] != THESIS_TIPO_5_ROW_127;
    for (int i = 32; i < 127; ++i)
        bad5_elided += t5[i] != THESIS_TIPO_5[i % 32];
    sample_expect("tipo_3, segments 0..31, equals Fig. 5.5 exactly", bad3 == 0);
    sample_expect("tipo_5, segments 0..31 and 127, equals Fig. 5.5 exactly", bad5 == 0);
    sample_expect("tipo_5, segments 32..126 (elided in Fig. 5.5), continue its pattern", bad5_elided == 0);
    int check = 0;
    check |= rugo_tolerances_check(t3, N3, NULL) != RUGO_OK;
    check |= rugo_tolerances_check(t5, N5, NULL) != RUGO_OK;
    sample_expect("both columns pass rugo_tolerances_check", check == 0);

    char path[1100];
    snprintf(path, sizeof path, "%s/fig5_5.json", dir);
    FILE* f = fopen(path, "w");
    if (f == NULL) return 1;
    fprintf(f, "{\"figure\": \"5.5\", \"matches_thesis\": %s,\n \"tipo_3\": {\"segments\": %d, \"values\": [",
            bad3 == 0 && bad5 == 0 && bad5_elided == 0 ? "true" : "false", N3);
    for (int i = 0; i < N3; ++i)
        fprintf(f, "%s%.2f", i ? ", " : "", t3[i]);
    fprintf(f, "]},\n \"tipo_5\": {\"segments\": %d, \"values\": [", N5);
    for (int i = 0; i < N5; ++i)
        fprintf(f, "%s%.2f", i ? ", " : "", t5[i]);
    fprintf(f, "]}}\n");
    sample_expect("wrote fig5_5.json", fclose(f) == 0);

    snprintf(path, sizeof path, "%s/fig5_5.csv", dir);
    f = fopen(path, "w");
    if (f == NULL) return 1;
    fprintf(f, "segment,tipo_3,tipo_5\n");
    for (int i = 0; i < N5; ++i) {
        if (i < N3)
            fprintf(f, "%d,%.2f,%.2f\n", i, t3[i], t5[i]);
        else
            fprintf(f, "%d,,%.2f\n", i, t5[i]);
    }
    sample_expect("wrote fig5_5.csv", fclose(f) == 0);

    snprintf(path, sizeof path, "%s/fig5_5.txt", dir);
    f = fopen(path, "w");
    if (f == NULL) return 1;
    fprintf(f,
            "Figure 5.5: tolerances of the library on contours of 32 (tipo_3) and 128 (tipo_5) segments\n\n");
    fprintf(f, "segment  tipo_3  tipo_5\n");
    for (int i = 0; i < N5; ++i) {
        if (i < N3)
            fprintf(f, "%7d  %6.2f  %6.2f\n", i, t3[i], t5[i]);
        else
            fprintf(f, "%7d  %6s  %6.2f\n", i, "-", t5[i]);
    }
    sample_expect("wrote fig5_5.txt", fclose(f) == 0);

    snprintf(path, sizeof path, "%s/fig5_6.svg", dir);
    sample_expect("wrote fig5_6.svg", bar_chart(path, t3, N3) == 0);
    printf("tipo_3 (32): %.2f %.2f %.2f %.2f ...; tipo_5 (128): %.2f x4, %.2f x4, %.2f x4, %.2f x4 ...\n",
           t3[0], t3[1], t3[2], t3[3], t5[0], t5[4], t5[8], t5[12]);
    return sample_finish();
}
