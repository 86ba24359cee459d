/* A minimal SVG writer for the samples and the rugo tool: world coordinates (y up) mapped into a
 * fixed-size picture. Not part of the library. */
#ifndef RUGO_SAMPLES_SVG_H
#define RUGO_SAMPLES_SVG_H

#include "rugo/rugo.h"

#include <stdio.h>

typedef struct svg_canvas {
    FILE* file;
    double scale, ox, oy; /* picture = (world - o) * scale, y flipped */
    double height;
} svg_canvas;

/* Opens path and writes the header for a picture of the world box [lo, hi] (with a margin).
 * Returns 0 on success, -1 if the file cannot be opened. */
int svg_open(svg_canvas* c, const char* path, rugo_vec2 lo, rugo_vec2 hi, double width_px);
/* Closes the picture; returns 0 if everything was written. */
int svg_close(svg_canvas* c);

/* The curve, tessellated with `per_segment` points per segment. */
void svg_contour(svg_canvas* c, rugo_contour k, int per_segment, const char* stroke, double width,
                 const char* dash);
/* The closed control polygon and its vertices. */
void svg_control_polygon(svg_canvas* c, rugo_contour k, const char* stroke);
void svg_point(svg_canvas* c, rugo_vec2 p, double radius_px, const char* fill);
void svg_arrow(svg_canvas* c, rugo_vec2 from, rugo_vec2 to, const char* stroke);
void svg_text(svg_canvas* c, rugo_vec2 at, const char* text, double size_px);

/* Bounds of a contour's curve and control points together. */
void svg_contour_extent(rugo_contour k, rugo_vec2* lo, rugo_vec2* hi);

#endif
