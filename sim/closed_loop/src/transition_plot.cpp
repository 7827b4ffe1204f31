#include "cover/sim/transition_plot.hpp"

#include <array>

#include "cover/sim/svg_plot.hpp"
#include "cover/vocabulary/stage.hpp"

namespace cover::sim {

TransitionTrace transition_trace(const ClosedLoopResult& result, std::size_t index,
                                 const std::string& label) {
  TransitionTrace trace;
  trace.label = label;
  if (index >= result.transitions.size()) return trace;
  const TransitionRecord& record = result.transitions[index];
  const auto& target_path = result.ugv_paths.at(static_cast<std::size_t>(record.to_ugv));
  const int transition = static_cast<int>(model::Stage::Transition);
  // The recorder keeps the UAV's and the UGVs' points on the same steps: the index-th run
  // of transition-stage points is this stage, and the UGV points at those indices its target's.
  std::size_t block = 0;
  bool inside = false;
  for (std::size_t i = 0; i < result.uav_path.size(); ++i) {
    const bool in_transition = result.uav_path[i].stage_code == transition;
    if (inside && !in_transition) ++block;
    inside = in_transition;
    if (!in_transition || block != index) continue;
    trace.uav_m.push_back(result.uav_path[i].uav_world_m);
    if (i < target_path.size()) trace.target_m.push_back(target_path[i]);
  }
  // The stage starts where the UAV was when it began (the recorder's start point).
  if (!trace.uav_m.empty()) trace.uav_m.insert(trace.uav_m.begin(), record.start_world_m.head<2>());
  trace.bound_m = record.bound.path_m;
  return trace;
}

bool write_transitions_plot(const std::vector<TransitionTrace>& traces, const std::string& title,
                            const std::string& path) {
  // Colours for up to ten methods (matplotlib's tab10 without the stage plots' red).
  static const std::array<const char*, 9> kColours = {"#1f77b4", "#ff7f0e", "#2ca02c",
                                                      "#9467bd", "#8c564b", "#e377c2",
                                                      "#7f7f7f", "#bcbd22", "#17becf"};
  SvgPlot plot(title);
  bool first_bound = true;
  for (std::size_t i = 0; i < traces.size(); ++i) {
    const TransitionTrace& t = traces[i];
    const std::string colour = kColours[i % kColours.size()];
    plot.add_path(t.target_m, {colour, 1.0, true, t.label + ": target UGV meanwhile"});
    plot.add_path(t.bound_m, {"#555555", 0.8, true, first_bound ? "shortest path (bound)" : ""});
    first_bound = first_bound && t.bound_m.empty();
    plot.add_path(t.uav_m, {colour, 2.5, false, t.label + ": UAV"});
    if (!t.uav_m.empty()) plot.add_marker(t.uav_m.back(), t.label + " arrives", colour);
  }
  if (!traces.empty() && !traces.front().uav_m.empty()) {
    plot.add_marker(traces.front().uav_m.front(), "start", "#000000");
  }
  return plot.write_file(path);
}

}  // namespace cover::sim
