/* Manifold reduction: at most k contacts per region, the deepest first and then, one at a time, the
 * contact farthest from those kept, so that a solver gets a patch's extent from few points. Separate
 * because it works on a query's output, after the query. */
#include "query/collide_internal.h"

int rugo_reduce_manifold(rugo_contact* contacts, int count, int k) {
    if (contacts == NULL || count <= 0) return 0;
    if (k < 1) k = 1;
    /* Kept contacts are marked in place by region -> -1 - region (undone at the end), so that nothing
     * is allocated; this needs the non-negative regions the queries produce. */
    for (int i = 0; i < count; ++i)
        if (contacts[i].region < 0) return count;
    for (int s = 0; s < count; ++s) {
        const int region = contacts[s].region;
        if (region < 0) continue; /* a kept contact of a region already done */
        int first = 1;
        for (int p = 0; p < s && first; ++p)
            first = contacts[p].region != region && contacts[p].region != -1 - region;
        if (!first) continue;
        int members = 0, deepest = s;
        for (int i = s; i < count; ++i)
            if (contacts[i].region == region) {
                ++members;
                if (contacts[i].separation < contacts[deepest].separation) deepest = i;
            }
        if (members <= k) {
            for (int i = s; i < count; ++i)
                if (contacts[i].region == region) contacts[i].region = -1 - region;
            continue;
        }
        contacts[deepest].region = -1 - region;
        for (int kept = 1; kept < k; ++kept) {
            int pick = -1;
            rugo_real best = -1.0;
            for (int i = s; i < count; ++i) {
                if (contacts[i].region != region) continue;
                const rugo_vec2 ci = rugo__lerp2(contacts[i].point_a, contacts[i].point_b, 0.5);
                rugo_real dmin = HUGE_VAL;
                for (int j = s; j < count; ++j)
                    if (contacts[j].region == -1 - region) {
                        const rugo_vec2 cj = rugo__lerp2(contacts[j].point_a, contacts[j].point_b, 0.5);
                        dmin = fmin(dmin, rugo__v2_length(rugo_v2_sub(ci, cj)));
                    }
                if (dmin > best) {
                    best = dmin;
                    pick = i;
                }
            }
            if (pick < 0) break;
            contacts[pick].region = -1 - region;
        }
    }
    int w = 0;
    for (int i = 0; i < count; ++i)
        if (contacts[i].region < 0) {
            contacts[w] = contacts[i];
            contacts[w].region = -1 - contacts[w].region;
            ++w;
        }
    return w;
}
