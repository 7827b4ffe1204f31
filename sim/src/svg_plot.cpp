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

// Maps metres to pixels with one scale for both axes (a top view must not distort).
struct Viewport {
  double min_x, min_y, scale, origin_x_px, origin_y_px;
  double px(double x) const { return origin_x_px + (x - min_x) * scale; }
  double py(double y) const { return origin_y_px - (y - min_y) * scale; }
};

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

std::string SvgPlot::render() const {
  Eigen::Vector2d lo(-1.0, -1.0), hi(1.0, 1.0);
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

  // Legend: one entry per distinct label, in order of first appearance.
  std::vector<const SvgStyle*> entries;
  for (const auto& path : paths_) {
    if (path.style.legend.empty()) continue;
    const bool seen = std::any_of(entries.begin(), entries.end(), [&](const SvgStyle* s) {
      return s->legend == path.style.legend;
    });
    if (!seen) entries.push_back(&path.style);
  }

  // Equal scale on both axes; the picture is then cropped to the data's aspect ratio
  // (keeping room for the legend) instead of leaving a band of white.
  std::size_t longest_label = 0;
  for (const SvgStyle* style : entries)
    longest_label = std::max(longest_label, style->legend.size());
  const double margin_right_px =
      std::max(kMinMarginRightPx, 60.0 + kLegendCharPx * static_cast<double>(longest_label));
  const double plot_w = width_px_ - kMarginLeftPx - margin_right_px;
  const double max_plot_h = height_px_ - kMarginTopPx - kMarginBottomPx;
  const double scale = std::min(plot_w / (hi.x() - lo.x()), max_plot_h / (hi.y() - lo.y()));
  const double legend_h = 20.0 * static_cast<double>(entries.size()) + 20.0;
  const double plot_h = std::max((hi.y() - lo.y()) * scale, std::min(legend_h, max_plot_h));
  const int height_px = static_cast<int>(std::ceil(kMarginTopPx + plot_h + kMarginBottomPx));
  const Viewport view{lo.x(), lo.y(), scale, kMarginLeftPx,
                      kMarginTopPx + (plot_h + (hi.y() - lo.y()) * scale) / 2};
  const double right_px = view.px(hi.x());
  const double top_px = view.py(hi.y());

  std::ostringstream svg;
  svg.precision(7);
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_px_ << "\" height=\""
      << height_px << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"" << width_px_ / 2 << "\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">"
      << escape_xml(title_) << "</text>\n";

  // Grid, ticks and axis labels (metres).
  const double step = nice_tick_step(std::max(hi.x() - lo.x(), hi.y() - lo.y()), 8);
  svg << "<g stroke=\"#e5e5e5\" stroke-width=\"1\">\n";
  for (double x = std::ceil(lo.x() / step) * step; x <= hi.x(); x += step) {
    svg << "<line x1=\"" << view.px(x) << "\" y1=\"" << view.py(lo.y()) << "\" x2=\"" << view.px(x)
        << "\" y2=\"" << top_px << "\"/>\n";
  }
  for (double y = std::ceil(lo.y() / step) * step; y <= hi.y(); y += step) {
    svg << "<line x1=\"" << view.px(lo.x()) << "\" y1=\"" << view.py(y) << "\" x2=\"" << right_px
        << "\" y2=\"" << view.py(y) << "\"/>\n";
  }
  svg << "</g>\n<g fill=\"#333\">\n";
  for (double x = std::ceil(lo.x() / step) * step; x <= hi.x(); x += step) {
    svg << "<text x=\"" << view.px(x) << "\" y=\"" << view.py(lo.y()) + 16
        << "\" text-anchor=\"middle\">" << format_number(x) << "</text>\n";
  }
  for (double y = std::ceil(lo.y() / step) * step; y <= hi.y(); y += step) {
    svg << "<text x=\"" << view.px(lo.x()) - 6 << "\" y=\"" << view.py(y) + 4
        << "\" text-anchor=\"end\">" << format_number(y) << "</text>\n";
  }
  svg << "</g>\n";
  svg << "<rect x=\"" << view.px(lo.x()) << "\" y=\"" << top_px << "\" width=\""
      << right_px - view.px(lo.x()) << "\" height=\"" << view.py(lo.y()) - top_px
      << "\" fill=\"none\" stroke=\"#333\"/>\n";
  svg << "<text x=\"" << (view.px(lo.x()) + right_px) / 2 << "\" y=\"" << view.py(lo.y()) + 38
      << "\" text-anchor=\"middle\">world x [m]</text>\n";
  const double y_label_px = (top_px + view.py(lo.y())) / 2;
  svg << "<text x=\"20\" y=\"" << y_label_px
      << "\" text-anchor=\"middle\" transform=\"rotate(-90 20 " << y_label_px
      << ")\">world y [m]</text>\n";

  for (const auto& path : paths_) {
    svg << "<polyline fill=\"none\" stroke=\"" << path.style.colour << "\" stroke-width=\""
        << path.style.width_px << "\"" << (path.style.dashed ? " stroke-dasharray=\"6 4\"" : "")
        << " points=\"";
    for (const auto& p : path.points) svg << view.px(p.x()) << ',' << view.py(p.y()) << ' ';
    svg << "\"/>\n";
  }
  for (const auto& marker : markers_) {
    svg << "<circle cx=\"" << view.px(marker.point.x()) << "\" cy=\"" << view.py(marker.point.y())
        << "\" r=\"4\" fill=\"" << marker.colour << "\"/>\n";
    svg << "<text x=\"" << view.px(marker.point.x()) + 6 << "\" y=\""
        << view.py(marker.point.y()) - 6 << "\">" << escape_xml(marker.label) << "</text>\n";
  }

  const double legend_x = right_px + 16;
  double legend_y = kMarginTopPx + 10;
  for (const SvgStyle* style : entries) {
    svg << "<line x1=\"" << legend_x << "\" y1=\"" << legend_y << "\" x2=\"" << legend_x + 24
        << "\" y2=\"" << legend_y << "\" stroke=\"" << style->colour << "\" stroke-width=\"3\""
        << (style->dashed ? " stroke-dasharray=\"6 4\"" : "") << "/>\n";
    svg << "<text x=\"" << legend_x + 30 << "\" y=\"" << legend_y + 4 << "\">"
        << escape_xml(style->legend) << "</text>\n";
    legend_y += 20;
  }
  svg << "</svg>\n";
  return svg.str();
}

bool SvgPlot::write_file(const std::string& path) const {
  std::ofstream file(path);
  if (!file) return false;
  file << render();
  return static_cast<bool>(file);
}

}  // namespace cover::sim
