#include "cover/sim/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace cover::sim {

namespace {

constexpr double kMarginLeftPx = 70.0;
constexpr double kMinMarginRightPx = 200.0;  // room for the legend
constexpr double kLegendCharPx = 7.0;        // mean glyph width at font-size 12, generous
constexpr double kMarginTopPx = 50.0;
constexpr double kMarginBottomPx = 60.0;

std::string escape_xml(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// 1, 2 or 5 times a power of ten, giving about `target` ticks over `span`.
double nice_tick_step(double span, int target) {
  const double raw = span / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double factor : {1.0, 2.0, 5.0}) {
    if (factor * magnitude >= raw) return factor * magnitude;
  }
  return 10.0 * magnitude;
}

std::string format_number(double value) {
  std::ostringstream out;
  out.precision(6);
  out << (std::abs(value) < 1e-9 ? 0.0 : value);
  return out.str();
}

}  // namespace

SvgPlot::SvgPlot(std::string title, int width_px, int height_px)
    : title_(std::move(title)), width_px_(width_px), height_px_(height_px) {}

void SvgPlot::add_path(const std::vector<Eigen::Vector2d>& points_m, const SvgStyle& style) {
  std::vector<Eigen::Vector2d> finite;
  finite.reserve(points_m.size());
  for (const auto& p : points_m) {
    if (p.allFinite()) finite.push_back(p);
  }
  if (!finite.empty()) paths_.push_back({std::move(finite), style});
}

SvgStyle SvgPlot::stage_style(int stage_code) {
  switch (stage_code) {
    case 0:
      return {"#2ca02c", 2.0, false, "UAV, initial stage"};
    case 1:
      return {"#d62728", 2.0, false, "UAV, transition stage"};
    case 2:
      return {"#1f77b4", 2.0, false, "UAV, final stage"};
    default:
      return {"#7f7f7f", 1.5, true, "UAV, no stage"};
  }
}

void SvgPlot::add_staged_path_codes(const std::vector<Eigen::Vector2d>& points_m,
                                    const std::vector<int>& stage_codes) {
  const std::size_t n = std::min(points_m.size(), stage_codes.size());
  std::size_t run_start = 0;
  for (std::size_t i = 1; i <= n; ++i) {
    if (i < n && stage_codes[i] == stage_codes[run_start]) continue;
    // Each run also takes the next run's first point so the coloured pieces join up.
    const std::size_t run_end = std::min(i + 1, n);
    add_path({points_m.begin() + run_start, points_m.begin() + run_end},
             stage_style(stage_codes[run_start]));
    run_start = i;
  }
}

void SvgPlot::add_ugv_path(const std::vector<Eigen::Vector2d>& points_m, int ugv_index,
                           const std::string& name) {
  static const char* const kGreys[] = {"#000000", "#666666", "#aaaaaa", "#cccccc"};
  const char* colour = kGreys[std::clamp(ugv_index, 0, 3)];
  add_path(points_m, {colour, 1.5, false, name});
}

void SvgPlot::add_marker(const Eigen::Vector2d& point_m, const std::string& label,
                         const std::string& colour) {
  if (point_m.allFinite()) markers_.push_back({point_m, label, colour});
}

// Where the picture's parts go: the data's padded bounds in metres, one scale for both
// axes (a top view must not distort) and the plot box in pixels.
struct SvgPlot::Layout {
  Eigen::Vector2d lo, hi;                       // data bounds with a margin, m
  double scale = 1.0;                           // px per m
  double origin_x_px = 0.0, origin_y_px = 0.0;  // where (lo.x, lo.y) lands
  int height_px = 0;                            // the picture cropped to the data's aspect
  double px(double x) const { return origin_x_px + (x - lo.x()) * scale; }
  double py(double y) const { return origin_y_px - (y - lo.y()) * scale; }
  double left_px() const { return px(lo.x()); }
  double right_px() const { return px(hi.x()); }
  double top_px() const { return py(hi.y()); }
  double bottom_px() const { return py(lo.y()); }
};

std::string SvgPlot::render() const {
  const std::vector<const SvgStyle*> entries = legend_entries();
  const Layout layout = make_layout(entries);
  std::ostringstream svg;
  svg.precision(7);
  write_header(svg, layout);
  write_grid(svg, layout);
  write_frame(svg, layout);
  write_paths(svg, layout);
  write_markers(svg, layout);
  write_legend(svg, layout, entries);
  svg << "</svg>\n";
  return svg.str();
}

void SvgPlot::padded_bounds(Eigen::Vector2d& lo, Eigen::Vector2d& hi) const {
  lo = Eigen::Vector2d(-1.0, -1.0);
  hi = Eigen::Vector2d(1.0, 1.0);
  bool any = false;
  auto extend = [&](const Eigen::Vector2d& p) {
    lo = any ? lo.cwiseMin(p) : p;
    hi = any ? hi.cwiseMax(p) : p;
    any = true;
  };
  for (const auto& path : paths_) {
    for (const auto& p : path.points) extend(p);
  }
  for (const auto& marker : markers_) extend(marker.point);
  const Eigen::Vector2d pad = ((hi - lo) * 0.05).cwiseMax(0.5);
  lo -= pad;
  hi += pad;
}

// One entry per distinct label, in order of first appearance.
std::vector<const SvgStyle*> SvgPlot::legend_entries() const {
  std::vector<const SvgStyle*> entries;
  for (const auto& path : paths_) {
    if (path.style.legend.empty()) continue;
    const bool seen = std::any_of(entries.begin(), entries.end(), [&](const SvgStyle* s) {
      return s->legend == path.style.legend;
    });
    if (!seen) entries.push_back(&path.style);
  }
  return entries;
}

// Equal scale on both axes; the picture is then cropped to the data's aspect ratio
// (keeping room for the legend) instead of leaving a band of white.
SvgPlot::Layout SvgPlot::make_layout(const std::vector<const SvgStyle*>& entries) const {
  Layout layout;
  padded_bounds(layout.lo, layout.hi);
  const Eigen::Vector2d span = layout.hi - layout.lo;
  std::size_t longest_label = 0;
  for (const SvgStyle* style : entries)
    longest_label = std::max(longest_label, style->legend.size());
  const double margin_right_px =
      std::max(kMinMarginRightPx, 60.0 + kLegendCharPx * static_cast<double>(longest_label));
  const double plot_w = width_px_ - kMarginLeftPx - margin_right_px;
  const double max_plot_h = height_px_ - kMarginTopPx - kMarginBottomPx;
  layout.scale = std::min(plot_w / span.x(), max_plot_h / span.y());
  const double legend_h = 20.0 * static_cast<double>(entries.size()) + 20.0;
  const double plot_h = std::max(span.y() * layout.scale, std::min(legend_h, max_plot_h));
  layout.height_px = static_cast<int>(std::ceil(kMarginTopPx + plot_h + kMarginBottomPx));
  layout.origin_x_px = kMarginLeftPx;
  layout.origin_y_px = kMarginTopPx + (plot_h + span.y() * layout.scale) / 2;
  return layout;
}

void SvgPlot::write_header(std::ostream& svg, const Layout& layout) const {
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_px_ << "\" height=\""
      << layout.height_px << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"" << width_px_ / 2 << "\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">"
      << escape_xml(title_) << "</text>\n";
}

// Grid lines and tick labels (metres), the same step on both axes.
void SvgPlot::write_grid(std::ostream& svg, const Layout& layout) {
  const Eigen::Vector2d& lo = layout.lo;
  const Eigen::Vector2d& hi = layout.hi;
  const double step = nice_tick_step(std::max(hi.x() - lo.x(), hi.y() - lo.y()), 8);
  svg << "<g stroke=\"#e5e5e5\" stroke-width=\"1\">\n";
  for (double x = std::ceil(lo.x() / step) * step; x <= hi.x(); x += step) {
    svg << "<line x1=\"" << layout.px(x) << "\" y1=\"" << layout.bottom_px() << "\" x2=\""
        << layout.px(x) << "\" y2=\"" << layout.top_px() << "\"/>\n";
  }
  for (double y = std::ceil(lo.y() / step) * step; y <= hi.y(); y += step) {
    svg << "<line x1=\"" << layout.left_px() << "\" y1=\"" << layout.py(y) << "\" x2=\""
        << layout.right_px() << "\" y2=\"" << layout.py(y) << "\"/>\n";
  }
  svg << "</g>\n<g fill=\"#333\">\n";
  for (double x = std::ceil(lo.x() / step) * step; x <= hi.x(); x += step) {
    svg << "<text x=\"" << layout.px(x) << "\" y=\"" << layout.bottom_px() + 16
        << "\" text-anchor=\"middle\">" << format_number(x) << "</text>\n";
  }
  for (double y = std::ceil(lo.y() / step) * step; y <= hi.y(); y += step) {
    svg << "<text x=\"" << layout.left_px() - 6 << "\" y=\"" << layout.py(y) + 4
        << "\" text-anchor=\"end\">" << format_number(y) << "</text>\n";
  }
  svg << "</g>\n";
}

// The plot box and the axis labels.
void SvgPlot::write_frame(std::ostream& svg, const Layout& layout) {
  svg << "<rect x=\"" << layout.left_px() << "\" y=\"" << layout.top_px() << "\" width=\""
      << layout.right_px() - layout.left_px() << "\" height=\""
      << layout.bottom_px() - layout.top_px() << "\" fill=\"none\" stroke=\"#333\"/>\n";
  svg << "<text x=\"" << (layout.left_px() + layout.right_px()) / 2 << "\" y=\""
      << layout.bottom_px() + 38 << "\" text-anchor=\"middle\">world x [m]</text>\n";
  const double y_label_px = (layout.top_px() + layout.bottom_px()) / 2;
  svg << "<text x=\"20\" y=\"" << y_label_px
      << "\" text-anchor=\"middle\" transform=\"rotate(-90 20 " << y_label_px
      << ")\">world y [m]</text>\n";
}

void SvgPlot::write_paths(std::ostream& svg, const Layout& layout) const {
  for (const auto& path : paths_) {
    svg << "<polyline fill=\"none\" stroke=\"" << path.style.colour << "\" stroke-width=\""
        << path.style.width_px << "\"" << (path.style.dashed ? " stroke-dasharray=\"6 4\"" : "")
        << " points=\"";
    for (const auto& p : path.points) svg << layout.px(p.x()) << ',' << layout.py(p.y()) << ' ';
    svg << "\"/>\n";
  }
}

void SvgPlot::write_markers(std::ostream& svg, const Layout& layout) const {
  for (const auto& marker : markers_) {
    const double x_px = layout.px(marker.point.x());
    const double y_px = layout.py(marker.point.y());
    svg << "<circle cx=\"" << x_px << "\" cy=\"" << y_px << "\" r=\"4\" fill=\"" << marker.colour
        << "\"/>\n";
    svg << "<text x=\"" << x_px + 6 << "\" y=\"" << y_px - 6 << "\">" << escape_xml(marker.label)
        << "</text>\n";
  }
}

// Right of the plot box, one line per entry.
void SvgPlot::write_legend(std::ostream& svg, const Layout& layout,
                           const std::vector<const SvgStyle*>& entries) {
  const double legend_x = layout.right_px() + 16;
  double legend_y = kMarginTopPx + 10;
  for (const SvgStyle* style : entries) {
    svg << "<line x1=\"" << legend_x << "\" y1=\"" << legend_y << "\" x2=\"" << legend_x + 24
        << "\" y2=\"" << legend_y << "\" stroke=\"" << style->colour << "\" stroke-width=\"3\""
        << (style->dashed ? " stroke-dasharray=\"6 4\"" : "") << "/>\n";
    svg << "<text x=\"" << legend_x + 30 << "\" y=\"" << legend_y + 4 << "\">"
        << escape_xml(style->legend) << "</text>\n";
    legend_y += 20;
  }
}

bool SvgPlot::write_file(const std::string& path) const {
  std::ofstream file(path);
  if (!file) return false;
  file << render();
  return static_cast<bool>(file);
}

}  // namespace cover::sim
