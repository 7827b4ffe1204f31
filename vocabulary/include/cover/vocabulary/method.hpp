#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace cover::sampc {

// The paper's comparisons (docs/model.md, "Baselines"):
//  - Cover:    stage-adaptive: xy-z-ref at the transition stage, x-y-z-ref otherwise.
//  - NoRefVxy: as Cover with Q0v_x = Q0v_y = 0 ("w.o. Ref. Vxy").
//  - ConiMpc:  x-y-z-ref at every stage (the prior method).
// Beyond the paper:
//  - Intercept: as Cover, but the transition stage's velocity reference aims at where the
//    target UGV will be (intercept_velocity.hpp), eq. 30 when that is not predictable.
// Apart from SAMPC (its own small target): a task names its method, and whatever reads a
// task (the task manager, the ground station) checks the name without linking the solver.
enum class Mode { Cover, NoRefVxy, ConiMpc, Intercept };

const char* to_string(Mode mode);
// "cover" | "no-ref-vxy" | "coni-mpc" | "intercept" (to_string's names); nullopt otherwise.
std::optional<Mode> parse_mode(std::string_view name);
inline constexpr Mode kModes[] = {Mode::Cover, Mode::NoRefVxy, Mode::ConiMpc, Mode::Intercept};
// kModes' names joined by `separator` ("cover | no-ref-vxy | ..."): for errors and help.
std::string mode_names(std::string_view separator);

}  // namespace cover::sampc
