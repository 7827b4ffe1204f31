#pragma once

#include <string>

#include "cover/msg/types.hpp"
#include "fuzz_input.hpp"

namespace cover::fuzz {

// Task ids as hostile stations send them: mostly valid, sometimes anything at all.
inline std::string task_id(FuzzInput& in) {
  switch (in.byte() % 4) {
    case 0:
      return in.text(80);
    case 1:
      return std::string(in.range(0, 70), 't');  // around the length limit
    default:
      return "t" + std::to_string(in.byte() % 8);
  }
}

inline msg::Vector3 point(FuzzInput& in) {
  if (in.byte() % 3 == 0) return {in.real(), in.real(), in.real()};
  return {static_cast<double>(in.range(-25, 25)), static_cast<double>(in.range(-25, 25)),
          static_cast<double>(in.range(-1, 12))};
}

inline msg::TransitionTask transition_task(FuzzInput& in) {
  msg::TransitionTask t;
  t.task_id = task_id(in);
  t.uav_id = in.byte() % 8 ? in.byte() % 3 : in.raw<std::uint32_t>();
  const std::size_t count = in.byte() % 5;
  for (std::size_t i = 0; i < count && !in.empty(); ++i) {
    msg::TransitionProcess p;
    p.from_ugv = in.byte() % 8 ? in.byte() % 4 : in.raw<std::uint32_t>();
    p.to_ugv = in.byte() % 8 ? in.byte() % 4 : in.raw<std::uint32_t>();
    p.initial_point_m = point(in);
    p.transition_point_m = point(in);
    p.final_point_m = point(in);
    p.final_action = static_cast<msg::FinalAction>(in.byte() % 5);
    p.vmax_m_s = in.byte() % 3 ? in.range(0, 40) * 0.1 : in.real();
    p.amax_m_s2 = in.byte() % 3 ? in.range(0, 60) * 0.1 : in.real();
    p.method = in.byte() % 4 ? "" : in.text(16);
    t.processes.push_back(p);
  }
  return t;
}

}  // namespace cover::fuzz
