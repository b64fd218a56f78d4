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
  const Mesh solid = without_unused_vertices(mesh);
  if (const std::string problem = options.check(); !problem.empty()) {
    result.message = problem;
    return result;
  }
  if (solid.V.rows() < 4 || solid.F.rows() < 4) {
    result.message = "the solid has fewer than 4 vertices or faces";
    return result;
  }
  const Vector10d P = mass_properties(solid);
  if (!(P(kMass) > 0.0) || !P.allFinite()) {
    result.message = "the solid's volume is not positive";
    return result;
  }
  const Eigen::Vector3d com(P(kCx), P(kCy), P(kCz));
  StabilityOptions stability_options;
  stability_options.ground_tol = input.ground_tol;
  const Stability stability = compute_stability(solid, com, stability_options);
  const Shells shells = split_shells(solid);
  const bool have_outer = shells.outer.F.rows() > 0;
  const Vector10d Pout = have_outer ? mass_properties(shells.outer) : P;
  const double void_volume = input.void_volume >= 0.0 ? input.void_volume : std::max(Pout(kMass) - P(kMass), 0.0);

  // Extents of everything drawn.
  Eigen::Vector3d lo = solid.V.colwise().minCoeff().transpose(), hi = solid.V.colwise().maxCoeff().transpose();
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
  const double s = std::min(options.view_height / std::max(range.z(), range.y()),
                            options.views_width / (2.0 * range.x() + range.y()));

  const double margin = 20.0, gap = 24.0, top = 78.0, min_slot = 190.0;
  View views[3];
  const char* ids[3] = {"view-xz", "view-yz", "view-top"};
  const std::string titles[3][2] = {{"front: section y = " + num(com.y()), "(xz plane, seen from -y)"},
                                    {"side: section x = " + num(com.x()), "(yz plane, seen from +x)"},
                                    {"top view", "(seen from +z)"}};
  const double ranges[3][4] = {{lo.x(), hi.x(), lo.z(), hi.z()}, {lo.y(), hi.y(), lo.z(), hi.z()}, {lo.x(), hi.x(), lo.y(), hi.y()}};
  double x = margin, views_bottom = top;
  for (int i = 0; i < 3; ++i) {
    View& v = views[i];
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
  const double width = std::max(x - gap + margin, 900.0);

  // Goal-specific figures.
  const Eigen::Vector2d com_xy(com.x(), com.y());
  const Eigen::Vector2d pivot = pivot_point(stability, com_xy);
  const std::vector<Eigen::Vector2d> shrunk = shrink_polygon(stability.support_polygon, input.margin);
  const bool stand_goal = input.goal == GoalKind::stand || input.goal == GoalKind::stand_filled;
  bool have_filled = false;
  Eigen::Vector3d filled_com = com;
  Stability filled_stability;
  if (input.goal == GoalKind::stand_filled && have_outer && void_volume > 0.0 && Pout(kMass) > P(kMass)) {
    const double vv = Pout(kMass) - P(kMass);
    const Eigen::Vector3d cout(Pout(kCx), Pout(kCy), Pout(kCz));
    const Eigen::Vector3d cvoid = (Pout(kMass) * cout - P(kMass) * com) / vv;
    const double mf = P(kMass) + input.fill_density * vv;
    filled_com = (P(kMass) * com + input.fill_density * vv * cvoid) / mf;
    filled_stability = stability;
    support_polygon_margins(stability.support_polygon, Eigen::Vector2d(filled_com.x(), filled_com.y()),
                            filled_com.z() - stability.ground_z, filled_stability);
    have_filled = true;
  }
  FloatingEquilibrium water;
  bool have_water = false, neutral = false;
  if (input.goal == GoalKind::floating && input.fluid_density > 0.0 && have_outer) {
    FloatingOptions fo;
    fo.fluid_density = input.fluid_density;
    fo.max_iterations = options.bisection_cap;
    water = floating_equilibrium(shells.outer, P(kMass), fo);
    have_water = true;
    // The float goal (eq. 9) asks for weight = buoyancy fully submerged: within the tolerance
    // verification uses (1e-3 of the mass) the fluid's surface is at or above the top, and the
    // centre of buoyancy is the outer volume's centroid.
    if (std::fabs(input.fluid_density * Pout(kMass) - P(kMass)) <= 1e-3 * P(kMass)) {
      water.status = FloatingEquilibrium::Status::floats;
      water.waterline = shells.outer.V.col(2).maxCoeff();
      water.displaced_volume = Pout(kMass);
      water.center_of_buoyancy = Eigen::Vector3d(Pout(kCx), Pout(kCy), Pout(kCz));
      neutral = true;
    } else if (water.status == FloatingEquilibrium::Status::sinks) {
      water.center_of_buoyancy = Eigen::Vector3d(Pout(kCx), Pout(kCy), Pout(kCz));
    }
  }

  Svg svg;
  std::string& out = svg.out;
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + px(width) + "\" height=\"@HEIGHT@\" viewBox=\"0 0 " +
         px(width) + " @HEIGHT@\" font-family=\"sans-serif\">\n";
  out += "<title>offsetopt preview: goal " + std::string(to_string(input.goal)) + "</title>\n";
  out += "<defs>\n";
  for (const View& v : views)
    out += "<clipPath id=\"clip-" + v.id + "\"><rect x=\"" + px(v.x) + "\" y=\"" + px(v.y) + "\" width=\"" + px(v.w) +
           "\" height=\"" + px(v.h) + "\"/></clipPath>\n";
  out += "</defs>\n";
  out += "<rect x=\"0\" y=\"0\" width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  svg.text(margin, 28, std::string("offsetopt preview: goal ") + to_string(input.goal), 16);

  const double r = options.marker_radius;
  for (int i = 0; i < 3; ++i) {
    const View& v = views[i];
    svg.text(v.x + 0.5 * v.w, v.y - 22, titles[i][0], 11, "middle");
    svg.text(v.x + 0.5 * v.w, v.y - 8, titles[i][1], 11, "middle", "#505050");
    out += "<g id=\"" + v.id + "\" data-origin-x=\"" + format_double(v.ox) + "\" data-origin-y=\"" + format_double(v.oy) +
           "\" data-scale=\"" + format_double(v.s) + "\" data-x=\"" + px(v.x) + "\" data-y=\"" + px(v.y) + "\" data-width=\"" +
           px(v.w) + "\" data-height=\"" + px(v.h) + "\" clip-path=\"url(#clip-" + v.id + ")\">\n";
    // u, v of a model point in this view.
    auto uv = [&](const Eigen::Vector3d& p) {
      return i == 0 ? Eigen::Vector2d(p.x(), p.z()) : i == 1 ? Eigen::Vector2d(p.y(), p.z()) : Eigen::Vector2d(p.x(), p.y());
    };
    auto at = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector2d q = uv(p);
      return v.map(q.x(), q.y());
    };
    if (i < 2) {
      // Ground, then the section. Loops do not cross, and a loop inside another is smaller, so
      // painting them from the largest area down nests them right: material loops (counter-
      // clockwise) in the material colour, cavity loops over them in the cavity colour, islands
      // inside a cavity over those. Each edge pixel then blends exactly the two colours that meet
      // there (filling the material with holes over the cavity would let the background bleed
      // into every edge pixel). Outlines of the material loops last.
      svg.line(v.map(v.umin, stability.ground_z), v.map(v.umax, stability.ground_z), kGround, 1.5);
      const PlaneSection section = plane_section(solid, i == 0 ? xz_plane(com.y()) : yz_plane(com.x()));
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
      // Goal extras in the sections.
      if (stand_goal) {
        const Eigen::Vector3d foot(pivot.x(), pivot.y(), stability.ground_z);
        svg.line(at(com), at(foot), kGoalMark, 1.5, "5 3");
        // The angle where the tipping direction lies mostly in this view's plane.
        const Eigen::Vector2d towards = pivot - com_xy;
        if ((i == 0) == (std::fabs(towards.x()) >= std::fabs(towards.y()))) {
          const Eigen::Vector2d label = at(foot);
          const bool right_half = label.x() > v.x + 0.5 * v.w;
          svg.text(label.x() + (right_half ? -4 : 4), label.y() - 6, "tips at " + fixed(stability.tipping_angle_deg, 1) + " deg",
                   10, right_half ? "end" : "start", kGoalMark);
        }
      }
      if (input.has_sphere && input.goal == GoalKind::roly_poly) {
        const double off = i == 0 ? com.y() - input.sphere_center.y() : com.x() - input.sphere_center.x();
        if (std::fabs(off) < input.sphere_radius) {
          const double rr = std::sqrt(input.sphere_radius * input.sphere_radius - off * off);
          const Eigen::Vector2d c = at(input.sphere_center);
          out += "<circle cx=\"" + px(c.x()) + "\" cy=\"" + px(c.y()) + "\" r=\"" + px(rr * s) + "\" fill=\"none\" stroke=\"" +
                 kGoalMark + "\" stroke-width=\"1.2\" stroke-dasharray=\"6 4\"/>\n";
        }
        svg.cross(at(input.sphere_center), r + 1.5, kGoalMark);
      }
      if (input.has_tip && input.goal == GoalKind::spin) {
        const double u = i == 0 ? input.tip.x() : input.tip.y();
        svg.line(v.map(u, v.vmin), v.map(u, v.vmax), kGoalMark, 1.5, "10 4 2 4");
        svg.cross(at(input.tip), r + 1.5, kGoalMark);
      }
      if (have_water) {
        if (water.status == FloatingEquilibrium::Status::floats)
          svg.line(v.map(v.umin, water.waterline), v.map(v.umax, water.waterline), kWater, 1.5, "8 4");
        svg.dot(at(water.center_of_buoyancy), r, "#ffffff", kWater);
      }
    } else {
      // Top view: the horizontal section through the centre of mass as a light silhouette, the
      // support polygon and the polygon shrunk by the margin.
      const PlaneSection section = plane_section(solid, xy_plane(com.z()));
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
      polygon(stability.support_polygon, "#c8e6c9", nullptr);
      polygon(shrunk, "none", "4 3");
      if (stand_goal) svg.line(at(com), v.map(pivot.x(), pivot.y()), kGoalMark, 1.5, "5 3");
      if (input.has_sphere && input.goal == GoalKind::roly_poly) svg.cross(at(input.sphere_center), r + 1.5, kGoalMark);
      if (input.has_tip && input.goal == GoalKind::spin) svg.cross(at(input.tip), r + 1.5, kGoalMark);
      if (have_water) svg.dot(at(water.center_of_buoyancy), r, "#ffffff", kWater);
    }
    for (const PreviewInput::Opening& o : input.openings) {
      svg.line(at(o.inner), at(o.outer), kPreviewOpeningColour, 2.0);
      const Eigen::Vector2d c = at(o.outer);
      out += "<circle cx=\"" + px(c.x()) + "\" cy=\"" + px(c.y()) + "\" r=\"" + px(std::max(o.radius * s, 2.0)) +
             "\" fill=\"none\" stroke=\"" + kPreviewOpeningColour + "\" stroke-width=\"2\"/>\n";
    }
    if (have_filled) svg.dot(at(filled_com), r, kWater);
    if (input.has_before_com) svg.dot(at(input.before_com), r, kPreviewComBeforeColour);
    svg.dot(at(com), r, kPreviewComAfterColour);  // last: never covered
    out += "</g>\n";
    out += "<rect x=\"" + px(v.x) + "\" y=\"" + px(v.y) + "\" width=\"" + px(v.w) + "\" height=\"" + px(v.h) +
           "\" fill=\"none\" stroke=\"#b0b0b0\" stroke-width=\"1\"/>\n";
  }

  // Scale bar: 1, 2 or 5 times a power of ten, 60 to 150 px long.
  double bar = 1.0;
  for (int i = 0; i < 400 && bar * s > 150.0; ++i) bar /= 10.0;
  for (int i = 0; i < 400 && bar * s < 60.0; ++i) bar *= 10.0;
  if (bar * s > 150.0) bar /= 2.0;
  if (bar * s > 150.0) bar /= 2.5;
  double y = views_bottom + 28;
  {
    const Eigen::Vector2d a(margin, y), b(margin + bar * s, y);
    svg.line(a, b, "#000000", 2.0);
    svg.line(a - Eigen::Vector2d(0, 5), a + Eigen::Vector2d(0, 5), "#000000", 1.5);
    svg.line(b - Eigen::Vector2d(0, 5), b + Eigen::Vector2d(0, 5), "#000000", 1.5);
    svg.text(b.x() + 8, y + 4, format_double(bar) + " input units (the mesh's units; all views at this scale)", 11);
  }
  y += 26;

  // Legend (left column) and figures (right column).
  const double legend_top = y;
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
  if (stand_goal) legend.push_back({"dash", kGoalMark, "to the tipping edge (direction it would tip)"});
  if (have_filled) legend.push_back({"dot", kWater, "centre of mass, filled"});
  if (!input.openings.empty()) legend.push_back({"ring", kPreviewOpeningColour, "opening (drain hole, channel): axis and radius"});
  if (input.goal == GoalKind::roly_poly) legend.push_back({"cross", kGoalMark, "sphere centre (dashed: its section)"});
  if (input.goal == GoalKind::spin) legend.push_back({"dash", kGoalMark, "spin axis through the tip (cross)"});
  if (have_water) {
    legend.push_back({"dash", kWater, neutral ? "waterline (at the top: fully submerged)" : "waterline"});
    legend.push_back({"ring", kWater, "centre of buoyancy"});
  }
  for (const Entry& e : legend) {
    const double sx = margin, sy = y - 9;
    if (e.kind == "fill")
      out += "<rect x=\"" + px(sx) + "\" y=\"" + px(sy) + "\" width=\"22\" height=\"11\" fill=\"" + e.colour +
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
  const double legend_bottom = y;

  std::vector<std::string> lines;
  lines.push_back("solid: volume (mass at density 1) " + num(P(kMass)) + ", " + std::to_string(shells.count) + " shell(s), " +
                  std::to_string(shells.cavities) + " cavity shell(s)");
  lines.push_back("centre of mass " + vec(com));
  if (input.has_before_com) lines.push_back("input's centre of mass " + vec(input.before_com));
  lines.push_back("void volume " + num(void_volume));
  lines.push_back("support polygon: " + std::to_string(stability.support_polygon.size()) + " corners, " +
                  std::to_string(stability.contact_vertex_count) + " contact vertices");
  lines.push_back("(ground z = " + num(stability.ground_z) + ", contact tolerance " + num(stability.ground_tol) + ")");
  if (stand_goal)
    lines.push_back("centre of mass inside it by " + num(stability.com_margin) + " (margin asked " + num(input.margin) + ")");
  std::vector<std::pair<std::string, double>> bars;
  switch (input.goal) {
    case GoalKind::stand:
    case GoalKind::stand_filled:
      lines.push_back("tipping angle " + fixed(stability.tipping_angle_deg, 2) + " deg" +
                      (stability.stands ? "" : " (falls over)") + (have_filled ? " empty" : ""));
      if (have_filled)
        lines.push_back("tipping angle " + fixed(filled_stability.tipping_angle_deg, 2) + " deg filled (density " +
                        num(input.fill_density) + "), centre of mass " + vec(filled_com));
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
      bars = {{"I_a", pi.moments(a)}, {"I_b", pi.moments(b)}, {"Izz", P(kIzz)}};
      lines.push_back("Izz " + num(P(kIzz)) + ", other principal moments " + num(pi.moments(a)) + ", " + num(pi.moments(b)) +
                      " (Izz should be the largest)");
      break;
    }
    case GoalKind::floating:
      if (have_water) {
        const double excess = input.fluid_density * Pout(kMass) - P(kMass);
        if (neutral)
          lines.push_back("fully submerged in density " + num(input.fluid_density) + ": buoyancy - weight = " + num(excess) +
                          " (" + num(100.0 * excess / P(kMass)) + "% of the weight)");
        else if (water.status == FloatingEquilibrium::Status::floats)
          lines.push_back("floats in density " + num(input.fluid_density) + ", waterline z = " + num(water.waterline));
        else
          lines.push_back("sinks in density " + num(input.fluid_density) + ": buoyancy - weight = " + num(excess));
        lines.push_back("centre of buoyancy " + vec(water.center_of_buoyancy) + "; centre of mass " +
                        num(water.center_of_buoyancy.z() - com.z()) + " below it");
      }
      break;
    case GoalKind::volume:
      lines.push_back("void volume " + num(void_volume) +
                      (input.target_volume > 0.0 ? " (target " + num(input.target_volume) + ")" : std::string()));
      break;
  }
  double ty = legend_top;
  const double column = 330.0;
  for (const std::string& line : lines) {
    svg.text(column, ty, line, 11);
    ty += 17;
  }
  if (!bars.empty()) {
    double biggest = 0.0;
    for (const auto& b : bars) biggest = std::max(biggest, b.second);
    ty += 4;
    for (const auto& b : bars) {
      const double length = biggest > 0.0 ? 200.0 * b.second / biggest : 0.0;
      svg.text(column, ty + 9, b.first, 11);
      out += "<rect x=\"" + px(column + 34) + "\" y=\"" + px(ty) + "\" width=\"" + px(length) + "\" height=\"11\" fill=\"" +
             (b.first == "Izz" ? kGoalMark : "#8aa0bd") + "\"/>\n";
      svg.text(column + 40 + length, ty + 9, num(b.second), 11);
      ty += 17;
    }
  }
  const double height = std::max(legend_bottom, ty) + margin;
  out += "</svg>\n";
  const std::string h = px(height);
  for (std::size_t at = out.find("@HEIGHT@"); at != std::string::npos; at = out.find("@HEIGHT@", at)) out.replace(at, 8, h);
  result.status = PreviewStatus::ok;
  result.svg = std::move(out);
  return result;
}

}  // namespace offsetopt
