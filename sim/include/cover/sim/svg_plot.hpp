#pragma once

#include <Eigen/Core>
#include <iosfwd>
#include <string>
#include <type_traits>
#include <vector>

namespace cover::sim {

struct SvgStyle {
  std::string colour = "#000000";
  double width_px = 2.0;
  bool dashed = false;
  std::string legend;  // empty: not listed in the legend
};

// A top view (world x right, world y up, equal scale) of world-frame paths for the
// benchmarks: UAV paths coloured by stage like the paper's Fig. 7 (green initial, red
// transition, blue final), UGV paths in black/grey, axes in metres, legend and title.
class SvgPlot {
 public:
  explicit SvgPlot(std::string title, int width_px = 900, int height_px = 760);

  void add_path(const std::vector<Eigen::Vector2d>& points_m, const SvgStyle& style);

  // A UAV path whose stage changes along it. `stages[i]` is the stage of `points_m[i]`;
  // any enum whose values are 0 = initial, 1 = transition, 2 = final (cover::model::Stage).
  template <typename StageEnum>
  void add_staged_path(const std::vector<Eigen::Vector2d>& points_m,
                       const std::vector<StageEnum>& stages) {
    std::vector<int> codes;
    codes.reserve(stages.size());
    for (const auto stage : stages) codes.push_back(static_cast<int>(stage));
    add_staged_path_codes(points_m, codes);
  }
  void add_staged_path_codes(const std::vector<Eigen::Vector2d>& points_m,
                             const std::vector<int>& stage_codes);

  // UGV k's path: black, dark grey, light grey, ... (the paper's Fig. 16 convention).
  void add_ugv_path(const std::vector<Eigen::Vector2d>& points_m, int ugv_index,
                    const std::string& name);

  // A labelled dot (e.g. "release", "landing").
  void add_marker(const Eigen::Vector2d& point_m, const std::string& label,
                  const std::string& colour = "#ff7f0e");

  static SvgStyle stage_style(int stage_code);

  std::string render() const;
  // Returns false if the file cannot be written.
  bool write_file(const std::string& path) const;

 private:
  struct Path {
    std::vector<Eigen::Vector2d> points;
    SvgStyle style;
  };
  struct Marker {
    Eigen::Vector2d point;
    std::string label;
    std::string colour;
  };

  struct Layout;  // svg_plot.cpp
  // render()'s parts, in the order they are drawn.
  void padded_bounds(Eigen::Vector2d& lo, Eigen::Vector2d& hi) const;
  std::vector<const SvgStyle*> legend_entries() const;
  Layout make_layout(const std::vector<const SvgStyle*>& entries) const;
  void write_header(std::ostream& svg, const Layout& layout) const;
  static void write_grid(std::ostream& svg, const Layout& layout);
  static void write_frame(std::ostream& svg, const Layout& layout);
  void write_paths(std::ostream& svg, const Layout& layout) const;
  void write_markers(std::ostream& svg, const Layout& layout) const;
  static void write_legend(std::ostream& svg, const Layout& layout,
                           const std::vector<const SvgStyle*>& entries);

  std::string title_;
  int width_px_;
  int height_px_;
  std::vector<Path> paths_;
  std::vector<Marker> markers_;
};

}  // namespace cover::sim
