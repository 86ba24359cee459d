/* The Bezier pieces of a shape-against-shape query: A's in its own frame, B's moved into A's, each
 * computed at most once per query (a table indexed by segment, invalidated by an epoch instead of
 * cleared) or, without a table, kept in a small cache for the run of pairs that share them. Separate
 * because every narrow pass of the query asks for pieces, in different orders. */
#include "query/collide_internal.h"

#include <string.h>

void rugo__piece_of_b(const shape_pair* g, int k, rugo_vec2 out[4]) {
    rugo_vec2 q[4];
    rugo_contour_bezier(g->B->curve, k, q);
    for (int i = 0; i < 4; ++i)
        out[i] = rugo_transform_point(g->rel, q[i]);
}

void rugo__piece_cache_init(piece_cache* pc) {
    pc->ka = -1;
    for (int i = 0; i < PIECE_CACHE; ++i)
        pc->kb[i] = -1;
}

/* Pieces from the query's table (g->tab set: rugo__piece_table_setup). */
const rugo_vec2* rugo__table_piece_a(const shape_pair* g, int k) {
    if (g->stamp[k] != g->epoch) {
        rugo_contour_bezier(g->A->curve, k, g->tab[k]);
        g->stamp[k] = g->epoch;
    }
    return g->tab[k];
}

const rugo_vec2* rugo__table_piece_b(const shape_pair* g, int k) {
    const size_t e = (size_t)g->A->n + (size_t)k;
    if (g->stamp[e] != g->epoch) {
        rugo__piece_of_b(g, k, g->tab[e]);
        g->stamp[e] = g->epoch;
    }
    return g->tab[e];
}

const rugo_vec2* rugo__cached_piece_a(piece_cache* pc, const shape_pair* g, int k) {
    if (g->tab != NULL) return rugo__table_piece_a(g, k);
    if (pc->ka != k) {
        rugo_contour_bezier(g->A->curve, k, pc->fa);
        pc->ka = k;
    }
    return pc->fa;
}

const rugo_vec2* rugo__cached_piece_b(piece_cache* pc, const shape_pair* g, int k) {
    if (g->tab != NULL) return rugo__table_piece_b(g, k);
    const int slot = k & (PIECE_CACHE - 1);
    if (pc->kb[slot] != k) {
        rugo__piece_of_b(g, k, pc->gb[slot]);
        pc->kb[slot] = k;
    }
    return pc->gb[slot];
}

/* Sets up g's piece table in ctx for the query (A->n + B->n entries); 0 if out of memory. A new epoch
 * invalidates every entry without clearing; stamps are zeroed once when first allocated, and all of
 * them when the epoch wraps. */
int rugo__piece_table_setup(rugo_collide_context* ctx, shape_pair* g) {
    const size_t n = (size_t)g->A->n + (size_t)g->B->n;
    if (!rugo__scratch_reserve(ctx, &ctx->ptab, n, sizeof(rugo_vec2[4])) ||
        !rugo__scratch_reserve(ctx, &ctx->pstamp, n, sizeof(uint32_t)))
        return 0;
    uint32_t* stamp = (uint32_t*)ctx->pstamp.data;
    if (ctx->pstamp_zeroed < n) {
        memset(stamp + ctx->pstamp_zeroed, 0, (n - ctx->pstamp_zeroed) * sizeof(uint32_t));
        ctx->pstamp_zeroed = n;
    }
    if (++ctx->epoch == 0) {
        memset(stamp, 0, ctx->pstamp_zeroed * sizeof(uint32_t));
        ctx->epoch = 1;
    }
    g->tab = (rugo_vec2(*)[4])ctx->ptab.data;
    g->stamp = stamp;
    g->epoch = ctx->epoch;
    return 1;
}
