// A query's contacts into contact patches, each of which becomes one b2Contact: one normal and at most
// two points, at the ends of the patch as Box2D clips a face (its block solver then holds stacks).
//
//  - A region of librugo's (its contacts share `region`) is a patch; regions whose normals agree
//    within ~10 degrees (kMergeCos) join the deepest one: a face resting on several bumps, a body
//    standing on two feet.
//  - A contact on a straight face of each side (bridge_shape.cpp's faces; a polygon's or an edge's side)
//    adds the two ends of the stretch the faces share: a flat face on a flat face has one distance
//    minimum when tilted, and on one point a box rocks. When librugo reports a conforming stretch as a
//    region with its two ends, those are among the region's contacts already and this adds nothing new.
//  - The manifold's points: the two extremes, along the patch's tangent, of its touching points (a
//    face resting on bumps rests on its outermost ones), or else of the points level with the deepest
//    (within half a linear slop: a face landing flat); when those are closer together than a slop, the
//    deepest point and the farthest point of the patch (apart, if it is: Evaluate keeps it only if it
//    closes within the step).
//  - A patch belongs to the proxy pair whose pieces hold the segments of its deepest point, or of
//    another of its points if that pair has a deeper patch already (a b2Contact has one normal); with
//    none free it is left unowned, for the caller to give to a free proxy contact of the body pair.
#include "bridge_impl.hpp"

#include <algorithm>
#include <cmath>

namespace rugo {
namespace detail {

namespace {

struct Cand {
    PatchPoint p;
    rugo_vec2 n; // the normal of the region the point comes from
    double u;    // along the patch's tangent
    int ownerA, ownerB;
};

// A side's straight face through a contact point: the polyline of its joints in world coordinates is
// queried through this.
struct FaceView {
    bool on = false;
    // Rough: the face and the level's tolerances, pose; primitive: a segment (v0, v1), its outward
    // normal and radius.
    const Face* face = nullptr;
    int faceIndex = -1;
    int levelCount = 0;
    rugo_tolerance_level tl;
    rugo_transform x;
    b2Vec2 v0, v1, normal;
    float radius = 0.0f;
    double lo = 0.0, hi = 0.0; // u-interval
};

rugo_vec2 lerp(rugo_vec2 a, rugo_vec2 b, double t) {
    return rugo_v2(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
}

// The rough side's face at (segment, level) if its direction lies along the tangent t.
bool roughFace(const PatchSide& s, int segment, int level, rugo_vec2 o, rugo_vec2 t, rugo_vec2 n,
               FaceView* f) {
    const ShapeData* d = s.data;
    if (d == nullptr || segment < 0) return false;
    const int idx = level - d->level;
    if (idx < 0 || idx >= static_cast<int>(d->faces.size())) return false;
    const LevelFaces& lf = d->faces[static_cast<size_t>(idx)];
    const int count = static_cast<int>(lf.faceOf.size());
    // The face holding the segment, or the nearest one within two segments: a slightly tilted face
    // touches at the start of its rounded end, just beyond the straight stretch.
    int fi = -1;
    rugo_vec2 a = rugo_v2(0, 0), b = rugo_v2(0, 0);
    for (int off = 0; off <= 4 && fi < 0; ++off) {
        const int seg = ((segment + (off % 2 == 1 ? (off + 1) / 2 : -(off / 2))) % count + count) % count;
        const int cand = lf.faceOf[static_cast<size_t>(seg)];
        if (cand < 0) continue;
        const Face& face = lf.faces[static_cast<size_t>(cand)];
        a = rugo_transform_point(s.x, face.joints.front());
        b = rugo_transform_point(s.x, face.joints.back());
        const rugo_vec2 dir = rugo_v2_sub(b, a);
        const double len = std::hypot(dir.x, dir.y);
        if (len > 0.0 && std::fabs(rugo_v2_dot(dir, n)) <= kFaceSin * len) fi = cand;
    }
    if (fi < 0) return false;
    const Face& face = lf.faces[static_cast<size_t>(fi)];
    if (rugo_shape_tolerance_level(d->shape, level, &f->tl) != RUGO_OK) return false;
    f->on = true;
    f->face = &face;
    f->faceIndex = fi;
    f->levelCount = count;
    f->x = s.x;
    const double ua = rugo_v2_dot(rugo_v2_sub(a, o), t), ub = rugo_v2_dot(rugo_v2_sub(b, o), t);
    f->lo = std::min(ua, ub);
    f->hi = std::max(ua, ub);
    return true;
}

// The primitive side's face: the polygon edge facing the other body (outward normal along `facing`),
// or the edge itself.
bool primitiveFace(const PatchSide& s, rugo_vec2 o, rugo_vec2 t, rugo_vec2 facing, FaceView* f) {
    const b2Vec2 fw = toB2(facing);
    if (s.type == b2Shape::e_polygon) {
        int best = -1;
        float bestDot = std::sqrt(1.0f - static_cast<float>(kFaceSin * kFaceSin));
        for (int i = 0; i < s.n; ++i) {
            const float dot = b2Dot(s.normals[i], fw);
            if (dot >= bestDot) {
                bestDot = dot;
                best = i;
            }
        }
        if (best < 0) return false;
        f->v0 = s.v[best];
        f->v1 = s.v[(best + 1) % s.n];
        f->normal = s.normals[best];
    } else if (s.type == b2Shape::e_edge || s.type == b2Shape::e_chain) {
        f->v0 = s.v[0];
        f->v1 = s.v[1];
        b2Vec2 d = f->v1 - f->v0;
        if (d.Normalize() <= 0.0f) return false;
        f->normal = b2Vec2(d.y, -d.x);
        if (b2Dot(f->normal, fw) < 0.0f) f->normal = -f->normal;
        if (b2Dot(f->normal, fw) < std::sqrt(1.0f - static_cast<float>(kFaceSin * kFaceSin))) return false;
    } else {
        return false;
    }
    f->on = true;
    f->radius = s.radius;
    const double ua = rugo_v2_dot(rugo_v2_sub(toRv(f->v0), o), t),
                 ub = rugo_v2_dot(rugo_v2_sub(toRv(f->v1), o), t);
    f->lo = std::min(ua, ub);
    f->hi = std::max(ua, ub);
    return true;
}

// The point of a face at tangent coordinate u (within its interval): on the curve (rough) or on the
// primitive's surface, with the band there (0 for a primitive), the segment and the parameter in it
// (rough; the face is straight, so the parameter is taken along the chord between its joints).
rugo_vec2 facePoint(const FaceView& f, rugo_vec2 o, rugo_vec2 t, double u, double* lambda, int* segment,
                    double* param) {
    *lambda = 0.0;
    *segment = -1;
    *param = 0.0;
    if (f.face != nullptr) {
        const std::vector<rugo_vec2>& j = f.face->joints;
        rugo_vec2 prev = rugo_transform_point(f.x, j[0]);
        double uPrev = rugo_v2_dot(rugo_v2_sub(prev, o), t);
        for (size_t i = 1; i < j.size(); ++i) {
            const rugo_vec2 cur = rugo_transform_point(f.x, j[i]);
            const double uCur = rugo_v2_dot(rugo_v2_sub(cur, o), t);
            const bool last = i + 1 == j.size();
            if ((u - uPrev) * (u - uCur) <= 0.0 || last) {
                const double du = uCur - uPrev;
                const double tau = du != 0.0 ? std::min(1.0, std::max(0.0, (u - uPrev) / du)) : 0.0;
                const int seg = (f.face->first + static_cast<int>(i) - 1) % f.levelCount;
                *segment = seg;
                *param = tau;
                *lambda = rugo_tolerance_at(f.tl.total, f.tl.count, seg, tau, 0.0);
                return lerp(prev, cur, tau);
            }
            prev = cur;
            uPrev = uCur;
        }
        return prev;
    }
    const rugo_vec2 a = toRv(f.v0), b = toRv(f.v1);
    const double ua = rugo_v2_dot(rugo_v2_sub(a, o), t), ub = rugo_v2_dot(rugo_v2_sub(b, o), t);
    const double tau = ub != ua ? std::min(1.0, std::max(0.0, (u - ua) / (ub - ua))) : 0.0;
    const rugo_vec2 q = lerp(a, b, tau);
    return rugo_v2_add(q, rugo_v2_scale(static_cast<double>(f.radius), toRv(f.normal)));
}

// The band-adjusted deepest point near a contact, on one rough side: librugo's contact is a minimum of
// the curves' distance, and where the band thickens beside it the band-adjusted separation is lower
// there (a ball rolling onto a thicker band climbs it). Samples `side`'s curve over a segment on each
// side of (segment, t) at the given level, eight per segment, against the other side's surface as the
// line through `other` along the tangent, bent away by its curvature otherKappa (> 0: convex there),
// with the band `otherBand` there. True with the deepest sample (curve point, foot on the other
// surface, band sum, separation, and the sample's own band, segment and t) if it lies below `than`.
struct SideSample {
    double lam = 0.0, t = 0.0;
    int segment = -1;
};
bool bandDeepest(const PatchSide& side, int segment, double t, int level, rugo_vec2 nOut, rugo_vec2 other,
                 double otherBand, double otherKappa, double than, rugo_vec2* pSide, rugo_vec2* pOther,
                 double* band, double* sep, SideSample* own) {
    const ShapeData* d = side.data;
    if (d == nullptr || segment < 0) return false;
    rugo_contour c;
    rugo_tolerance_level tl;
    if (rugo_shape_level(d->shape, level, &c) != RUGO_OK ||
        rugo_shape_tolerance_level(d->shape, level, &tl) != RUGO_OK)
        return false;
    bool found = false;
    const double base = static_cast<double>(segment) + t;
    const rugo_vec2 tan = rugo_v2_perp(nOut);
    for (int i = -8; i <= 8; ++i) {
        if (i == 0) continue;
        double u = base + i / 8.0;
        const double whole = std::floor(u);
        const int k = ((static_cast<int>(whole) % c.count) + c.count) % c.count;
        const double tt = u - whole;
        const rugo_vec2 x = rugo_transform_point(side.x, rugo_contour_point(c, k, tt));
        const double lam = rugo_tolerance_at(tl.total, tl.count, k, tt, 0.0);
        // nOut points from this side toward the other: the other surface lies at (other - x) . nOut,
        // plus how far it bends away at this distance along the tangent.
        const double along = rugo_v2_dot(rugo_v2_sub(x, other), tan);
        const double bend = 0.5 * otherKappa * along * along;
        const double s = rugo_v2_dot(rugo_v2_sub(other, x), nOut) + bend - lam - otherBand;
        if (s < than) {
            than = s;
            found = true;
            *pSide = x;
            *pOther = rugo_v2_add(x, rugo_v2_scale(rugo_v2_dot(rugo_v2_sub(other, x), nOut) + bend, nOut));
            *band = lam + otherBand;
            *sep = s;
            own->lam = lam;
            own->t = tt;
            own->segment = k;
        }
    }
    return found;
}

// The curvature of a side at a contact point, positive where it is convex (bends away from the other
// body): a rough side's curve at (segment, t); a circle's 1/r; 0 for polygons and edges.
double sideCurvature(const PatchSide& s, int segment, double t, int level) {
    if (s.data == nullptr)
        return s.type == b2Shape::e_circle && s.radius > 0.0f ? 1.0 / static_cast<double>(s.radius) : 0.0;
    rugo_contour c;
    if (segment < 0 || rugo_shape_level(s.data->shape, level, &c) != RUGO_OK) return 0.0;
    const rugo_vec2 d1 = rugo_contour_d1(c, segment, t), d2 = rugo_contour_d2(c, segment, t);
    const double sp = std::hypot(d1.x, d1.y);
    return sp > 0.0 ? (d1.x * d2.y - d1.y * d2.x) / (sp * sp * sp) : 0.0;
}

int ownerOf(const PatchSide& s, int segment, int level) {
    if (s.data == nullptr || segment < 0) return -1;
    return Bridge::Impl::pieceOf(s.data, segment, level);
}

} // namespace

int buildPatches(const QContact* c, int n, const PatchSide& A, const PatchSide& B, std::vector<Patch>* out,
                 std::vector<int>* work) {
    if (n <= 0) return 0;
    const bool primitive = B.data == nullptr;
    // Regions, each by its deepest contact, deepest first (ties by region index: determinism).
    std::vector<int>& deep = *work; // region representatives (contact indices)
    deep.clear();
    auto adj = [&](int i) { return c[i].seed ? 1e300 : c[i].sep - c[i].tolA - c[i].tolB; };
    for (int i = 0; i < n; ++i) {
        bool seen = false;
        for (int& d : deep)
            if (c[d].region == c[i].region) {
                if (adj(i) < adj(d)) d = i;
                seen = true;
                break;
            }
        if (!seen) deep.push_back(i);
    }
    std::sort(deep.begin(), deep.end(),
              [&](int a, int b) { return adj(a) != adj(b) ? adj(a) < adj(b) : c[a].region < c[b].region; });
    const size_t firstPatch = out->size();
    int dropped = 0;
    Cand cands[64];
    for (size_t r = 0; r < deep.size(); ++r) {
        if (deep[r] < 0) continue;
        const QContact& D = c[deep[r]];
        const rugo_vec2 nrm = D.n, t = rugo_v2_perp(nrm);
        const rugo_vec2 o = rugo_v2_scale(0.5, rugo_v2_add(D.pa, D.pb));
        int nc = 0;
        auto addContact = [&](const QContact& k) {
            if (nc >= 62 || k.seed) return; // two slots stay free for the face ends
            Cand& q = cands[nc++];
            q.p.pa = k.pa;
            q.p.pb = k.pb;
            q.p.band = k.tolA + k.tolB;
            q.p.s = rugo_v2_dot(rugo_v2_sub(k.pb, k.pa), nrm) - q.p.band;
            q.p.lamA = k.tolA;
            q.p.lamB = k.tolB;
            q.p.segA = k.segA;
            q.p.segB = k.segB;
            q.p.levelA = static_cast<int16_t>(k.levelA);
            q.p.levelB = static_cast<int16_t>(k.levelB);
            q.p.tA = static_cast<float>(k.tA);
            q.p.tB = static_cast<float>(k.tB);
            q.p.key = hashId(primitive ? k.id ^ (static_cast<uint64_t>(static_cast<uint32_t>(B.child)) << 40)
                                       : k.id);
            q.n = k.n;
            q.u = rugo_v2_dot(rugo_v2_sub(rugo_v2_scale(0.5, rugo_v2_add(k.pa, k.pb)), o), t);
            q.ownerA = ownerOf(A, k.segA, k.levelA);
            q.ownerB = ownerOf(B, k.segB, k.levelB);
        };
        // This region's contacts and those of every later region with nearly the same normal.
        for (size_t r2 = r; r2 < deep.size(); ++r2) {
            if (deep[r2] < 0) continue;
            const QContact& R = c[deep[r2]];
            if (r2 != r && rugo_v2_dot(R.n, nrm) < kMergeCos) continue;
            const int region = R.region;
            for (int i = 0; i < n; ++i)
                if (c[i].region == region) addContact(c[i]);
            if (r2 != r) deep[r2] = -1;
        }
        // The deepest contact's faces: the ends of the stretch both faces share.
        FaceView fa, fb;
        const bool faceA = roughFace(A, D.segA, D.levelA, o, t, nrm, &fa);
        const bool faceB = faceA && (primitive ? primitiveFace(B, o, t, rugo_v2_scale(-1.0, nrm), &fb)
                                               : roughFace(B, D.segB, D.levelB, o, t, nrm, &fb));
        if (faceA && faceB) {
            const double lo = std::max(fa.lo, fb.lo), hi = std::min(fa.hi, fb.hi);
            if (hi - lo >= static_cast<double>(b2_linearSlop)) {
                for (int end = 0; end < 2; ++end) {
                    const double u = end == 0 ? lo : hi;
                    double la = 0.0, lb = 0.0, ta = 0.0, tb = 0.0;
                    int sa = -1, sb = -1;
                    const rugo_vec2 qa = facePoint(fa, o, t, u, &la, &sa, &ta);
                    const rugo_vec2 qb = facePoint(fb, o, t, u, &lb, &sb, &tb);
                    Cand& q = cands[nc++];
                    q.p.pa = qa;
                    q.p.pb = qb;
                    q.p.band = la + lb;
                    q.p.s = rugo_v2_dot(rugo_v2_sub(qb, qa), nrm) - q.p.band;
                    q.p.lamA = la;
                    q.p.lamB = lb;
                    q.p.segA = sa;
                    q.p.segB = sb;
                    q.p.levelA = static_cast<int16_t>(D.levelA);
                    q.p.levelB = static_cast<int16_t>(D.levelB);
                    q.p.tA = static_cast<float>(ta);
                    q.p.tB = static_cast<float>(tb);
                    uint64_t h = mixHash(0xFACEull, static_cast<uint64_t>(fa.faceIndex));
                    h = mixHash(h, static_cast<uint64_t>(primitive ? 0x10000 + B.child : fb.faceIndex));
                    q.p.key = hashId(mixHash(h, static_cast<uint64_t>(end)));
                    q.u = u;
                    q.n = nrm;
                    q.ownerA = ownerOf(A, sa, D.levelA);
                    q.ownerB = primitive ? -1 : ownerOf(B, sb, D.levelB);
                }
            }
        }
        if (nc == 0) continue; // a seed whose face does not rest on this child
        // The band-adjusted deepest point beside the deepest contact, on each rough side (librugo's
        // contacts are minima of the curves' distance; the resolution-aware query reports minima of the
        // band-adjusted distance itself, and then this finds nothing deeper).
        if (!D.seed && nc < 63) {
            const double sD0 = D.sep - D.tolA - D.tolB;
            rugo_vec2 ps, po;
            double band = 0.0, sep = 0.0;
            int side = -1;
            SideSample own;
            Cand extra;
            const double deeper = sD0 - 1e-4;
            const double kB = sideCurvature(B, D.segB, D.tB, D.levelB),
                         kA = sideCurvature(A, D.segA, D.tA, D.levelA);
            if (bandDeepest(A, D.segA, D.tA, D.levelA, nrm, D.pb, D.tolB, kB, deeper, &ps, &po, &band, &sep,
                            &own)) {
                extra.p.pa = ps;
                extra.p.pb = po;
                extra.p.lamA = own.lam;
                extra.p.segA = own.segment;
                extra.p.tA = static_cast<float>(own.t);
                extra.p.lamB = D.tolB;
                extra.p.segB = D.segB;
                extra.p.tB = static_cast<float>(D.tB);
                extra.p.levelA = static_cast<int16_t>(D.levelA);
                extra.p.levelB = static_cast<int16_t>(D.levelB);
                side = 0;
            }
            if (bandDeepest(B, D.segB, D.tB, D.levelB, rugo_v2_scale(-1.0, nrm), D.pa, D.tolA, kA,
                            side >= 0 ? sep : deeper, &ps, &po, &band, &sep, &own)) {
                extra.p.pa = po;
                extra.p.pb = ps;
                extra.p.lamA = D.tolA;
                extra.p.segA = D.segA;
                extra.p.tA = static_cast<float>(D.tA);
                extra.p.lamB = own.lam;
                extra.p.segB = own.segment;
                extra.p.tB = static_cast<float>(own.t);
                extra.p.levelA = static_cast<int16_t>(D.levelA);
                extra.p.levelB = static_cast<int16_t>(D.levelB);
                side = 1;
            }
            if (side >= 0) {
                Cand& q = cands[nc++];
                q = extra;
                q.p.band = band;
                q.p.s = sep;
                q.p.key = hashId(mixHash(D.id, 0xBA4Dull + static_cast<uint64_t>(side)));
                q.n = nrm;
                q.u = rugo_v2_dot(rugo_v2_sub(rugo_v2_scale(0.5, rugo_v2_add(q.p.pa, q.p.pb)), o), t);
                q.ownerA = ownerOf(A, D.segA, D.levelA);
                q.ownerB = ownerOf(B, D.segB, D.levelB);
            }
        }
        // The manifold's points: the extremes of the touching points; failing two of those, of the
        // points level with the deepest (a face landing flat); failing those, the deepest point and
        // the farthest one.
        int iD = 0;
        for (int i = 1; i < nc; ++i)
            if (cands[i].p.s < cands[iD].p.s) iD = i;
        const double sD = cands[iD].p.s, slop = static_cast<double>(b2_linearSlop);
        int pick[2] = {iD, -1};
        for (int pass = 0; pass < 2 && pick[1] < 0; ++pass) {
            const double below = pass == 0 ? 0.0 : sD + 0.5 * slop;
            int lo = -1, hi = -1;
            for (int i = 0; i < nc; ++i) {
                if (cands[i].p.s > below) continue;
                if (lo < 0 || cands[i].u < cands[lo].u) lo = i;
                if (hi < 0 || cands[i].u > cands[hi].u) hi = i;
            }
            if (lo < 0 || cands[hi].u - cands[lo].u < slop) continue;
            if (iD != lo && iD != hi && sD < std::min(cands[lo].p.s, cands[hi].p.s) - slop) {
                // Much deeper inside than at the ends: keep the deepest, with the end farther from it.
                pick[1] =
                    std::fabs(cands[lo].u - cands[iD].u) > std::fabs(cands[hi].u - cands[iD].u) ? lo : hi;
            } else {
                pick[0] = lo;
                pick[1] = hi;
            }
        }
        if (pick[1] < 0) {
            double far = slop;
            for (int i = 0; i < nc; ++i) {
                const double d = std::fabs(cands[i].u - cands[iD].u);
                if (d > far) {
                    far = d;
                    pick[1] = i;
                }
            }
        }
        Patch p;
        p.n = nrm;
        p.count = pick[1] >= 0 ? 2 : 1;
        if (p.count == 2) {
            // Two points of regions with different normals (a face resting on two bumps): the mean of
            // their normals, not the deeper one's, so that the one normal leans neither way.
            const rugo_vec2 m = rugo_v2_add(cands[pick[0]].n, cands[pick[1]].n);
            const double len = std::hypot(m.x, m.y);
            if (len > 0.0) p.n = rugo_v2_scale(1.0 / len, m);
        }
        for (int k = 0; k < p.count; ++k) {
            p.p[k] = cands[pick[k]].p;
            p.p[k].s = rugo_v2_dot(rugo_v2_sub(p.p[k].pb, p.p[k].pa), p.n) - p.p[k].band;
            p.p[k].la = rugo_inv_transform_point(A.x, p.p[k].pa);
            p.p[k].lb = rugo_inv_transform_point(B.x, p.p[k].pb);
        }
        // The points' ids name the patch's ends, not where a point came from (a librugo contact, a
        // face's end, a band-deepest point): which of those is the extreme changes from step to step as
        // a face tilts by a hair, and Box2D warm-starts a point only from the old point of its id. A
        // stack then keeps its impulses, as Box2D's own face clipping does.
        if (p.count == 2 && cands[pick[0]].u > cands[pick[1]].u) std::swap(p.p[0], p.p[1]);
        for (int k = 0; k < p.count; ++k)
            p.p[k].key = kPatchEndKey + static_cast<uint32_t>(k);
        // Owner: the deepest point's pieces, or another point's if that proxy pair already has a patch.
        p.ownerA = -2;
        for (int pass = 0; pass < 2 && p.ownerA == -2; ++pass)
            for (int i = 0; i < nc; ++i) {
                const int ci = pass == 0 ? iD : i;
                bool taken = false;
                for (size_t q = firstPatch; q < out->size() && !taken; ++q)
                    taken = (*out)[q].ownerA == cands[ci].ownerA && (*out)[q].ownerB == cands[ci].ownerB;
                if (!taken) {
                    p.ownerA = cands[ci].ownerA;
                    p.ownerB = cands[ci].ownerB;
                    break;
                }
                if (pass == 0) break;
            }
        // No free proxy pair among the points' own: the caller gives the patch to another proxy
        // contact of the body pair, if one is free (ownerA stays -2).
        if (p.ownerA == -2) ++dropped;
        out->push_back(p);
    }
    return dropped;
}

} // namespace detail
} // namespace rugo
