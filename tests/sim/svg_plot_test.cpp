#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "cover/sim/svg_plot.hpp"

namespace cover::sim {
namespace {

enum class TestStage : std::uint8_t { Initial = 0, Transition = 1, Final = 2 };

int count(const std::string& text, const std::string& needle) {
  int n = 0;
  for (auto pos = text.find(needle); pos != std::string::npos; pos = text.find(needle, pos + 1))
    ++n;
  return n;
}

TEST(SvgPlot, DrawsStagedUavPathUgvPathsLegendAndTitle) {
  SvgPlot plot("Cyclic transitions <v=0.5>");
  std::vector<Eigen::Vector2d> uav;
  std::vector<TestStage> stages;
  for (int i = 0; i < 30; ++i) {
    uav.emplace_back(0.1 * i, std::sin(0.1 * i));
    stages.push_back(i < 10 ? TestStage::Initial
                            : (i < 20 ? TestStage::Transition : TestStage::Final));
  }
  plot.add_staged_path(uav, stages);
  std::vector<Eigen::Vector2d> ugv;
  for (int i = 0; i < 50; ++i) ugv.emplace_back(2 * std::cos(0.13 * i), 2 * std::sin(0.13 * i));
  plot.add_ugv_path(ugv, 0, "G0");
  plot.add_marker({1.0, 0.5}, "release");
  const std::string svg = plot.render();
  EXPECT_NE(svg.find("Cyclic transitions &lt;v=0.5&gt;"), std::string::npos);  // escaped title
  EXPECT_EQ(count(svg, "<polyline"), 4);              // three stage runs + one UGV
  EXPECT_NE(svg.find("#2ca02c"), std::string::npos);  // green initial
  EXPECT_NE(svg.find("#d62728"), std::string::npos);  // red transition
  EXPECT_NE(svg.find("#1f77b4"), std::string::npos);  // blue final
  EXPECT_NE(svg.find("UAV, transition stage"), std::string::npos);
  EXPECT_NE(svg.find(">G0<"), std::string::npos);
  EXPECT_NE(svg.find("world x [m]"), std::string::npos);
  EXPECT_NE(svg.find("release"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

TEST(SvgPlot, SkipsNonFinitePointsAndRendersEmptyPlots) {
  SvgPlot plot("empty");
  plot.add_path({Eigen::Vector2d(NAN, 0.0)}, SvgStyle{});
  const std::string svg = plot.render();
  EXPECT_EQ(count(svg, "<polyline"), 0);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

}  // namespace
}  // namespace cover::sim
