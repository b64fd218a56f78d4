// The preview picture of a printable solid (see preview_svg.h). Sections come from
// geometry/plane_section.h, stability from mass/stability.h (Prévost et al. 2013), the waterline
// from mass/buoyancy.h; goals as in Musialski et al. 2015, section 6. Every number in the file is
// written by std::to_chars (no locale), so the same solid and input give the same bytes.
#include "optimize/preview_svg.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/mesh_shells.h"
#include "geometry/plane_section.h"
#include "mass/buoyancy.h"
#include "mass/mass_properties.h"
#include "mass/stability.h"
#include "util/format_double.h"

namespace offsetopt {

namespace {

// Fixed-point text with `decimals` digits after the point; "-0.00" becomes "0.00".
std::string fixed(double x, int decimals) {
  char buffer[64];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::fixed, decimals);
  if (r.ec != std::errc()) return format_double(x);
  std::string s(buffer, r.ptr);
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

// About four significant digits for a figure in the text (no libm: the exponent is counted).
std::string num(double x) {
  if (!std::isfinite(x)) return format_double(x);
  if (std::fabs(x) < 5e-7) return "0";  // round-off around zero (a symmetric mesh's cy) reads as 0
  double a = std::fabs(x);
  int decimals = 3;
  for (int i = 0; i < 3 && a >= 10.0; ++i, a /= 10.0) --decimals;
  for (int i = 0; i < 6 && a < 1.0; ++i, a *= 10.0) ++decimals;
  return fixed(x, std::max(decimals, 0));
}

std::string vec(const Eigen::Vector3d& p) { return "(" + num(p.x()) + ", " + num(p.y()) + ", " + num(p.z()) + ")"; }

std::string px(double x) { return fixed(x, 2); }

const char* const kOutline = "#2b3f5c";
const char* const kSupport = "#2e7d32";
const char* const kGoalMark = "#d00000";     // tipping, sphere centre, spin axis
const char* const kWater = "#0070c0";        // waterline, buoyancy, filled centre of mass
const char* const kGround = "#6b4f2a";

// One drawing area: model coordinates (u, v) map to (ox + s·u, oy − s·v) pixels.
struct View {
  std::string id, title;
  double umin = 0, umax = 0, vmin = 0, vmax = 0;
  double x = 0, y = 0, w = 0, h = 0;  // pixel rectangle
  double ox = 0, oy = 0, s = 1;
  Eigen::Vector2d map(double u, double v) const { return {ox + s * u, oy - s * v}; }
};

struct Svg {
  std::string out;
  void line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const char* colour, double width,
            const char* dash = nullptr) {
    out += "<line x1=\"" + px(a.x()) + "\" y1=\"" + px(a.y()) + "\" x2=\"" + px(b.x()) + "\" y2=\"" + px(b.y()) +
           "\" stroke=\"" + colour + "\" stroke-width=\"" + px(width) + "\"";
    if (dash) out += std::string(" stroke-dasharray=\"") + dash + "\"";
    out += "/>\n";
  }
  void dot(const Eigen::Vector2d& c, double r, const char* fill, const char* stroke = "#000000") {
    out += "<circle cx=\"" + px(c.x()) + "\" cy=\"" + px(c.y()) + "\" r=\"" + px(r) + "\" fill=\"" + fill +
           "\" stroke=\"" + stroke + "\" stroke-width=\"1\"/>\n";
  }
  void cross(const Eigen::Vector2d& c, double r, const char* colour) {
    line(c - Eigen::Vector2d(r, r), c + Eigen::Vector2d(r, r), colour, 1.5);
    line(c - Eigen::Vector2d(r, -r), c + Eigen::Vector2d(r, -r), colour, 1.5);
  }
  void text(double x, double y, const std::string& s, int size = 12, const char* anchor = "start",
            const char* colour = "#000000") {
    out += "<text x=\"" + px(x) + "\" y=\"" + px(y) + "\" font-size=\"" + std::to_string(size) + "\" fill=\"" +
           colour + "\" text-anchor=\"" + anchor + "\">" + s + "</text>\n";
  }
};

std::string loop_path(const View& view, const std::vector<Eigen::Vector2d>& points) {
  std::string d;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d p = view.map(points[i].x(), points[i].y());
    d += (i ? " L" : "M") + px(p.x()) + " " + px(p.y());
  }
  return d + " Z";
}

// Connected pieces of the surface (faces sharing a vertex) and their signed volumes: positive
// shells bound material from outside, negative ones are cavities.
struct Shells {
  Mesh outer;              // the faces of the positive shells (all vertices kept)
  int count = 0, cavities = 0;
};

Shells split_shells(const Mesh& mesh) {
  // Signed volume per shell, measured from the bounding box's centre (small numbers, exact sign).
  const Eigen::Vector3d centre = 0.5 * (mesh.V.colwise().minCoeff() + mesh.V.colwise().maxCoeff()).transpose();
  const MeshShells found = mesh_shells(mesh, centre);
  Shells shells;
  shells.count = found.count;
  for (double v : found.volume) shells.cavities += v < 0.0;
  std::vector<int> keep;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    if (found.volume[static_cast<std::size_t>(found.shell_of_face[static_cast<std::size_t>(f)])] > 0.0)
      keep.push_back(static_cast<int>(f));
  shells.outer.V = mesh.V;
  shells.outer.F.resize(static_cast<Eigen::Index>(keep.size()), 3);
  for (std::size_t i = 0; i < keep.size(); ++i) shells.outer.F.row(static_cast<Eigen::Index>(i)) = mesh.F.row(keep[i]);
  return shells;
}

Mesh without_unused_vertices(const Mesh& mesh) {
  std::vector<int> index(static_cast<std::size_t>(mesh.V.rows()), -1);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.F(f, k);
      index[static_cast<std::size_t>(v)] = 0;
    }
  int used = 0;
  for (int& i : index)
    if (i == 0) i = used++;
  if (used == mesh.V.rows()) return mesh;
  Mesh out;
  out.V.resize(used, 3);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    if (index[static_cast<std::size_t>(v)] >= 0) out.V.row(index[static_cast<std::size_t>(v)]) = mesh.V.row(v);
  out.F.resize(mesh.F.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) out.F(f, k) = index[static_cast<std::size_t>(mesh.F(f, k))];
  return out;
}

// The convex polygon shrunk by `margin`: clipped against each edge's line moved inwards
// (Sutherland and Hodgman 1974). Empty when nothing is left.
std::vector<Eigen::Vector2d> shrink_polygon(const std::vector<Eigen::Vector2d>& polygon, double margin) {
  if (polygon.size() < 3) return {};
  std::vector<Eigen::Vector2d> current = polygon;
  for (std::size_t i = 0; i < polygon.size() && !current.empty(); ++i) {
    const Eigen::Vector2d a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    const Eigen::Vector2d edge = b - a;
    const double length = edge.norm();
    if (length == 0.0) continue;
    const Eigen::Vector2d inward = Eigen::Vector2d(-edge.y(), edge.x()) / length;  // CCW: left is inside
    auto distance = [&](const Eigen::Vector2d& p) { return inward.dot(p - a) - margin; };
    std::vector<Eigen::Vector2d> next;
    for (std::size_t j = 0; j < current.size(); ++j) {
      const Eigen::Vector2d p = current[j], q = current[(j + 1) % current.size()];
      const double dp = distance(p), dq = distance(q);
      if (dp >= 0.0) next.push_back(p);
      if ((dp >= 0.0) != (dq >= 0.0)) next.push_back(p + (dp / (dp - dq)) * (q - p));
    }
    current = std::move(next);
  }
  if (current.size() < 3) return {};
  return current;
}

// The point of the support polygon's boundary where the object pivots when it tips: the foot of
// the perpendicular from the centre of mass to the tipping edge (clamped to the edge), or the
// single contact point.
Eigen::Vector2d pivot_point(const Stability& st, const Eigen::Vector2d& c) {
  const auto& poly = st.support_polygon;
  if (st.tipping_edge < 0 || poly.size() < 2) return poly.empty() ? c : poly[0];
  const Eigen::Vector2d a = poly[static_cast<std::size_t>(st.tipping_edge)];
  const Eigen::Vector2d b = poly[(static_cast<std::size_t>(st.tipping_edge) + 1) % poly.size()];
  const double len2 = (b - a).squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((c - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
  return a + t * (b - a);
}

const double kMargin = 20.0;  // px around the picture

// What the picture shows, measured once on the solid: mass properties, stability, shells, and
// the goal's own figures (the filled centre of mass, the waterline).
struct Scene {
  Mesh solid;
  Vector10d P;                 // the solid's
  Eigen::Vector3d com;
  Stability stability;
  Shells shells;
  bool have_outer = false;
  Vector10d Pout;              // the outer shells' (the solid with its cavities filled)
  double void_volume = 0.0;
  Eigen::Vector2d com_xy, pivot;
  std::vector<Eigen::Vector2d> shrunk;  // the support polygon shrunk by the margin
  bool stand_goal = false;
  bool have_filled = false;
  Eigen::Vector3d filled_com;
  Stability filled_stability;
  FloatingEquilibrium water;
  bool have_water = false, neutral = false;
};

// The goal-specific figures of `scene` (its solid, mass properties, stability and shells set).
void measure_goal(Scene& sc, const PreviewInput& input, const PreviewOptions& options) {
  const Vector10d& P = sc.P;
  const Vector10d& Pout = sc.Pout;
  const Eigen::Vector3d& com = sc.com;
  sc.com_xy = Eigen::Vector2d(com.x(), com.y());
  sc.pivot = pivot_point(sc.stability, sc.com_xy);
  sc.shrunk = shrink_polygon(sc.stability.support_polygon, input.margin);
  sc.stand_goal = input.goal == GoalKind::stand || input.goal == GoalKind::stand_filled;
  sc.filled_com = com;
  if (input.goal == GoalKind::stand_filled && sc.have_outer && sc.void_volume > 0.0 && Pout(kMass) > P(kMass)) {
    const double vv = Pout(kMass) - P(kMass);
    const Eigen::Vector3d cout(Pout(kCx), Pout(kCy), Pout(kCz));
    const Eigen::Vector3d cvoid = (Pout(kMass) * cout - P(kMass) * com) / vv;
    const double mf = P(kMass) + input.fill_density * vv;
    sc.filled_com = (P(kMass) * com + input.fill_density * vv * cvoid) / mf;
    sc.filled_stability = sc.stability;
    support_polygon_margins(sc.stability.support_polygon, Eigen::Vector2d(sc.filled_com.x(), sc.filled_com.y()),
                            sc.filled_com.z() - sc.stability.ground_z, sc.filled_stability);
    sc.have_filled = true;
  }
  if (input.goal == GoalKind::floating && input.fluid_density > 0.0 && sc.have_outer) {
    FloatingOptions fo;
    fo.fluid_density = input.fluid_density;
    fo.max_iterations = options.bisection_cap;
    FloatingEquilibrium& water = sc.water;
    water = floating_equilibrium(sc.shells.outer, P(kMass), fo);
    sc.have_water = true;
    // The float goal (eq. 9) asks for weight = buoyancy fully submerged: within the tolerance
    // verification uses (1e-3 of the mass) the fluid's surface is at or above the top, and the
    // centre of buoyancy is the outer volume's centroid.
    if (std::fabs(input.fluid_density * Pout(kMass) - P(kMass)) <= 1e-3 * P(kMass)) {
      water.status = FloatingEquilibrium::Status::floats;
      water.waterline = sc.shells.outer.V.col(2).maxCoeff();
      water.displaced_volume = Pout(kMass);
      water.center_of_buoyancy = Eigen::Vector3d(Pout(kCx), Pout(kCy), Pout(kCz));
      sc.neutral = true;
    } else if (water.status == FloatingEquilibrium::Status::sinks) {
      water.center_of_buoyancy = Eigen::Vector3d(Pout(kCx), Pout(kCy), Pout(kCz));
    }
  }
}

// The three views side by side at one scale: front and side sections, top view.
struct Layout {
  View views[3];
  std::string titles[3][2];
  double s = 1.0;              // px per input unit
  double width = 0.0, views_bottom = 0.0;
};

Layout layout_views(const Scene& sc, const PreviewInput& input, const PreviewOptions& options) {
  // Extents of everything drawn.
  Eigen::Vector3d lo = sc.solid.V.colwise().minCoeff().transpose(), hi = sc.solid.V.colwise().maxCoeff().transpose();
  auto include = [&](const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  if (input.has_before_com) include(input.before_com);
  if (input.has_tip) include(input.tip);
  if (input.has_sphere) {
    include(input.sphere_center - Eigen::Vector3d::Constant(input.sphere_radius));
    include(input.sphere_center + Eigen::Vector3d::Constant(input.sphere_radius));
  }
  const double pad = 0.06 * (hi - lo).maxCoeff();
  lo -= Eigen::Vector3d::Constant(pad);
  hi += Eigen::Vector3d::Constant(pad);
  const Eigen::Vector3d range = hi - lo;
  Layout layout;
  const double s = layout.s = std::min(options.view_height / std::max(range.z(), range.y()),
                                       options.views_width / (2.0 * range.x() + range.y()));

  const double gap = 24.0, top = 78.0, min_slot = 190.0;
  const char* ids[3] = {"view-xz", "view-yz", "view-top"};
  const std::string titles[3][2] = {{"front: section y = " + num(sc.com.y()), "(xz plane, seen from -y)"},
                                    {"side: section x = " + num(sc.com.x()), "(yz plane, seen from +x)"},
                                    {"top view", "(seen from +z)"}};
  const double ranges[3][4] = {{lo.x(), hi.x(), lo.z(), hi.z()}, {lo.y(), hi.y(), lo.z(), hi.z()}, {lo.x(), hi.x(), lo.y(), hi.y()}};
  double x = kMargin, views_bottom = top;
  for (int i = 0; i < 3; ++i) {
    View& v = layout.views[i];
    layout.titles[i][0] = titles[i][0];
    layout.titles[i][1] = titles[i][1];
    v.id = ids[i];
    v.title = titles[i][0];
    v.umin = ranges[i][0];
    v.umax = ranges[i][1];
    v.vmin = ranges[i][2];
    v.vmax = ranges[i][3];
    v.s = s;
    v.w = (v.umax - v.umin) * s;
    v.h = (v.vmax - v.vmin) * s;
    const double slot = std::max(v.w, min_slot);  // room for the title under a narrow view
    v.x = x + 0.5 * (slot - v.w);
    v.y = top;
    v.ox = v.x - s * v.umin;
    v.oy = v.y + s * v.vmax;
    x += slot + gap;
    views_bottom = std::max(views_bottom, v.y + v.h);
  }
  layout.width = std::max(x - gap + kMargin, 900.0);
  layout.views_bottom = views_bottom;
  return layout;
}

// The document's head: size (the height filled in at the end), title, clip paths, background.
void begin_document(Svg& svg, const Layout& layout, GoalKind goal) {
  std::string& out = svg.out;
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + px(layout.width) +
         "\" height=\"@HEIGHT@\" viewBox=\"0 0 " + px(layout.width) + " @HEIGHT@\" font-family=\"sans-serif\">\n";
  out += "<title>offsetopt preview: goal " + std::string(to_string(goal)) + "</title>\n";
  out += "<defs>\n";
  for (const View& v : layout.views)
    out += "<clipPath id=\"clip-" + v.id + "\"><rect x=\"" + px(v.x) + "\" y=\"" + px(v.y) + "\" width=\"" + px(v.w) +
           "\" height=\"" + px(v.h) + "\"/></clipPath>\n";
  out += "</defs>\n";
  out += "<rect x=\"0\" y=\"0\" width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  svg.text(kMargin, 28, std::string("offsetopt preview: goal ") + to_string(goal), 16);
}

// Where model point p is drawn in view i (0: xz, 1: yz, 2: top).
Eigen::Vector2d view_point(const View& v, int i, const Eigen::Vector3d& p) {
  const Eigen::Vector2d q =
      i == 0 ? Eigen::Vector2d(p.x(), p.z()) : i == 1 ? Eigen::Vector2d(p.y(), p.z()) : Eigen::Vector2d(p.x(), p.y());
  return v.map(q.x(), q.y());
}

// A vertical section (view 0 or 1): ground, material and cavity loops, outlines.
void draw_section(Svg& svg, const View& v, int i, const Scene& sc) {
  std::string& out = svg.out;
  // Loops do not cross, and a loop inside another is smaller, so painting them from the largest
  // area down nests them right: material loops (counter-clockwise) in the material colour,
  // cavity loops over them in the cavity colour, islands inside a cavity over those. Each edge
  // pixel then blends exactly the two colours that meet there (filling the material with holes
  // over the cavity would let the background bleed into every edge pixel). Outlines of the
  // material loops last.
  svg.line(v.map(v.umin, sc.stability.ground_z), v.map(v.umax, sc.stability.ground_z), kGround, 1.5);
  const PlaneSection section = plane_section(sc.solid, i == 0 ? xz_plane(sc.com.y()) : yz_plane(sc.com.x()));
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < section.loops.size(); ++k)
    if (section.loops[k].points.size() >= 3) order.push_back(k);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::fabs(section.loops[a].signed_area) > std::fabs(section.loops[b].signed_area);
  });
  std::string outline;
  for (const std::size_t k : order) {
    const SectionLoop& loop = section.loops[k];
    const std::string d = loop_path(v, loop.points);
    out += "<path d=\"" + d + "\" fill=\"" + (loop.signed_area < 0.0 ? kPreviewCavityColour : kPreviewMaterialColour) +
           "\" stroke=\"none\"/>\n";
    if (loop.signed_area >= 0.0) outline += d + " ";
  }
  if (!outline.empty())
    out += "<path d=\"" + outline + "\" fill=\"none\" stroke=\"" + kOutline + "\" stroke-width=\"1\"/>\n";
}

// The goal's marks in a vertical section: the tipping line and angle, the sphere, the spin
// axis, the waterline and the centre of buoyancy.
void draw_section_goal(Svg& svg, const View& v, int i, const Scene& sc, const PreviewInput& input, double r) {
  auto at = [&](const Eigen::Vector3d& p) { return view_point(v, i, p); };
  const Stability& stability = sc.stability;
  if (sc.stand_goal) {
    const Eigen::Vector3d foot(sc.pivot.x(), sc.pivot.y(), stability.ground_z);
    svg.line(at(sc.com), at(foot), kGoalMark, 1.5, "5 3");
    // The angle where the tipping direction lies mostly in this view's plane.
    const Eigen::Vector2d towards = sc.pivot - sc.com_xy;
    if ((i == 0) == (std::fabs(towards.x()) >= std::fabs(towards.y()))) {
      const Eigen::Vector2d label = at(foot);
      const bool right_half = label.x() > v.x + 0.5 * v.w;
      svg.text(label.x() + (right_half ? -4 : 4), label.y() - 6, "tips at " + fixed(stability.tipping_angle_deg, 1) + " deg",
               10, right_half ? "end" : "start", kGoalMark);
    }
  }
  if (input.has_sphere && input.goal == GoalKind::roly_poly) {
    const double off = i == 0 ? sc.com.y() - input.sphere_center.y() : sc.com.x() - input.sphere_center.x();
    if (std::fabs(off) < input.sphere_radius) {
      const double rr = std::sqrt(input.sphere_radius * input.sphere_radius - off * off);
      const Eigen::Vector2d c = at(input.sphere_center);
      svg.out += "<circle cx=\"" + px(c.x()) + "\" cy=\"" + px(c.y()) + "\" r=\"" + px(rr * v.s) +
                 "\" fill=\"none\" stroke=\"" + kGoalMark + "\" stroke-width=\"1.2\" stroke-dasharray=\"6 4\"/>\n";
    }
    svg.cross(at(input.sphere_center), r + 1.5, kGoalMark);
  }
  if (input.has_tip && input.goal == GoalKind::spin) {
    const double u = i == 0 ? input.tip.x() : input.tip.y();
    svg.line(v.map(u, v.vmin), v.map(u, v.vmax), kGoalMark, 1.5, "10 4 2 4");
    svg.cross(at(input.tip), r + 1.5, kGoalMark);
  }
  if (sc.have_water) {
    if (sc.water.status == FloatingEquilibrium::Status::floats)
      svg.line(v.map(v.umin, sc.water.waterline), v.map(v.umax, sc.water.waterline), kWater, 1.5, "8 4");
    svg.dot(at(sc.water.center_of_buoyancy), r, "#ffffff", kWater);
  }
}

// The top view (view 2): the horizontal section through the centre of mass as a light
// silhouette, the support polygon and the polygon shrunk by the margin, the goal's marks.
void draw_top_view(Svg& svg, const View& v, const Scene& sc, const PreviewInput& input, double r) {
  std::string& out = svg.out;
  auto at = [&](const Eigen::Vector3d& p) { return view_point(v, 2, p); };
  const PlaneSection section = plane_section(sc.solid, xy_plane(sc.com.z()));
  std::string material;
  for (const SectionLoop& loop : section.loops)
    if (loop.points.size() >= 2) material += loop_path(v, loop.points) + " ";
  if (!material.empty())
    out += "<path d=\"" + material + "\" fill=\"#e4ebf4\" fill-rule=\"nonzero\" stroke=\"#8aa0bd\" stroke-width=\"0.8\"/>\n";
  auto polygon = [&](const std::vector<Eigen::Vector2d>& poly, const char* fill, const char* dash) {
    if (poly.empty()) return;
    if (poly.size() == 1) {
      svg.cross(v.map(poly[0].x(), poly[0].y()), 3.0, kSupport);
      return;
    }
    out += "<path d=\"" + loop_path(v, poly) + "\" fill=\"" + fill + "\" stroke=\"" + kSupport + "\" stroke-width=\"1.5\"";
    if (dash) out += std::string(" stroke-dasharray=\"") + dash + "\"";
    out += "/>\n";
  };
  polygon(sc.stability.support_polygon, "#c8e6c9", nullptr);
  polygon(sc.shrunk, "none", "4 3");
  if (sc.stand_goal) svg.line(at(sc.com), v.map(sc.pivot.x(), sc.pivot.y()), kGoalMark, 1.5, "5 3");
  if (input.has_sphere && input.goal == GoalKind::roly_poly) svg.cross(at(input.sphere_center), r + 1.5, kGoalMark);
  if (input.has_tip && input.goal == GoalKind::spin) svg.cross(at(input.tip), r + 1.5, kGoalMark);
  if (sc.have_water) svg.dot(at(sc.water.center_of_buoyancy), r, "#ffffff", kWater);
}

// Each view: its titles, its group (the mapping in data attributes, clipped to the view), the
// drawing, the centres of mass on top, the frame.
void draw_views(Svg& svg, const Layout& layout, const Scene& sc, const PreviewInput& input, double r) {
  std::string& out = svg.out;
  for (int i = 0; i < 3; ++i) {
    const View& v = layout.views[i];
    svg.text(v.x + 0.5 * v.w, v.y - 22, layout.titles[i][0], 11, "middle");
    svg.text(v.x + 0.5 * v.w, v.y - 8, layout.titles[i][1], 11, "middle", "#505050");
    out += "<g id=\"" + v.id + "\" data-origin-x=\"" + format_double(v.ox) + "\" data-origin-y=\"" + format_double(v.oy) +
           "\" data-scale=\"" + format_double(v.s) + "\" data-x=\"" + px(v.x) + "\" data-y=\"" + px(v.y) + "\" data-width=\"" +
           px(v.w) + "\" data-height=\"" + px(v.h) + "\" clip-path=\"url(#clip-" + v.id + ")\">\n";
    if (i < 2) {
      draw_section(svg, v, i, sc);
      draw_section_goal(svg, v, i, sc, input, r);
    } else {
      draw_top_view(svg, v, sc, input, r);
    }
    for (const PreviewInput::Opening& o : input.openings) {
      svg.line(view_point(v, i, o.inner), view_point(v, i, o.outer), kPreviewOpeningColour, 2.0);
      const Eigen::Vector2d c = view_point(v, i, o.outer);
      out += "<circle cx=\"" + px(c.x()) + "\" cy=\"" + px(c.y()) + "\" r=\"" + px(std::max(o.radius * v.s, 2.0)) +
             "\" fill=\"none\" stroke=\"" + kPreviewOpeningColour + "\" stroke-width=\"2\"/>\n";
    }
    if (sc.have_filled) svg.dot(view_point(v, i, sc.filled_com), r, kWater);
    if (input.has_before_com) svg.dot(view_point(v, i, input.before_com), r, kPreviewComBeforeColour);
    svg.dot(view_point(v, i, sc.com), r, kPreviewComAfterColour);  // last: never covered
    out += "</g>\n";
    out += "<rect x=\"" + px(v.x) + "\" y=\"" + px(v.y) + "\" width=\"" + px(v.w) + "\" height=\"" + px(v.h) +
           "\" fill=\"none\" stroke=\"#b0b0b0\" stroke-width=\"1\"/>\n";
  }
}

// Scale bar at height y: 1, 2 or 5 times a power of ten, 60 to 150 px long.
void draw_scale_bar(Svg& svg, double s, double y) {
  double bar = 1.0;
  for (int i = 0; i < 400 && bar * s > 150.0; ++i) bar /= 10.0;
  for (int i = 0; i < 400 && bar * s < 60.0; ++i) bar *= 10.0;
  if (bar * s > 150.0) bar /= 2.0;
  if (bar * s > 150.0) bar /= 2.5;
  const Eigen::Vector2d a(kMargin, y), b(kMargin + bar * s, y);
  svg.line(a, b, "#000000", 2.0);
  svg.line(a - Eigen::Vector2d(0, 5), a + Eigen::Vector2d(0, 5), "#000000", 1.5);
  svg.line(b - Eigen::Vector2d(0, 5), b + Eigen::Vector2d(0, 5), "#000000", 1.5);
  svg.text(b.x() + 8, y + 4, format_double(bar) + " input units (the mesh's units; all views at this scale)", 11);
}

// The legend in the left column from height y down; returns the height below it.
double draw_legend(Svg& svg, const Scene& sc, const PreviewInput& input, double r, double y) {
  struct Entry {
    std::string kind, colour, label;
  };
  std::vector<Entry> legend = {{"fill", kPreviewMaterialColour, "material (section)"},
                               {"fill", kPreviewCavityColour, "cavity (section)"},
                               {"dot", kPreviewComAfterColour, "centre of mass, result"},
                               {"dot", kPreviewComBeforeColour, "centre of mass, input"},
                               {"line", kGround, "ground plane"},
                               {"fill", "#c8e6c9", "support polygon (ground contacts)"},
                               {"dash", kSupport, "support polygon shrunk by the margin"},
                               {"fill", "#e4ebf4", "top view: section at the centre of mass's height"}};
  if (sc.stand_goal) legend.push_back({"dash", kGoalMark, "to the tipping edge (direction it would tip)"});
  if (sc.have_filled) legend.push_back({"dot", kWater, "centre of mass, filled"});
  if (!input.openings.empty()) legend.push_back({"ring", kPreviewOpeningColour, "opening (drain hole, channel): axis and radius"});
  if (input.goal == GoalKind::roly_poly) legend.push_back({"cross", kGoalMark, "sphere centre (dashed: its section)"});
  if (input.goal == GoalKind::spin) legend.push_back({"dash", kGoalMark, "spin axis through the tip (cross)"});
  if (sc.have_water) {
    legend.push_back({"dash", kWater, sc.neutral ? "waterline (at the top: fully submerged)" : "waterline"});
    legend.push_back({"ring", kWater, "centre of buoyancy"});
  }
  for (const Entry& e : legend) {
    const double sx = kMargin, sy = y - 9;
    if (e.kind == "fill")
      svg.out += "<rect x=\"" + px(sx) + "\" y=\"" + px(sy) + "\" width=\"22\" height=\"11\" fill=\"" + e.colour +
                 "\" stroke=\"#808080\" stroke-width=\"0.5\"/>\n";
    else if (e.kind == "dot")
      svg.dot(Eigen::Vector2d(sx + 11, sy + 5.5), r, e.colour.c_str());
    else if (e.kind == "ring")
      svg.dot(Eigen::Vector2d(sx + 11, sy + 5.5), r, "#ffffff", e.colour.c_str());
    else if (e.kind == "cross")
      svg.cross(Eigen::Vector2d(sx + 11, sy + 5.5), r, e.colour.c_str());
    else
      svg.line(Eigen::Vector2d(sx, sy + 5.5), Eigen::Vector2d(sx + 22, sy + 5.5), e.colour.c_str(), 1.5,
               e.kind == "dash" ? "5 3" : nullptr);
    svg.text(sx + 30, y, e.label, 11);
    y += 17;
  }
  return y;
}

// The figures in the right column: lines of text and, for spin, bars of the principal moments.
struct Figures {
  std::vector<std::string> lines;
  std::vector<std::pair<std::string, double>> bars;
};

Figures goal_figures(const Scene& sc, const PreviewInput& input) {
  const Vector10d& P = sc.P;
  const Eigen::Vector3d& com = sc.com;
  const Stability& stability = sc.stability;
  Figures figures;
  std::vector<std::string>& lines = figures.lines;
  lines.push_back("solid: volume (mass at density 1) " + num(P(kMass)) + ", " + std::to_string(sc.shells.count) +
                  " shell(s), " + std::to_string(sc.shells.cavities) + " cavity shell(s)");
  lines.push_back("centre of mass " + vec(com));
  if (input.has_before_com) lines.push_back("input's centre of mass " + vec(input.before_com));
  lines.push_back("void volume " + num(sc.void_volume));
  lines.push_back("support polygon: " + std::to_string(stability.support_polygon.size()) + " corners, " +
                  std::to_string(stability.contact_vertex_count) + " contact vertices");
  lines.push_back("(ground z = " + num(stability.ground_z) + ", contact tolerance " + num(stability.ground_tol) + ")");
  if (sc.stand_goal)
    lines.push_back("centre of mass inside it by " + num(stability.com_margin) + " (margin asked " + num(input.margin) + ")");
  switch (input.goal) {
    case GoalKind::stand:
    case GoalKind::stand_filled:
      lines.push_back("tipping angle " + fixed(stability.tipping_angle_deg, 2) + " deg" +
                      (stability.stands ? "" : " (falls over)") + (sc.have_filled ? " empty" : ""));
      if (sc.have_filled)
        lines.push_back("tipping angle " + fixed(sc.filled_stability.tipping_angle_deg, 2) + " deg filled (density " +
                        num(input.fill_density) + "), centre of mass " + vec(sc.filled_com));
      break;
    case GoalKind::roly_poly:
      if (input.has_sphere)
        lines.push_back("sphere centre " + vec(input.sphere_center) + ", radius " + num(input.sphere_radius) +
                        "; centre of mass " + num(input.sphere_center.z() - com.z()) + " below it (margin asked " +
                        num(input.margin) + ")");
      break;
    case GoalKind::spin: {
      if (input.has_tip) lines.push_back("spin axis: vertical through the tip " + vec(input.tip));
      const PrincipalInertia pi = principal_inertia(P);
      int k = 0;
      for (int j = 1; j < 3; ++j)
        if (std::fabs(pi.axes(2, j)) > std::fabs(pi.axes(2, k))) k = j;
      int a = -1, b = -1;
      for (int j = 0; j < 3; ++j)
        if (j != k) (a < 0 ? a : b) = j;
      figures.bars = {{"I_a", pi.moments(a)}, {"I_b", pi.moments(b)}, {"Izz", P(kIzz)}};
      lines.push_back("Izz " + num(P(kIzz)) + ", other principal moments " + num(pi.moments(a)) + ", " + num(pi.moments(b)) +
                      " (Izz should be the largest)");
      break;
    }
    case GoalKind::floating:
      if (sc.have_water) {
        const double excess = input.fluid_density * sc.Pout(kMass) - P(kMass);
        if (sc.neutral)
          lines.push_back("fully submerged in density " + num(input.fluid_density) + ": buoyancy - weight = " + num(excess) +
                          " (" + num(100.0 * excess / P(kMass)) + "% of the weight)");
        else if (sc.water.status == FloatingEquilibrium::Status::floats)
          lines.push_back("floats in density " + num(input.fluid_density) + ", waterline z = " + num(sc.water.waterline));
        else
          lines.push_back("sinks in density " + num(input.fluid_density) + ": buoyancy - weight = " + num(excess));
        lines.push_back("centre of buoyancy " + vec(sc.water.center_of_buoyancy) + "; centre of mass " +
                        num(sc.water.center_of_buoyancy.z() - com.z()) + " below it");
      }
      break;
    case GoalKind::volume:
      lines.push_back("void volume " + num(sc.void_volume) +
                      (input.target_volume > 0.0 ? " (target " + num(input.target_volume) + ")" : std::string()));
      break;
  }
  return figures;
}

// The figures in the right column from height `top` down; returns the height below them.
double draw_figures(Svg& svg, const Figures& figures, double top) {
  double ty = top;
  const double column = 330.0;
  for (const std::string& line : figures.lines) {
    svg.text(column, ty, line, 11);
    ty += 17;
  }
  if (!figures.bars.empty()) {
    double biggest = 0.0;
    for (const auto& b : figures.bars) biggest = std::max(biggest, b.second);
    ty += 4;
    for (const auto& b : figures.bars) {
      const double length = biggest > 0.0 ? 200.0 * b.second / biggest : 0.0;
      svg.text(column, ty + 9, b.first, 11);
      svg.out += "<rect x=\"" + px(column + 34) + "\" y=\"" + px(ty) + "\" width=\"" + px(length) +
                 "\" height=\"11\" fill=\"" + (b.first == "Izz" ? kGoalMark : "#8aa0bd") + "\"/>\n";
      svg.text(column + 40 + length, ty + 9, num(b.second), 11);
      ty += 17;
    }
  }
  return ty;
}

}  // namespace

std::string PreviewOptions::check() const {
  const PreviewOptions& s = *this;
  if (!(s.view_height >= 50.0 && s.view_height <= 5000.0)) return "view_height must be in [50, 5000] px";
  if (!(s.views_width >= 150.0 && s.views_width <= 20000.0)) return "views_width must be in [150, 20000] px";
  if (!(s.marker_radius >= 1.0 && s.marker_radius <= 50.0)) return "marker_radius must be in [1, 50] px";
  if (s.bisection_cap < 1 || s.bisection_cap > 10000) return "bisection_cap must be in [1, 10000]";
  return {};
}

PreviewResult preview_svg(const Mesh& mesh, const PreviewInput& input, const PreviewOptions& options) {
  PreviewResult result;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.F(f, k) < 0 || mesh.F(f, k) >= mesh.V.rows()) {
        result.message = "face " + std::to_string(f) + " refers to a vertex that does not exist";
        return result;
      }
  // Vertices no face uses are left out (the reader drops them too), so the picture drawn from a
  // result in memory and from its file read back are the same.
  Scene sc;
  sc.solid = without_unused_vertices(mesh);
  if (const std::string problem = options.check(); !problem.empty()) {
    result.message = problem;
    return result;
  }
  if (sc.solid.V.rows() < 4 || sc.solid.F.rows() < 4) {
    result.message = "the solid has fewer than 4 vertices or faces";
    return result;
  }
  sc.P = mass_properties(sc.solid);
  if (!(sc.P(kMass) > 0.0) || !sc.P.allFinite()) {
    result.message = "the solid's volume is not positive";
    return result;
  }
  sc.com = Eigen::Vector3d(sc.P(kCx), sc.P(kCy), sc.P(kCz));
  StabilityOptions stability_options;
  stability_options.ground_tol = input.ground_tol;
  sc.stability = compute_stability(sc.solid, sc.com, stability_options);
  sc.shells = split_shells(sc.solid);
  sc.have_outer = sc.shells.outer.F.rows() > 0;
  sc.Pout = sc.have_outer ? mass_properties(sc.shells.outer) : sc.P;
  sc.void_volume = input.void_volume >= 0.0 ? input.void_volume : std::max(sc.Pout(kMass) - sc.P(kMass), 0.0);
  measure_goal(sc, input, options);

  const Layout layout = layout_views(sc, input, options);
  Svg svg;
  begin_document(svg, layout, input.goal);
  draw_views(svg, layout, sc, input, options.marker_radius);
  double y = layout.views_bottom + 28;
  draw_scale_bar(svg, layout.s, y);
  y += 26;
  const double legend_top = y;
  const double legend_bottom = draw_legend(svg, sc, input, options.marker_radius, y);
  const double figures_bottom = draw_figures(svg, goal_figures(sc, input), legend_top);

  const double height = std::max(legend_bottom, figures_bottom) + kMargin;
  std::string& out = svg.out;
  out += "</svg>\n";
  const std::string h = px(height);
  for (std::size_t at = out.find("@HEIGHT@"); at != std::string::npos; at = out.find("@HEIGHT@", at)) out.replace(at, 8, h);
  result.status = PreviewStatus::ok;
  result.svg = std::move(out);
  return result;
}

}  // namespace offsetopt
