/* The scratch context of the contact queries: buffers that grow to the largest query a context has
 * run and are then reused, so that queries allocate nothing once the context has grown (or has been
 * reserved for the shapes it will see). Separate from the queries because it outlives them. */
#include "query/collide_internal.h"

#include <string.h>

rugo_status rugo_collide_context_create(const rugo_allocator* allocator, rugo_collide_context** out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    *out = NULL;
    rugo_allocator al = rugo__allocator_or_default(allocator);
    rugo_collide_context* c = (rugo_collide_context*)rugo__alloc_array(&al, 1, sizeof(rugo_collide_context));
    if (c == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    memset(c, 0, sizeof *c);
    c->al = al;
    *out = c;
    return RUGO_OK;
}

void rugo_collide_context_destroy(rugo_collide_context* c) {
    if (c == NULL) return;
    rugo__array* all[] = {&c->stack, &c->box_pool, &c->pairs, &c->xs,  &c->ss,   &c->ss2,
                          &c->ints,  &c->marks,    &c->segs,  &c->out, &c->ptab, &c->pstamp};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; ++i)
        rugo__array_free(all[i], &c->al);
    rugo_allocator al = c->al;
    rugo__free(&al, c);
}

/* Room for the queries between two shapes the size of s (the same coarsest and finest levels, or smaller)
 * with up to `contacts` contacts. The traversal's stack holds at most the root's children (2^j0 x 2^j0)
 * plus 3 per level descended on either side (each later expansion pops one node and pushes at most 2 x 2),
 * and its box pool 2 + 2 x 2^j0 boxes plus 4 per level on either side (see rugo__traverse); the
 * per-segment tables take both shapes' segments. What grows with the contacts is sized from what the
 * benchmarks measure per contact (about 25 segment pairs near one contact at the finest level, a few hits
 * each), with room to spare, and the pair list holds every segment pair when there are at most 2^18; a
 * query beyond that (shapes over 512 segments deeply overlapping) still grows. */
rugo_status rugo_collide_context_reserve(rugo_collide_context* ctx, const rugo_shape* s, int contacts) {
    if (ctx == NULL || s == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (contacts < 0 || contacts > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_BAD_ARGUMENT;
    const rugo_mobb_tree* t = rugo_shape_tree(s);
    if (t == NULL) return RUGO_ERR_NULL_ARGUMENT;
    const int j0 = rugo_mobb_tree_coarsest_level(t), levels = rugo_mobb_tree_finest_level(t) - j0 + 1;
    const size_t fan = (size_t)1 << j0, seg = (size_t)2 << rugo_mobb_tree_finest_level(t); /* both shapes */
    const size_t c = contacts > 0 ? (size_t)contacts : 1;
    /* every segment pair of two such shapes, when that is at most 2^18 (2 MB; shapes up to 512
     * segments): deeply overlapping shapes, and falling ones whose speculative margins grow the boxes by
     * centimetres (65 537 pairs seen between two 512-segment bodies in benchmark 3), then fit too */
    const size_t half = seg / 2, all_pairs = half <= 512 ? half * half : (size_t)1 << 18;
    const size_t pairs = all_pairs > 64 * c ? all_pairs : 64 * c;
    const size_t marks = seg > (4 * c + 2) * sizeof(rugo_real) ? seg : (4 * c + 2) * sizeof(rugo_real);
    const int ok =
        rugo__scratch_reserve(ctx, &ctx->stack, fan * fan + 6 * (size_t)levels + 1, sizeof(traversal_node)) &&
        rugo__scratch_reserve(ctx, &ctx->box_pool, 2 + 2 * fan + 8 * (size_t)levels, sizeof(tested_box)) &&
        rugo__scratch_reserve(ctx, &ctx->pairs, pairs, sizeof(rugo_node_pair)) &&
        rugo__scratch_reserve(ctx, &ctx->xs, 4 * c, sizeof(hit)) &&
        rugo__scratch_reserve(ctx, &ctx->ss, 8 * c, sizeof(hit)) &&
        rugo__scratch_reserve(ctx, &ctx->ss2, 8 * c, sizeof(hit)) &&
        rugo__scratch_reserve(ctx, &ctx->ints, 24 * c, sizeof(int)) &&
        rugo__scratch_reserve(ctx, &ctx->marks, marks, 1) &&
        rugo__scratch_reserve(ctx, &ctx->segs, seg, sizeof(seginfo)) &&
        rugo__scratch_reserve(ctx, &ctx->out, 4 * c, sizeof(rugo_contact)) &&
        rugo__scratch_reserve(ctx, &ctx->ptab, seg, sizeof(rugo_vec2[4])) &&
        rugo__scratch_reserve(ctx, &ctx->pstamp, seg, sizeof(uint32_t));
    return ok ? RUGO_OK : RUGO_ERR_OUT_OF_MEMORY;
}
