/* What a query takes and gives: the query's defaults and checks, and its contacts — each filled in from
 * a pair in A's frame (world points and normal, the surfaces' tolerance, friction and restitution at
 * the points, a stable id), ordered by region and depth, truncated to the caller's room. Separate
 * because every kind of query reports through it. */
#include "query/collide_internal.h"

#include <stdlib.h>
#include <string.h>

/* "RUGQ": catches queries that did not come from rugo_default_contact_query. */
#define QUERY_COOKIE 0x52554751

rugo_contact_query rugo_default_contact_query(void) {
    rugo_contact_query q;
    memset(&q, 0, sizeof q);
    q.resolution = RUGO_RESOLUTION_AUTO;
    q.lod = 0;
    q.lod_error_budget = 0.0;
    q.tolerance = -1.0;
    q.friction_mix = RUGO_MIX_MAX;
    q.restitution_mix = RUGO_MIX_MIN;
    q.cookie = QUERY_COOKIE;
    return q;
}

const char* rugo_contact_state_name(rugo_contact_state s) {
    switch (s) {
    case RUGO_STATE_APART:
        return "apart";
    case RUGO_STATE_CONTACT:
        return "contact";
    case RUGO_STATE_INTERSECTING:
        return "intersecting";
    default:
        return "unknown";
    }
}

rugo_contact_output rugo_contact_output_of(rugo_contact* contacts, int capacity) {
    rugo_contact_output o;
    memset(&o, 0, sizeof o);
    o.contacts = contacts;
    o.capacity = capacity;
    return o;
}

rugo_status rugo__check_query(const rugo_contact_query* q, const rugo_contact_output* out) {
    if (q->cookie != QUERY_COOKIE) return RUGO_ERR_BAD_ARGUMENT;
    if (out->capacity < 0) return RUGO_ERR_BAD_ARGUMENT;
    if (out->capacity > 0 && out->contacts == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (!isfinite(q->tolerance) || !isfinite(q->margin) || !isfinite(q->lod_error_budget) ||
        !isfinite(q->resolution))
        return RUGO_ERR_NOT_FINITE;
    if (q->resolution < 0.0 && q->resolution != RUGO_RESOLUTION_AUTO) return RUGO_ERR_BAD_ARGUMENT;
    if ((unsigned)q->contact_rule > (unsigned)RUGO_CONTACT_THESIS) return RUGO_ERR_BAD_ARGUMENT;
    if (q->margin < 0.0 || q->lod_error_budget < 0.0) return RUGO_ERR_BAD_ARGUMENT;
    if (q->lod > 0 && q->lod != RUGO_LOD_AUTO) return RUGO_ERR_BAD_ARGUMENT;
    if ((unsigned)q->friction_mix > (unsigned)RUGO_MIX_GEOMETRIC ||
        (unsigned)q->restitution_mix > (unsigned)RUGO_MIX_GEOMETRIC)
        return RUGO_ERR_BAD_ARGUMENT;
    return RUGO_OK;
}

/* A contact's id from what identifies it across steps: the two levels (5 bits each), the two segments
 * (20 bits each), the type of contact (2 bits: minimum, region, containment) and its index there (12
 * bits). */
static uint64_t contact_id(int level_a, int level_b, int seg_a, int seg_b, int type, int index) {
    return ((uint64_t)(level_a & 31) << 59) | ((uint64_t)(level_b & 31) << 54) |
           ((uint64_t)(seg_a & 0xFFFFF) << 34) | ((uint64_t)(seg_b & 0xFFFFF) << 14) |
           ((uint64_t)(type & 3) << 12) | (uint64_t)(index & 0xFFF);
}

/* Adds a contact from a pair in A's frame: n unit from A to B. id_b: B's segment, or the primitive's
 * feature, for the id. */
int rugo__emit_contact(contact_out* o, int sa, rugo_real ta, int sb, rugo_real tb, rugo_vec2 pa, rugo_vec2 pb,
                       rugo_vec2 n, int region, int type, int index, int id_b) {
    if (!rugo__scratch_reserve(o->ctx, &o->ctx->out, o->n + 1, sizeof(rugo_contact))) return 0;
    rugo_contact* c = (rugo_contact*)o->ctx->out.data + o->n++;
    memset(c, 0, sizeof *c);
    c->point_a = rugo_transform_point(o->xa, pa);
    c->point_b = rugo_transform_point(o->xa, pb);
    c->normal = rugo_rotate(o->xa.q, n);
    c->separation = rugo_v2_dot(rugo_v2_sub(pb, pa), n);
    c->segment_a = sa;
    c->t_a = ta;
    c->level_a = o->A->level;
    c->tolerance_a = rugo__query_side_tolerance(o->A, sa, ta, o->override);
    rugo_friction_map fa = rugo_shape_friction_map(o->A->shape);
    rugo_restitution ra = rugo_shape_restitution(o->A->shape);
    const rugo_real mu_a = rugo_friction(&fa, c->tolerance_a);
    if (o->B != NULL) {
        c->segment_b = sb;
        c->t_b = tb;
        c->level_b = o->B->level;
        c->tolerance_b = rugo__query_side_tolerance(o->B, sb, tb, o->override);
        rugo_friction_map fb = rugo_shape_friction_map(o->B->shape);
        rugo_restitution rb = rugo_shape_restitution(o->B->shape);
        c->friction = rugo_mix(o->q->friction_mix, mu_a, rugo_friction(&fb, c->tolerance_b));
        c->restitution = rugo_mix(o->q->restitution_mix, ra.epsilon, rb.epsilon);
    } else {
        /* A primitive has no surface of its own: the shape's values, for the caller to mix. */
        c->segment_b = -1;
        c->t_b = 0.0;
        c->level_b = 0;
        c->tolerance_b = o->override >= 0.0 ? o->override : 0.0;
        c->friction = mu_a;
        c->restitution = ra.epsilon;
    }
    c->region = region;
    c->id = contact_id(c->level_a, c->level_b, sa, id_b, type, index);
    return 1;
}

static int contact_cmp(const void* pa, const void* pb) {
    const rugo_contact* a = (const rugo_contact*)pa;
    const rugo_contact* b = (const rugo_contact*)pb;
    if (a->region != b->region) return a->region < b->region ? -1 : 1;
    if (a->separation != b->separation) return a->separation < b->separation ? -1 : 1;
    if (a->id != b->id) return a->id < b->id ? -1 : 1;
    return 0;
}

void rugo__finish_contacts(contact_out* o, rugo_contact* contacts, int capacity, int* count,
                           rugo_query_stats* stats) {
    rugo_contact* all = (rugo_contact*)o->ctx->out.data;
    if (o->n > 1) qsort(all, o->n, sizeof(rugo_contact), contact_cmp);
    size_t w = o->n < (size_t)capacity ? o->n : (size_t)capacity;
    for (size_t i = 0; i < w; ++i)
        contacts[i] = all[i];
    *count = (int)w;
    if (stats != NULL) stats->contacts_found = o->n > (size_t)INT32_MAX ? INT32_MAX : (int)o->n;
}
