// An animation of a scene that plays offline in any browser: one HTML file holding the bodies' outlines
// (in their body frames: rough bodies' curves at their contact level, boxes, circles, chains) and the
// run's trajectory.csv, replayed in a canvas by a few lines of JavaScript (play, pause, a time slider,
// speed). The CSV is copied into the page because browsers do not let a page opened from a file read
// its neighbours. Header-only; C++17.
#ifndef RUGO_SAMPLES_B2_ANIMATION_HPP
#define RUGO_SAMPLES_B2_ANIMATION_HPP

#include "b2_sample.hpp"

#include <fstream>
#include <sstream>

namespace b2s {

// Writes dir/animation.html from the run's bodies and dir/trajectory.csv (columns step, time, body,
// name, kind, x, y, angle, ...: b2_demo's). *rows gets the number of trajectory rows embedded.
inline bool WriteAnimation(const Run& run, const std::string& dir, const char* title, long* rows) {
    std::ifstream in(dir + "/trajectory.csv");
    if (!in) return false;
    std::stringstream csv;
    csv << in.rdbuf();
    const std::string text = csv.str();
    *rows = static_cast<long>(std::count(text.begin(), text.end(), '\n')) - 1; // less the header
    FILE* f = OpenOut(dir, "animation.html");
    if (!f) return false;
    std::fprintf(f, "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>%s</title>\n", title);
    std::fprintf(f, "<style>body{background:#1a1a1f;color:#ddd;font:14px sans-serif;margin:12px}"
                    "canvas{background:#fff;display:block;margin-top:8px}</style></head><body>\n");
    std::fprintf(f, "<div>%s &mdash; <button id=\"play\">pause</button> <input id=\"t\" type=\"range\" min=\"0\" "
                    "max=\"1000\" value=\"0\" style=\"width:50%%\"> <span id=\"time\"></span> speed "
                    "<select id=\"speed\"><option>0.25</option><option>0.5</option><option selected>1</option>"
                    "<option>2</option></select></div>\n",
                 title);
    std::fprintf(f, "<canvas id=\"c\" width=\"1100\" height=\"900\"></canvas>\n<script>\n");
    // The view box and each body's outline in its own frame.
    std::fprintf(f, "const view = [%.4f, %.4f, %.4f, %.4f];\nconst bodies = [\n", run.sc->view_lo.x, run.sc->view_lo.y,
                 run.sc->view_hi.x, run.sc->view_hi.y);
    for (std::size_t i = 0; i < run.bodies.size(); ++i) {
        const b2Body* b = run.bodies[i];
        const scene_body& sb = run.sc->bodies[i];
        const char* colour = sb.is_static ? "#555555" : Colour(static_cast<int>(i));
        std::fprintf(f, "{name: \"%s\", colour: \"%s\", ", sb.name, colour);
        if (sb.kind == SCENE_ROUGH) {
            rugo_contour k;
            rugo_shape_level(sb.shape, run.bridge->GetLevel(b), &k);
            std::fprintf(f, "closed: true, pts: [");
            for (int j = 0; j < k.count; ++j)
                for (int s = 0; s < 4; ++s) {
                    const rugo_vec2 p = rugo_contour_point(k, j, s / 4.0);
                    std::fprintf(f, "%.4f,%.4f,", p.x, p.y);
                }
            std::fprintf(f, "]},\n");
            continue;
        }
        const b2Fixture* fx = b->GetFixtureList();
        if (fx && fx->GetType() == b2Shape::e_circle) {
            const b2CircleShape* c = static_cast<const b2CircleShape*>(fx->GetShape());
            std::fprintf(f, "circle: [%.4f, %.4f, %.4f]},\n", c->m_p.x, c->m_p.y, c->m_radius);
        } else if (fx && fx->GetType() == b2Shape::e_polygon) {
            const b2PolygonShape* p = static_cast<const b2PolygonShape*>(fx->GetShape());
            std::fprintf(f, "closed: true, pts: [");
            for (int j = 0; j < p->m_count; ++j)
                std::fprintf(f, "%.4f,%.4f,", p->m_vertices[j].x, p->m_vertices[j].y);
            std::fprintf(f, "]},\n");
        } else if (fx && fx->GetType() == b2Shape::e_chain) {
            const b2ChainShape* c = static_cast<const b2ChainShape*>(fx->GetShape());
            std::fprintf(f, "closed: false, pts: [");
            for (int j = 0; j < c->m_count; ++j)
                std::fprintf(f, "%.4f,%.4f,", c->m_vertices[j].x, c->m_vertices[j].y);
            std::fprintf(f, "]},\n");
        } else {
            std::fprintf(f, "pts: []},\n");
        }
    }
    std::fprintf(f, "];\n</script>\n<script type=\"text/csv\" id=\"trajectory\">\n%s</script>\n", text.c_str());
    // The player: frames are the CSV's sampled steps; poses between them are interpolated.
    std::fprintf(f, "%s", R"JS(<script>
const rows = document.getElementById('trajectory').textContent.trim().split('\n');
const head = rows[0].split(','), col = n => head.indexOf(n);
const iT = col('time'), iB = col('body'), iX = col('x'), iY = col('y'), iA = col('angle');
const frames = []; // [{t, poses: [[x, y, a] per body]}]
for (const line of rows.slice(1)) {
  const v = line.split(','), t = +v[iT];
  if (!frames.length || frames[frames.length - 1].t !== t) frames.push({t, poses: []});
  frames[frames.length - 1].poses[+v[iB]] = [+v[iX], +v[iY], +v[iA]];
}
const canvas = document.getElementById('c'), g = canvas.getContext('2d');
const s = Math.min(canvas.width / (view[2] - view[0]), canvas.height / (view[3] - view[1]));
canvas.height = Math.ceil(s * (view[3] - view[1]));
const X = x => (x - view[0]) * s, Y = y => canvas.height - (y - view[1]) * s;
const T = frames[frames.length - 1].t;
let time = 0, playing = true, last = null;
function pose(i, t) {
  let k = 0;
  while (k + 1 < frames.length && frames[k + 1].t <= t) ++k;
  const a = frames[k].poses[i], b = (frames[k + 1] || frames[k]).poses[i];
  const u = k + 1 < frames.length ? (t - frames[k].t) / (frames[k + 1].t - frames[k].t) : 0;
  return [a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1]), a[2] + u * (b[2] - a[2])];
}
function draw() {
  g.clearRect(0, 0, canvas.width, canvas.height);
  g.lineWidth = 1.5;
  bodies.forEach((b, i) => {
    const [x, y, a] = pose(i, time), c = Math.cos(a), sn = Math.sin(a);
    const W = (px, py) => [X(x + c * px - sn * py), Y(y + sn * px + c * py)];
    g.strokeStyle = b.colour;
    g.fillStyle = b.colour + '33';
    g.beginPath();
    if (b.circle) {
      const [cx, cy] = W(b.circle[0], b.circle[1]);
      g.arc(cx, cy, b.circle[2] * s, 0, 2 * Math.PI);
      g.moveTo(cx, cy);
      const [ex, ey] = W(b.circle[0] + b.circle[2], b.circle[1]);
      g.lineTo(ex, ey);
    } else {
      for (let k = 0; k < b.pts.length; k += 2) {
        const [px, py] = W(b.pts[k], b.pts[k + 1]);
        k ? g.lineTo(px, py) : g.moveTo(px, py);
      }
      if (b.closed) g.closePath();
    }
    if (b.closed || b.circle) g.fill();
    g.stroke();
  });
  document.getElementById('time').textContent = 't = ' + time.toFixed(2) + ' s of ' + T.toFixed(2);
  document.getElementById('t').value = Math.round(1000 * time / T);
}
function tick(now) {
  if (playing && last !== null) {
    time += (now - last) / 1000 * +document.getElementById('speed').value;
    if (time > T) time = 0;
  }
  last = now;
  draw();
  requestAnimationFrame(tick);
}
document.getElementById('play').onclick = e => {
  playing = !playing;
  e.target.textContent = playing ? 'pause' : 'play';
};
document.getElementById('t').oninput = e => { time = T * e.target.value / 1000; };
requestAnimationFrame(tick);
</script>
</body></html>
)JS");
    return std::fclose(f) == 0;
}

} // namespace b2s

#endif
