// A b2Draw that draws into a Dear ImGui draw list (the window's background), through the testbed's
// camera: what the bridge's debug draw (rugo::Bridge::Draw), the ordinary fixtures and the testbed's own
// overlays are drawn with. ImGui's OpenGL 3 backend renders the list.
#ifndef RUGO_TESTBED_TESTBED_DRAW_HPP
#define RUGO_TESTBED_TESTBED_DRAW_HPP

#include "testbed.hpp"

struct ImDrawList;

namespace testbed {

class ImDebugDraw : public b2Draw {
  public:
    ImDebugDraw(ImDrawList* list, const Camera& camera) : m_list(list), m_camera(camera) {}
    void DrawPolygon(const b2Vec2* vertices, int32 count, const b2Color& color) override;
    void DrawSolidPolygon(const b2Vec2* vertices, int32 count, const b2Color& color) override;
    void DrawCircle(const b2Vec2& center, float radius, const b2Color& color) override;
    void DrawSolidCircle(const b2Vec2& center, float radius, const b2Vec2& axis,
                         const b2Color& color) override;
    void DrawSegment(const b2Vec2& p1, const b2Vec2& p2, const b2Color& color) override;
    void DrawTransform(const b2Transform& xf) override;
    void DrawPoint(const b2Vec2& p, float size, const b2Color& color) override;

    // Line width in pixels of segments and outlines.
    float lineWidth = 2.0f;

  private:
    ImDrawList* m_list;
    const Camera& m_camera;
};

} // namespace testbed

#endif
