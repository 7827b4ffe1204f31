#pragma once

#include <Eigen/Core>
#include <memory>

#include "cover/sampc/horizon_cost.hpp"
#include "cover/sampc/horizon_reference.hpp"
#include "cover/sampc/sampc_params.hpp"
#include "cover/vocabulary/solve_status.hpp"
#include "cover/vocabulary/state.hpp"

namespace cover::sampc {

struct SampcOutput {
  // [F (m/s^2), wx, wy, wz (rad/s)]: always finite and within the configured bounds; the
  // hover input [g, 0, 0, 0] when is_error(status).
  Eigen::Vector4d command = model::hover_input();
  SolveStatus status = SolveStatus::Ok;
  const char* reason = "";   // static string explaining a non-Ok status
  int iterations = 0;        // SQP iterations of this call
  int qp_iterations = 0;     // Riccati passes, summed over the SQP iterations
  double cost = 0.0;         // OCP cost of the returned plan (at the last linearisation)
  double prepare_us = 0.0;   // time of the preparation phase this command used
  double feedback_us = 0.0;  // time from the measurement to the command
};

// SAMPC, the stage-adaptive nonlinear MPC of sec. 4.3 (eq. 24) on the 10-state UAV model
// with the UGV motion as a parameter. Multiple shooting over N RK4 intervals, Gauss-Newton
// real-time iteration: one QP per control period, warm-started by shifting the previous
// solution by control_period_s, solved by RiccatiQp (active set on the input boxes).
//
// Real-time use at 100 Hz (the RTI split):
//     sampc.prepare(predicted);            // linearise + factorise, before the measurement
//     ... measurement arrives ...
//     out = sampc.feedback(measured);      // forward pass only (unless bounds change)
// or simply `out = sampc.solve(measured)`. References and weights are built in prepare()
// from `predicted` (its uav_state should be the expected measurement, e.g. the last one);
// feedback() re-prepares with its own input if none was prepared or the stage changed.
// After a frame switch call reset_frame(): the inputs (thrust, body rates) are body-frame
// quantities, so the previous input sequence stays the initial guess and only the states
// are re-rolled from the new frame's measurement; for switch_smoothing_s node 0 also pays
// for moving away from the previous command. reset() forgets everything: the next call
// starts from a hover roll-out and spends cold_start_iterations SQP iterations on it;
// after reset_frame() the next call spends frame_switch_iterations. No heap
// allocation after construction; no exceptions thrown by prepare/feedback/solve.
class Sampc {
 public:
  explicit Sampc(const SampcParams& params);
  ~Sampc();
  Sampc(Sampc&&) noexcept;
  Sampc& operator=(Sampc&&) noexcept;
  Sampc(const Sampc&) = delete;
  Sampc& operator=(const Sampc&) = delete;

  void prepare(const SampcInput& predicted_input);
  SampcOutput feedback(const SampcInput& input);
  SampcOutput solve(const SampcInput& input);
  void reset();
  void reset_frame();
  // Switches the method (a task's process may ask for its own) without touching the plan:
  // the next prepare builds that method's cost. Allocation-free, for the control loop.
  void set_mode(Mode mode);

  // A factorisation waits for its feedback (prepare() ran, and no reset, frame switch or
  // mode switch since): feedback() then runs the forward pass only.
  bool prepared() const;
  // Runs the prepared QP once on the predicted state and discards the result, so that the
  // factorisation and the feedback's code are in the caches when the measurement arrives:
  // a realtime host calls it just before. The next feedback() is the same with or without
  // it (the QP starts each solve afresh; a factorisation depends on its active set only).
  // No-op when nothing is prepared.
  void rehearse_feedback();
  // The state expected `dt_s` after the last feedback's measurement: the plan's node 0
  // flown for dt_s on the command handed out (RK4 at the UGV motion of that feedback). What
  // the RTI preparation linearises at before the next measurement arrives.
  model::UavState predicted_state(double dt_s) const;

  const SampcParams& params() const;
  // The cost (references, weights) of the last preparation: for logging and tests.
  const HorizonCost& horizon_cost() const;
  // The current plan: predicted UAV state at node k (0..N) and input k (0..N-1).
  model::UavState planned_state(int k) const;
  model::Input planned_input(int k) const;

 private:
  struct Workspace;
  std::unique_ptr<Workspace> ws_;
};

}  // namespace cover::sampc
