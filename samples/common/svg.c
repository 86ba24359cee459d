#include "svg.h"

#include <math.h>

static double px(const svg_canvas* c, double x) { return (x - c->ox) * c->scale; }
static double py(const svg_canvas* c, double y) { return c->height - (y - c->oy) * c->scale; }

int svg_open(svg_canvas* c, const char* path, rugo_vec2 lo, rugo_vec2 hi, double width_px) {
    double w = hi.x - lo.x, h = hi.y - lo.y;
    double size = w > h ? w : h;
    if (!(size > 0.0)) size = 1.0;
    double margin = 0.05 * size;
    c->file = fopen(path, "w");
    if (c->file == NULL) return -1;
    c->scale = width_px / (w + 2.0 * margin > 0.0 ? w + 2.0 * margin : 1.0);
    c->ox = lo.x - margin;
    c->oy = lo.y - margin;
    c->height = (h + 2.0 * margin) * c->scale;
    fprintf(c->file,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
            "viewBox=\"0 0 %.2f %.2f\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
            width_px, c->height, width_px, c->height);
    return 0;
}

int svg_close(svg_canvas* c) {
    fprintf(c->file, "</svg>\n");
    int err = ferror(c->file);
    return (fclose(c->file) == 0 && !err) ? 0 : -1;
}

void svg_contour(svg_canvas* c, rugo_contour k, int per_segment, const char* stroke, double width,
                 const char* dash) {
    fprintf(c->file, "<polygon fill=\"none\" stroke=\"%s\" stroke-width=\"%.2f\"%s%s%s points=\"", stroke,
            width, dash ? " stroke-dasharray=\"" : "", dash ? dash : "", dash ? "\"" : "");
    for (int j = 0; j < k.count; ++j)
        for (int i = 0; i < per_segment; ++i) {
            rugo_vec2 p = rugo_contour_point(k, j, (double)i / per_segment);
            fprintf(c->file, "%.2f,%.2f ", px(c, p.x), py(c, p.y));
        }
    fprintf(c->file, "\"/>\n");
}

void svg_control_polygon(svg_canvas* c, rugo_contour k, const char* stroke) {
    fprintf(c->file, "<polygon fill=\"none\" stroke=\"%s\" stroke-width=\"0.7\" points=\"", stroke);
    for (int j = 0; j < k.count; ++j)
        fprintf(c->file, "%.2f,%.2f ", px(c, k.points[j].x), py(c, k.points[j].y));
    fprintf(c->file, "\"/>\n");
    for (int j = 0; j < k.count; ++j)
        svg_point(c, k.points[j], 1.8, stroke);
}

void svg_point(svg_canvas* c, rugo_vec2 p, double radius_px, const char* fill) {
    fprintf(c->file, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"%s\"/>\n", px(c, p.x), py(c, p.y),
            radius_px, fill);
}

void svg_arrow(svg_canvas* c, rugo_vec2 from, rugo_vec2 to, const char* stroke) {
    double x0 = px(c, from.x), y0 = py(c, from.y), x1 = px(c, to.x), y1 = py(c, to.y);
    double dx = x1 - x0, dy = y1 - y0, len = sqrt(dx * dx + dy * dy);
    fprintf(c->file,
            "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"%s\" stroke-width=\"1.5\"/>\n",
            x0, y0, x1, y1, stroke);
    if (len > 1e-9) {
        double ux = dx / len, uy = dy / len, h = 8.0;
        fprintf(c->file, "<polygon fill=\"%s\" points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\"/>\n", stroke, x1, y1,
                x1 - h * ux + 0.5 * h * uy, y1 - h * uy - 0.5 * h * ux, x1 - h * ux - 0.5 * h * uy,
                y1 - h * uy + 0.5 * h * ux);
    }
}

void svg_text(svg_canvas* c, rugo_vec2 at, const char* text, double size_px) {
    fprintf(c->file, "<text x=\"%.2f\" y=\"%.2f\" font-family=\"sans-serif\" font-size=\"%.1f\">%s</text>\n",
            px(c, at.x), py(c, at.y), size_px, text);
}

void svg_contour_extent(rugo_contour k, rugo_vec2* lo, rugo_vec2* hi) {
    rugo_vec2 a, b;
    rugo_contour_bounds(k, &a, &b);
    for (int j = 0; j < k.count; ++j) {
        a.x = fmin(a.x, k.points[j].x);
        a.y = fmin(a.y, k.points[j].y);
        b.x = fmax(b.x, k.points[j].x);
        b.y = fmax(b.y, k.points[j].y);
    }
    *lo = a;
    *hi = b;
}
