#include "cover/planner/planner_params.hpp"

namespace cover::planner {

PlannerParams PlannerParams::load(config::YamlReader& reader) {
  PlannerParams params;
  config::load_fields(params, reader);
  params.validate();
  return params;
}

PlannerParams PlannerParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

PlannerParams PlannerParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "planner", /*required=*/false);
  return load(reader);
}

void PlannerParams::validate() const {
  const std::string ctx = "planner";
  config::check_fields(*this, ctx);
  // The defaults within the limits' bounds (max_evaluations >= 1 is always a stopping rule).
  config::check(default_vmax_m_s <= max_limit_m_s, ctx + ".default_vmax_m_s",
                "exceeds max_limit_m_s");
  config::check(default_amax_m_s2 <= max_limit_m_s2, ctx + ".default_amax_m_s2",
                "exceeds max_limit_m_s2");
}

}  // namespace cover::planner
