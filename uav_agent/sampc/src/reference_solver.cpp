#include "cover/sampc/reference_solver.hpp"

#include <nlopt.hpp>

#include "cover/model/dynamics.hpp"

namespace cover::sampc {

double single_shooting_cost(const SampcParams& params, const HorizonCost& cost,
                            const model::UavState& x0, const model::UgvMotion& ugv,
                            const std::vector<model::Input>& inputs,
                            std::vector<model::Input>* gradient) {
  const int n = params.horizon_steps;
  std::vector<model::UavState> x(n + 1);
  std::vector<model::UavStateMatrix> a(n);
  std::vector<model::UavInputMatrix> b(n);
  x[0] = x0;
  double total = 0.0;
  for (int k = 0; k < n; ++k) {
    const model::UgvMotion ugv_k = ugv.advanced(k * params.step_s);
    x[k + 1] = model::uav_rk4_step(x[k], inputs[k], ugv_k, params.step_s, a[k], b[k]);
  }
  if (gradient == nullptr) {
    for (int k = 0; k < n; ++k) total += cost.nodes[k].evaluate(x[k], inputs[k]);
    return total + cost.nodes[n].evaluate(x[n], model::hover_input());
  }
  // Adjoint: lambda_k = dJ/dx_k, swept backwards through the exact step Jacobians.
  gradient->assign(n, model::Input::Zero());
  model::UavState lambda = model::UavState::Zero();
  total += cost.nodes[n].evaluate(x[n], model::hover_input(), &lambda);
  for (int k = n - 1; k >= 0; --k) {
    model::UavState grad_x = model::UavState::Zero();
    model::Input grad_u = model::Input::Zero();
    total += cost.nodes[k].evaluate(x[k], inputs[k], &grad_x, &grad_u);
    (*gradient)[k] = grad_u + b[k].transpose() * lambda;
    lambda = grad_x + a[k].transpose() * lambda;
  }
  return total;
}

namespace {

// The 4 inputs of node k inside NLopt's flat decision vector.
Eigen::Map<model::Input> node_inputs(std::vector<double>& z, int k) {
  return Eigen::Map<model::Input>(z.data() + 4 * k);
}

struct Problem {
  const SampcParams& params;
  const HorizonCost& cost;
  const model::UavState& x0;
  const model::UgvMotion& ugv;
  int evaluations = 0;
};

double objective(const std::vector<double>& z, std::vector<double>& grad, void* data) {
  auto& problem = *static_cast<Problem*>(data);
  const int n = problem.params.horizon_steps;
  std::vector<model::Input> inputs(n);
  for (int k = 0; k < n; ++k) inputs[k] = Eigen::Map<const model::Input>(&z[4 * k]);
  std::vector<model::Input> gradient;
  const double value = single_shooting_cost(problem.params, problem.cost, problem.x0, problem.ugv,
                                            inputs, grad.empty() ? nullptr : &gradient);
  for (int k = 0; k < n && !grad.empty(); ++k) {
    node_inputs(grad, k) = gradient[k];
  }
  ++problem.evaluations;
  return value;
}

}  // namespace

ReferenceSolution solve_reference(const SampcParams& params, const HorizonCost& cost,
                                  const model::UavState& x0, const model::UgvMotion& ugv,
                                  const std::vector<model::Input>& initial_inputs) {
  const int n = params.horizon_steps;
  const unsigned dim = 4 * n;
  nlopt::opt opt(nlopt::LD_LBFGS, dim);
  std::vector<double> lower(dim), upper(dim), z(dim);
  for (int k = 0; k < n; ++k) {
    node_inputs(lower, k) = params.input_lower_bound();
    node_inputs(upper, k) = params.input_upper_bound();
    node_inputs(z, k) =
        initial_inputs[k].cwiseMax(params.input_lower_bound()).cwiseMin(params.input_upper_bound());
  }
  Problem problem{params, cost, x0, ugv};
  opt.set_lower_bounds(lower);
  opt.set_upper_bounds(upper);
  opt.set_min_objective(&objective, &problem);
  opt.set_ftol_rel(1e-14);
  opt.set_xtol_rel(1e-12);
  opt.set_maxeval(20000);
  opt.set_vector_storage(40);

  ReferenceSolution solution;
  double value = 0.0;
  try {
    const nlopt::result result = opt.optimize(z, value);
    solution.ok = result > 0;
  } catch (const nlopt::roundoff_limited&) {
    solution.ok = true;  // converged as far as floating point allows
  } catch (const std::exception&) {
    solution.ok = false;
  }
  solution.inputs.resize(n);
  for (int k = 0; k < n; ++k) solution.inputs[k] = node_inputs(z, k);
  solution.cost = single_shooting_cost(params, cost, x0, ugv, solution.inputs);
  solution.evaluations = problem.evaluations;
  return solution;
}

}  // namespace cover::sampc
