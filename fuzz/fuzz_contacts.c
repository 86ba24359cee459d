/* libFuzzer target: contact queries on random shapes and poses decoded from the input. Shapes are
 * star-shaped outlines (radius and angle jitter per control point, so most decode to valid shapes),
 * at scales from 1e-4 to 1e4 and offsets up to 1e5 from the origin, with random tolerances; queries
 * at random levels, margins and tolerance overrides, against each other and primitives. Properties:
 * no NaN or infinity in any output of a query on finite input, counts within capacity, a state
 * consistent with the count, and A/B symmetry of the state. */
#include "fuzz_common.h"

#include <stdint.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

typedef struct bytes {
    const uint8_t* p;
    size_t n;
} bytes;

static unsigned next(bytes* b) {
    if (b->n == 0) return 0;
    --b->n;
    return *b->p++;
}
/* A value in [0, 1] from two bytes. */
static double unit(bytes* b) {
    const unsigned v = next(b) | (next(b) << 8);
    return (double)v / 65535.0;
}

static const double SCALES[4] = {1e-4, 1.0, 37.5, 1e4};
static const double OFFSETS[4] = {0.0, 3.0, -250.0, 1e5};

static rugo_shape* make_shape(bytes* b, double scale, double offset) {
    const unsigned head = next(b);
    const int count = 4 << (head % 5); /* 4..64 */
    rugo_vec2 pts[64];
    rugo_real lam[64];
    const double lam_scale = (head >> 3) % 4 == 0 ? 0.0 : 0.05 * scale;
    for (int i = 0; i < count; ++i) {
        const double r = scale * (0.3 + unit(b));
        const double a = 6.283185307179586 * ((double)i + 0.9 * (unit(b) - 0.5)) / (double)count;
        pts[i] = rugo_v2(offset + r * cos(a), offset + r * sin(a));
        lam[i] = lam_scale * (double)next(b) / 255.0;
    }
    rugo_shape_def def = rugo_default_shape_def();
    def.points = pts;
    def.count = count;
    def.tolerances = lam;
    def.filter = (rugo_filter)((head >> 5) % RUGO_FILTER_COUNT);
    def.box_method = (head & 0x80) ? RUGO_BOXES_OF_BOXES : RUGO_BOXES_MULTIRES;
    def.estimator = (head & 0x40) ? RUGO_ESTIMATOR_COEFFICIENTS : RUGO_ESTIMATOR_DETAIL;
    rugo_shape* s = NULL;
    if (rugo_shape_create(&def, &s, NULL) != RUGO_OK) return NULL;
    return s;
}

static rugo_transform pose(bytes* b, double scale) {
    return rugo_make_transform(scale * 4.0 * (unit(b) - 0.5), scale * 4.0 * (unit(b) - 0.5), 6.3 * unit(b));
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    bytes b;
    b.p = data;
    b.n = size;
    const unsigned mode = next(&b);
    const double scale = SCALES[mode % 4], offset = OFFSETS[(mode >> 2) % 4];
    rugo_shape* A = make_shape(&b, scale, offset);
    rugo_shape* B = make_shape(&b, scale, offset);
    if (A == NULL || B == NULL) {
        rugo_shape_destroy(A);
        rugo_shape_destroy(B);
        return 0;
    }
    rugo_collide_context* ctx = NULL;
    FUZZ_CHECK(rugo_collide_context_create(NULL, &ctx) == RUGO_OK);
    rugo_contact c[32];
    for (int round = 0; round < 4 && b.n > 0; ++round) {
        const rugo_transform xa = pose(&b, scale), xb = pose(&b, scale);
        rugo_contact_query q = rugo_default_contact_query();
        const unsigned opt = next(&b);
        /* levels of detail 0 .. -4, and the automatic one with a budget of up to 5 % of the scale */
        q.lod = opt % 8 == 7 ? RUGO_LOD_AUTO : -(int)(opt % 8) % 5;
        if (q.lod == RUGO_LOD_AUTO) q.lod_error_budget = scale * 0.05 * unit(&b);
        if (opt & 0x10) q.margin = scale * 0.2 * unit(&b);
        if (opt & 0x20) q.tolerance = scale * 0.1 * unit(&b);
        q.friction_mix = (rugo_mix_rule)((opt >> 6) % 4);
        rugo_contact_output o = rugo_contact_output_of(c, 32);
        rugo_status st = rugo_collide_shapes(A, xa, B, xb, &q, ctx, &o);
        FUZZ_CHECK(st == RUGO_OK);
        fuzz_check_contacts(st, c, o.count, 32, o.state);
        const rugo_contact_state state = o.state;
        st = rugo_collide_shapes(B, xb, A, xa, &q, ctx, &o);
        FUZZ_CHECK(st == RUGO_OK);
        fuzz_check_contacts(st, c, o.count, 32, o.state);
        if (q.margin == 0.0) FUZZ_CHECK(state == o.state); /* what touches does not depend on the order */
        const rugo_vec2 centre =
            rugo_v2(offset + scale * 2.0 * (unit(&b) - 0.5), offset + scale * 2.0 * (unit(&b) - 0.5));
        const double r = scale * unit(&b);
        const rugo_transform id = rugo_identity_transform();
        const rugo_primitive circle = rugo_make_circle(centre, r);
        st = rugo_collide_primitive(A, xa, &circle, id, &q, ctx, &o);
        fuzz_check_contacts(st, c, o.count, 32, o.state);
        const rugo_primitive capsule = rugo_make_capsule(
            centre, rugo_v2(centre.x + scale * unit(&b), centre.y - scale * unit(&b)), 0.1 * r);
        st = rugo_collide_primitive(A, xa, &capsule, id, &q, ctx, &o);
        fuzz_check_contacts(st, c, o.count, 32, o.state);
        const rugo_vec2 tri[3] = {centre, rugo_v2(centre.x + r + scale * 1e-3, centre.y),
                                  rugo_v2(centre.x, centre.y + r + scale * 1e-3)};
        rugo_primitive triangle;
        st = rugo_make_polygon(tri, 3, 0.0, &triangle);
        if (st == RUGO_OK) {
            st = rugo_collide_primitive(A, xa, &triangle, id, &q, ctx, &o);
            fuzz_check_contacts(st, c, o.count, 32, o.state);
        }
    }
    rugo_collide_context_destroy(ctx);
    rugo_shape_destroy(A);
    rugo_shape_destroy(B);
    return 0;
}
