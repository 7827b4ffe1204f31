#pragma once

#include <vector>

#include "cover/sampc/horizon_cost.hpp"
#include "cover/sampc/sampc_params.hpp"
#include "cover/vocabulary/state.hpp"
#include "cover/vocabulary/ugv_motion.hpp"

namespace cover::sampc {

// An independent solve of SAMPC's optimal control problem, to check the SQP (tests and
// `cover-bench mpc`), never used in the loop: the same cost in single-shooting form (the
// inputs are the only unknowns, the states a model roll-out from x0) minimised by NLopt's
// L-BFGS (LD_LBFGS, bound-constrained) under the input bounds, with the exact gradient by the
// adjoint recursion.

// Cost of the inputs u[0..N-1] from x0; fills `gradient` (size N) when given.
double single_shooting_cost(const SampcParams& params, const HorizonCost& cost,
                            const model::UavState& x0, const model::UgvMotion& ugv,
                            const std::vector<model::Input>& inputs,
                            std::vector<model::Input>* gradient = nullptr);

struct ReferenceSolution {
  std::vector<model::Input> inputs;
  double cost = 0.0;
  int evaluations = 0;
  bool ok = false;  // NLopt reported success (or a round-off limited stop)
};

// Minimises from `initial_inputs` (e.g. all hover).
ReferenceSolution solve_reference(const SampcParams& params, const HorizonCost& cost,
                                  const model::UavState& x0, const model::UgvMotion& ugv,
                                  const std::vector<model::Input>& initial_inputs);

}  // namespace cover::sampc
