/* `rugo contacts`: the contact points between two placed shapes at a level of detail. */
#include "cli.h"

#include <stdlib.h>
#include <string.h>

static void print_vec(const char* name, rugo_vec2 v) { printf("\"%s\": [%.17g, %.17g]", name, v.x, v.y); }

int cmd_contacts(int argc, char** argv) {
    static const char* const vals[] = {"--pose-a",       "--pose-b",    "--lod", "--level",
                                       "--error-budget", "--tolerance", NULL};
    args a;
    int rc = parse_args(argc, argv, vals, NULL, &a);
    if (rc) return rc;
    if (a.positional_count != 2) return usage_error("expects two shape files A.json B.json%s", "");
    /* --level is the older name of --lod */
    const char *pa = opt(&a, "--pose-a", NULL), *pb = opt(&a, "--pose-b", NULL), *lv = opt(&a, "--lod", NULL),
               *bv = opt(&a, "--error-budget", NULL), *tv = opt(&a, "--tolerance", NULL);
    if (lv == NULL) lv = opt(&a, "--level", NULL);
    rugo_transform xa = rugo_identity_transform(), xb = rugo_identity_transform();
    if (pa && parse_pose(pa, &xa) != 0) return usage_error("--pose-a must be X,Y,THETA, got '%s'", pa);
    if (pb && parse_pose(pb, &xb) != 0) return usage_error("--pose-b must be X,Y,THETA, got '%s'", pb);
    rugo_contact_query q = rugo_default_contact_query();
    if (lv && strcmp(lv, "auto") == 0)
        q.lod = RUGO_LOD_AUTO;
    else if (lv && parse_int(lv, -30, 0, &q.lod) != 0)
        return usage_error("--lod must be 0 (the finest level), -1, -2, ... (coarser) or auto, got '%s'", lv);
    if (bv && (parse_real(bv, &q.lod_error_budget) != 0 || !(q.lod_error_budget >= 0.0)))
        return usage_error("--error-budget must be a length >= 0 (with --lod auto), got '%s'", bv);
    if (tv && (parse_real(tv, &q.tolerance) != 0 || q.tolerance < 0.0))
        return usage_error("--tolerance must be a number >= 0, got '%s'", tv);
    rugo_shape_desc da, db;
    rugo_shape *sa = NULL, *sb = NULL;
    if ((rc = load_shape_any(a.positional[0], &da, &sa))) return rc;
    if ((rc = load_shape_any(a.positional[1], &db, &sb))) {
        rugo_shape_destroy(sa);
        rugo_shape_desc_free(&da);
        return rc;
    }
    rugo_collide_context* ctx = NULL;
    rugo_contact* contacts = NULL;
    /* A baked shape is used as stored (bit-identical to the shape that was baked). */
    if ((sa == NULL && (rc = make_shape(a.positional[0], &da, &sa))) ||
        (sb == NULL && (rc = make_shape(a.positional[1], &db, &sb))))
        goto done;
    rugo_status st = rugo_collide_context_create(NULL, &ctx);
    int capacity = 64, count = 0;
    rugo_contact_state state = RUGO_STATE_APART;
    rugo_query_stats stats;
    for (int attempt = 0; st == RUGO_OK && attempt < 2; ++attempt) {
        free(contacts);
        contacts = malloc(sizeof *contacts * (size_t)capacity);
        if (contacts == NULL) {
            st = RUGO_ERR_OUT_OF_MEMORY;
            break;
        }
        rugo_contact_output out = rugo_contact_output_of(contacts, capacity);
        st = rugo_collide_shapes(sa, xa, sb, xb, &q, ctx, &out);
        count = out.count;
        state = out.state;
        stats = out.stats;
        if (st != RUGO_OK || stats.contacts_found <= capacity) break;
        capacity = stats.contacts_found; /* every contact, not a truncated list */
    }
    if (st != RUGO_OK) {
        rc = fail("contacts", st);
        goto done;
    }
    printf("{\"state\": \"%s\", \"contacts\": [", rugo_contact_state_name(state));
    for (int i = 0; i < count; ++i) {
        const rugo_contact* c = &contacts[i];
        printf("%s\n  {", i ? "," : "");
        print_vec("point_a", c->point_a);
        printf(", ");
        print_vec("point_b", c->point_b);
        printf(", ");
        print_vec("normal", c->normal);
        printf(
            ", \"separation\": %.17g, \"segment_a\": %d, \"segment_b\": %d, \"t_a\": %.17g, \"t_b\": %.17g, "
            "\"tolerance\": %.17g, \"friction\": %.17g, \"tolerance_a\": %.17g, \"tolerance_b\": %.17g, "
            "\"restitution\": %.17g, \"level_a\": %d, \"level_b\": %d, \"region\": %d, \"id\": \"%016llx\"}",
            c->separation, c->segment_a, c->segment_b, c->t_a, c->t_b, c->tolerance_a + c->tolerance_b,
            c->friction, c->tolerance_a, c->tolerance_b, c->restitution, c->level_a, c->level_b, c->region,
            (unsigned long long)c->id);
    }
    printf("%s], \"stats\": {\"box_tests\": %ld, \"segment_pairs\": %ld, \"newton_iterations\": %ld, "
           "\"fallbacks\": %ld}, \"reversed_a\": %s, \"reversed_b\": %s}\n",
           count ? "\n" : "", stats.box_tests, stats.segment_pairs, stats.newton_iterations, stats.fallbacks,
           rugo_shape_was_reversed(sa) ? "true" : "false", rugo_shape_was_reversed(sb) ? "true" : "false");
done:
    free(contacts);
    rugo_collide_context_destroy(ctx);
    rugo_shape_destroy(sa);
    rugo_shape_destroy(sb);
    rugo_shape_desc_free(&da);
    rugo_shape_desc_free(&db);
    return rc;
}
