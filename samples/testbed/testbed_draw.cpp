// The testbed's drawing: a b2Draw over ImGui's draw list (testbed_draw.hpp), and the world drawn
// through it — ordinary fixtures as Box2D's testbed colours them, rough bodies by the bridge's debug
// draw, and the testbed's overlays (exaggerated bands, MOBBtree boxes, contacts coloured by μ).
#include "testbed_draw.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace testbed {

namespace {

ImU32 Col(const b2Color& c, float alpha = 1.0f) {
    return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, c.a * alpha));
}

ImVec2 Im(b2Vec2 v) { return ImVec2(v.x, v.y); }

} // namespace

void ImDebugDraw::DrawPolygon(const b2Vec2* vertices, int32 count, const b2Color& color) {
    std::vector<ImVec2> v(static_cast<size_t>(count));
    for (int32 i = 0; i < count; ++i)
        v[static_cast<size_t>(i)] = Im(m_camera.ToScreen(vertices[i]));
    m_list->AddPolyline(v.data(), count, Col(color), ImDrawFlags_Closed, lineWidth);
}

void ImDebugDraw::DrawSolidPolygon(const b2Vec2* vertices, int32 count, const b2Color& color) {
    std::vector<ImVec2> v(static_cast<size_t>(count));
    for (int32 i = 0; i < count; ++i)
        v[static_cast<size_t>(i)] = Im(m_camera.ToScreen(vertices[i]));
    // Box2D's screen is y up, ImGui's y down: the convex fill wants clockwise on screen either way.
    m_list->AddConvexPolyFilled(v.data(), count,
                                Col(b2Color(0.5f * color.r, 0.5f * color.g, 0.5f * color.b), 0.6f));
    m_list->AddPolyline(v.data(), count, Col(color), ImDrawFlags_Closed, lineWidth);
}

void ImDebugDraw::DrawCircle(const b2Vec2& center, float radius, const b2Color& color) {
    m_list->AddCircle(Im(m_camera.ToScreen(center)), radius * m_camera.pixelsPerMetre, Col(color), 0,
                      lineWidth);
}

void ImDebugDraw::DrawSolidCircle(const b2Vec2& center, float radius, const b2Vec2& axis,
                                  const b2Color& color) {
    const ImVec2 c = Im(m_camera.ToScreen(center));
    const float r = radius * m_camera.pixelsPerMetre;
    m_list->AddCircleFilled(c, r, Col(b2Color(0.5f * color.r, 0.5f * color.g, 0.5f * color.b), 0.6f));
    m_list->AddCircle(c, r, Col(color), 0, lineWidth);
    m_list->AddLine(c, Im(m_camera.ToScreen(center + radius * axis)), Col(color), lineWidth);
}

void ImDebugDraw::DrawSegment(const b2Vec2& p1, const b2Vec2& p2, const b2Color& color) {
    m_list->AddLine(Im(m_camera.ToScreen(p1)), Im(m_camera.ToScreen(p2)), Col(color), lineWidth);
}

void ImDebugDraw::DrawTransform(const b2Transform& xf) {
    const float len = 0.4f;
    DrawSegment(xf.p, xf.p + len * xf.q.GetXAxis(), b2Color(1.0f, 0.0f, 0.0f));
    DrawSegment(xf.p, xf.p + len * xf.q.GetYAxis(), b2Color(0.0f, 1.0f, 0.0f));
}

void ImDebugDraw::DrawPoint(const b2Vec2& p, float size, const b2Color& color) {
    m_list->AddCircleFilled(Im(m_camera.ToScreen(p)), 0.5f * size + 1.0f, Col(color));
}

// ---- the world --------------------------------------------------------------------------------------
void Testbed::Draw(b2Draw* draw) const {
    if (settings.drawOrdinary) DrawOrdinary(draw);
    const rugo::Bridge* br = m_scene->w->bridge.get();
    if (br) {
        // Proxies first and wider, the true curves and bands over them: a proxy hugs its curve within the
        // band, so both stay visible, and the curve is what the collision answers to.
        if (settings.drawProxies) {
            ImDebugDraw* im = dynamic_cast<ImDebugDraw*>(draw);
            const float width = im ? im->lineWidth : 0.0f;
            if (im) im->lineWidth = 3.0f * width;
            br->Draw(draw, rugo::kDrawProxies);
            if (im) im->lineWidth = width;
        }
        unsigned flags = 0;
        if (settings.drawCurves) flags |= rugo::kDrawCurve;
        if (settings.drawBands && settings.bandExaggeration <= 1.0f) flags |= rugo::kDrawBand;
        if (settings.drawBridgeContacts) flags |= rugo::kDrawContacts;
        if (flags != 0) br->Draw(draw, flags);
    }
    if (settings.drawBands && settings.bandExaggeration > 1.0f) DrawBands(draw);
    if (settings.drawTree) DrawTree(draw);
    if (settings.drawContacts) DrawContacts(draw);
    if (m_mouse) {
        const b2Vec2 a = m_mouse->GetAnchorB(), t = m_mouse->GetTarget();
        const b2Color c(0.0f, 1.0f, 0.0f);
        draw->DrawPoint(a, 6.0f, c);
        draw->DrawPoint(t, 6.0f, c);
        draw->DrawSegment(a, t, b2Color(0.8f, 0.8f, 0.8f));
    }
}

void Testbed::DrawOrdinary(b2Draw* draw) const {
    const rugo::Bridge* br = m_scene->w->bridge.get();
    for (const b2Body* b = m_scene->w->world->GetBodyList(); b; b = b->GetNext()) {
        const b2Transform& xf = b->GetTransform();
        // Box2D's testbed colours.
        b2Color color(0.9f, 0.7f, 0.7f);
        if (b->GetType() == b2_staticBody)
            color = b2Color(0.5f, 0.9f, 0.5f);
        else if (b->GetType() == b2_kinematicBody)
            color = b2Color(0.5f, 0.5f, 0.9f);
        else if (!b->IsAwake())
            color = b2Color(0.6f, 0.6f, 0.6f);
        for (const b2Fixture* f = b->GetFixtureList(); f; f = f->GetNext()) {
            if (br && br->IsProxy(f)) continue; // the bridge draws rough bodies
            switch (f->GetType()) {
            case b2Shape::e_circle: {
                const b2CircleShape* c = static_cast<const b2CircleShape*>(f->GetShape());
                draw->DrawSolidCircle(b2Mul(xf, c->m_p), c->m_radius, xf.q.GetXAxis(), color);
                break;
            }
            case b2Shape::e_polygon: {
                const b2PolygonShape* p = static_cast<const b2PolygonShape*>(f->GetShape());
                b2Vec2 v[b2_maxPolygonVertices];
                for (int i = 0; i < p->m_count; ++i)
                    v[i] = b2Mul(xf, p->m_vertices[i]);
                draw->DrawSolidPolygon(v, p->m_count, color);
                break;
            }
            case b2Shape::e_edge: {
                const b2EdgeShape* e = static_cast<const b2EdgeShape*>(f->GetShape());
                draw->DrawSegment(b2Mul(xf, e->m_vertex1), b2Mul(xf, e->m_vertex2), color);
                break;
            }
            case b2Shape::e_chain: {
                const b2ChainShape* c = static_cast<const b2ChainShape*>(f->GetShape());
                for (int i = 0; i + 1 < c->m_count; ++i)
                    draw->DrawSegment(b2Mul(xf, c->m_vertices[i]), b2Mul(xf, c->m_vertices[i + 1]), color);
                break;
            }
            default:
                break;
            }
        }
    }
}

// The band's two offset curves at λ(t) times the exaggeration (the bridge draws them at λ(t)).
void Testbed::DrawBands(b2Draw* draw) const {
    const rugo::Bridge* br = m_scene->w->bridge.get();
    const b2Color color(0.5f, 0.5f, 0.2f);
    const int perSegment = 8;
    for (const auto& kv : m_rough) {
        const b2Body* b = kv.first;
        const int level = br->GetLevel(b);
        rugo_contour curve;
        rugo_tolerance_level tl;
        if (rugo_shape_level(kv.second.shape, level, &curve) != RUGO_OK ||
            rugo_shape_tolerance_level(kv.second.shape, level, &tl) != RUGO_OK)
            continue;
        const b2Transform& xf = b->GetTransform();
        for (int side = -1; side <= 1; side += 2) {
            b2Vec2 prev(0.0f, 0.0f);
            for (int k = 0; k <= curve.count * perSegment; ++k) {
                const int seg = (k / perSegment) % curve.count;
                const double t = static_cast<double>(k % perSegment) / perSegment;
                const rugo_vec2 p = rugo_contour_point(curve, seg, t), n = rugo_contour_normal(curve, seg, t);
                const double off = static_cast<double>(side) *
                                   static_cast<double>(settings.bandExaggeration) *
                                   rugo_tolerance_at(tl.total, tl.count, seg, t, 0.0);
                const b2Vec2 q = b2Mul(
                    xf, b2Vec2(static_cast<float>(p.x + off * n.x), static_cast<float>(p.y + off * n.y)));
                if (k > 0) draw->DrawSegment(prev, q, color);
                prev = q;
            }
        }
    }
}

// The MOBBtree's boxes at the chosen absolute level (clamped to each shape's levels).
void Testbed::DrawTree(b2Draw* draw) const {
    const b2Color color(0.8f, 0.45f, 0.9f);
    for (const auto& kv : m_rough) {
        const rugo_mobb_tree* tree = rugo_shape_tree(kv.second.shape);
        if (tree == nullptr) continue;
        const int level = std::max(rugo_mobb_tree_coarsest_level(tree),
                                   std::min(settings.treeLevel, rugo_mobb_tree_finest_level(tree)));
        const b2Transform& xf = kv.first->GetTransform();
        for (int k = 0; k < (1 << level); ++k) {
            const rugo_obb* box = rugo_mobb_tree_node(tree, level, k);
            if (box == nullptr) continue;
            rugo_vec2 c[4];
            rugo_obb_corners(box, c);
            b2Vec2 v[4];
            for (int i = 0; i < 4; ++i)
                v[i] = b2Mul(xf, b2Vec2(static_cast<float>(c[i].x), static_cast<float>(c[i].y)));
            draw->DrawPolygon(v, 4, color);
        }
    }
}

// Each point of the last step's touching contacts, and its normal, in the colour of the contact's μ.
void Testbed::DrawContacts(b2Draw* draw) const {
    for (const ContactView& c : m_contacts)
        for (int k = 0; k < c.points; ++k) {
            const b2Color col = MuColour(c.friction);
            draw->DrawPoint(c.p[k], c.rough ? 7.0f : 5.0f, col);
            draw->DrawSegment(c.p[k], c.p[k] + 0.25f * c.normal, col);
        }
}

} // namespace testbed
