// DaeIntegrator's events: where an element switches, the modes change, the coordinates are
// re-chosen and IDA restarts (the contract is in dae_integrator.hpp).
#include "runtime/dae/dae_integrator.hpp"

#include "runtime/dae/dae_integrator_detail.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace rheo::runtime {

// Re-chooses the coordinates for the current modes, mapping s and w from the positions and the
// rates of the rate edges under the previous coordinates, and sets which way each root
// function may cross next (a stuck slider's force or an open gap's elongation either way; a
// slipping slider's rate or a closed gap's force only back towards zero).
void DaeIntegrator::rechoose_coordinates(double t) {
  const DriveState drive = drive_at(t);
  edge_forces(drive, y_.data(), yp_.data(), force_.data());  // rate_: every rate edge's, old coordinates
  if (!start_rates_.empty()) {
    std::copy(start_rates_.begin(), start_rates_.end(), rate_.begin());
    start_rates_.clear();
  }
  kinematics_ = ModeKinematics::make(graph_, modes_);
  const int s0 = layout_.rate_coordinate(0), w0 = layout_.inerter_velocity(0);
  std::fill(y_.begin() + s0, y_.begin() + layout_.bouc_wen_state(0), 0.0);
  std::fill(yp_.begin() + s0, yp_.begin() + layout_.bouc_wen_state(0), 0.0);
  for (int j = 0; j < kinematics_.coordinates; ++j) {
    const int rate_index = at(kinematics_.coordinate_rate, j);
    const Edge& edge = at(graph_.edges, at(graph_.rate_edges, rate_index));
    at(y_, s0 + j) = elongation(y_.data(), drive, edge);
    at(yp_, s0 + j) = at(rate_, rate_index);
    const int slot = at(kinematics_.velocity_slot, j);
    if (slot >= 0) at(y_, w0 + slot) = at(rate_, rate_index);
  }
  for (int l = 0; l < layout_.switch_forces; ++l) {
    const int mode = at(modes_, l);
    at(root_direction_, 2 * l) = mode == 0 ? 1 : -mode;
    at(root_direction_, 2 * l + 1) = mode == 0 ? -1 : 0;
  }
  set_bouc_wen_root_directions();
  if (root_count() > 0) sundials::check_ida(IDASetRootDirection(solver_->ida.get(), root_direction_.data()), "IDASetRootDirection");
}

// After IDACalcIC: a gap closed under tension opens, and of the sliders stuck beyond their yield
// forces the one furthest beyond (largest |lambda| / fy) slips; the others wait for the next
// consistent state. Sliders in series carry one force: were all those beyond yield to slip at
// once (a friction element and a weaker slider in series, both beyond yield in the linearised
// start), the chain would need two forces, and IDACalcIC finds no consistent state. A stuck
// slider counts as beyond yield only while its force is still beyond it after 1e-3 HORIZON
// (rates_ahead): one just stuck where its slip rate crossed zero carries fy plus its dashpot's
// force at the rate the root left, up to the positions' tolerance times a stiff spring's
// stiffness (8e-5 N, 8e-6 fy, behind a 10627 N/mm spring, differential seed 41, model 71), and
// slipping it again would restart it at that rate's wrong sign. A closed gap under tension
// likewise opens only if still under tension then: one just closed on its stop may carry a
// rounding residue of tension, and opened beyond its stop it has no root left to close it
// (differential seed 53, model 106). True when no mode had to change.
bool DaeIntegrator::switch_inconsistent_modes(double t, double horizon) {
  bool consistent = true;
  int furthest = -1;
  double furthest_ratio = 1.0 + 0.5 * kSlack;
  bool ahead = false;  // rates_ahead_ holds this state's rates
  for (int l = 0; l < layout_.switch_forces; ++l) {
    const Edge& edge = switch_edge(l);
    std::int8_t& mode = at(modes_, l);
    const int i = layout_.switch_force(l);
    const double lambda = at(y_, i);
    const auto ratio = [&edge](double force) { return force > 0.0 ? force / edge.p[0] : -force / edge.p[1]; };
    if (edge.kind == EdgeKind::slider && mode == 0 && ratio(lambda) > furthest_ratio) {
      if (!ahead) ahead = rates_ahead(t, horizon);
      const double later = ahead ? lambda + 1e-3 * horizon * at(rates_ahead_, i) : lambda;
      if (later * lambda > 0.0 && ratio(later) > 1.0 + 0.5 * kSlack) furthest = l, furthest_ratio = ratio(lambda);
    } else if (edge.kind == EdgeKind::gap && mode != 0 && lambda * mode < -1e-12 * options_.force_scale) {
      if (!ahead) ahead = rates_ahead(t, horizon);
      const double later = ahead ? lambda + 1e-3 * horizon * at(rates_ahead_, i) : lambda;
      if (later * mode >= -1e-12 * options_.force_scale) continue;
      mode = 0;
      consistent = false;
    }
  }
  if (furthest >= 0) {
    at(modes_, furthest) = at(y_, layout_.switch_force(furthest)) > 0.0 ? 1 : -1;
    consistent = false;
  }
  return consistent;
}

bool DaeIntegrator::rates_ahead(double t, double horizon) {
  std::copy(yp_.begin(), yp_.end(), rates_ahead_.begin());
  const bool converged = try_euler_rates(t, 1e-3 * horizon);
  std::swap(yp_, rates_ahead_);  // yp_ as IDACalcIC left it; rates_ahead_ the step's
  return converged;
}

// IDACalcIC makes only the differential rates consistent; a slipping slider's root reads its
// elongation's rate, a difference of node positions' rates, which stay as they were before the
// restart. Where the slider stopped at the event (two sliders whose slip rates cross zero
// together: the root of one is found, and the other's rate, a stale one, has already crossed)
// the root is missed and the slider slips the wrong way until the next drive sample (differential
// seed 41, model 71: 0.45 of max |F| off at the sample after a reversal).
bool DaeIntegrator::stick_stopping_sliders(double t, double horizon) {
  bool slipping = false;
  for (int l = 0; l < layout_.switch_forces; ++l) slipping |= switch_edge(l).kind == EdgeKind::slider && at(modes_, l) != 0;
  if (!slipping || !rates_ahead(t, horizon)) return true;
  const DriveState drive = drive_at(t);
  bool stopped = false;
  for (int l = 0; l < layout_.switch_forces; ++l) {
    const Edge& edge = switch_edge(l);
    std::int8_t& mode = at(modes_, l);
    if (edge.kind != EdgeKind::slider || mode == 0 || elongation_rate(rates_ahead_.data(), drive, edge) * mode >= 0.0) continue;
    mode = 0;
    at(held_, l) = elongation(y_.data(), drive, edge);
    stopped = true;
  }
  if (stopped) return false;
  for (int i = 0; i < layout_.size(); ++i)
    if (!layout_.differential(i)) at(yp_, i) = at(rates_ahead_, i);
  std::copy(yp_.begin(), yp_.end(), N_VGetArrayPointer(solver_->yp.get()));
  sundials::check_ida(IDAReInit(solver_->ida.get(), t, solver_->y.get(), solver_->yp.get()), "IDAReInit");
  return true;
}

// Re-initialises IDA at t (with new coordinates when the modes changed) and makes the state
// consistent; modes found inconsistent are switched and the restart repeated.
void DaeIntegrator::restart(double t, bool modes_changed) {
  if (!solver_) {
    kinematics_ = ModeKinematics::make(graph_, modes_);
    return;
  }
  void* mem = solver_->ida.get();
  for (int attempt = 0;; ++attempt) {
    if (modes_changed) rechoose_coordinates(t), modes_changed_at_ = t;
    const double horizon = time_horizon();
    if (nested_bouc_wen_) bouc_wen_consistent_rates(t, horizon);  // no sliders or gaps: y is consistent
    std::copy(y_.begin(), y_.end(), N_VGetArrayPointer(solver_->y.get()));
    std::copy(yp_.begin(), yp_.end(), N_VGetArrayPointer(solver_->yp.get()));
    collect_statistics();  // IDAReInit zeroes IDA's counters
    sundials::check_ida(IDAReInit(mem, t, solver_->y.get(), solver_->yp.get()), "IDAReInit");
    first_step_ = true;
    if (nested_bouc_wen_) return;
    int flag = IDACalcIC(mem, IDA_YA_YDP_INIT, t + horizon);
    if ((flag == IDA_LINESEARCH_FAIL || flag == IDA_CONV_FAIL) && !error_) {
      // IDACalcIC's line search judges a step by the Newton step that the matrix of the start
      // predicts from the new point. From rest a quadratic dashpot's tangent there is cq v_eps,
      // far below what its rate reaches, so every full step looks like no progress (two quadratic
      // dashpots in series, whose rates the drive sets at once, failed at t = 0; a quadratic
      // dashpot and a dashpot behind a gap that closes, IDA_CONV_FAIL). Plain Newton overshoots
      // and comes back down the convex law; it is tried once from the same start.
      std::copy(y_.begin(), y_.end(), N_VGetArrayPointer(solver_->y.get()));
      std::copy(yp_.begin(), yp_.end(), N_VGetArrayPointer(solver_->yp.get()));
      sundials::check_ida(IDAReInit(mem, t, solver_->y.get(), solver_->yp.get()), "IDAReInit");
      sundials::check_ida(IDASetLineSearchOffIC(mem, SUNTRUE), "IDASetLineSearchOffIC");
      flag = IDACalcIC(mem, IDA_YA_YDP_INIT, t + horizon);
      sundials::check_ida(IDASetLineSearchOffIC(mem, SUNFALSE), "IDASetLineSearchOffIC");
    }
    if ((flag == IDA_LINESEARCH_FAIL || flag == IDA_CONV_FAIL) && !error_) {
      // Where a switch makes rate elements share the drive's rate at once (a quadratic dashpot
      // and a dashpot behind a gap that closes, or beside a slider that starts to slip), neither
      // finds the rates from the stale ones. They are started from those of a backward-Euler step
      // of 1e-3 of IDACalcIC's horizon (euler_rates: Newton with the matrix recomputed at every
      // iterate; the step makes the algebraic unknowns consistent at its end, so its differential
      // rates are those of a consistent state to O(h)).
      euler_rates(t, 1e-3 * horizon);
      for (int i = 0; i < layout_.size(); ++i)
        if (!layout_.differential(i)) at(yp_, i) = 0.0;
      std::copy(y_.begin(), y_.end(), N_VGetArrayPointer(solver_->y.get()));
      std::copy(yp_.begin(), yp_.end(), N_VGetArrayPointer(solver_->yp.get()));
      sundials::check_ida(IDAReInit(mem, t, solver_->y.get(), solver_->yp.get()), "IDAReInit");
      flag = IDACalcIC(mem, IDA_YA_YDP_INIT, t + horizon);
    }
    if (flag < 0) {
      if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
      sundials::check_ida(
          flag, "IDACalcIC",
          fmt::format("no consistent state of model '{}' at t = {:g} s after an element switched; {}", graph_.model, t, last_message_));
    }
    sundials::check_ida(IDAGetConsistentIC(mem, solver_->y.get(), solver_->yp.get()), "IDAGetConsistentIC");
    copy_from_solver();
    if (switch_inconsistent_modes(t, horizon) && stick_stopping_sliders(t, horizon)) return;
    if (attempt > 2 * layout_.switch_forces + 2)
      throw NumericalError(fmt::format("model '{}': the sliders and gaps find no consistent state at t = {:g} s", graph_.model, t));
    modes_changed = true;
  }
}

std::vector<double> DaeIntegrator::settling_state() const {
  if (nested_bouc_wen_) return {};  // its restart takes the state as consistent (no IDACalcIC)
  std::vector<double> out(y_.begin(), y_.begin() + layout_.positions);
  out.insert(out.end(), y_.begin() + layout_.bouc_wen_state(0), y_.begin() + layout_.size());
  return out;
}

void DaeIntegrator::move_to(const std::vector<double>& settling) {
  if (settling.size() != static_cast<std::size_t>(layout_.positions + layout_.bouc_wen_states))
    throw std::logic_error("DaeIntegrator::move_to: not a settling_state()");
  std::copy(settling.begin(), settling.begin() + layout_.positions, y_.begin());
  std::copy(settling.begin() + layout_.positions, settling.end(), y_.begin() + layout_.bouc_wen_state(0));
  const DriveState drive = drive_at(time_);
  for (int l = 0; l < layout_.switch_forces; ++l) {
    const Edge& edge = switch_edge(l);
    if (edge.kind == EdgeKind::slider && at(modes_, l) == 0) at(held_, l) = elongation(y_.data(), drive, edge);
  }
  restart(time_, true);
}

// y_ and yp_ from IDA's vectors.
void DaeIntegrator::copy_from_solver() {
  const double* y = N_VGetArrayPointer(solver_->y.get());
  const double* yp = N_VGetArrayPointer(solver_->yp.get());
  std::copy(y, y + layout_.size(), y_.begin());
  std::copy(yp, yp + layout_.size(), yp_.begin());
}

bool DaeIntegrator::switch_modes(double t, double t_stop, const std::vector<int>& found) {
  const DriveState drive = drive_at(t);
  const double horizon = time_horizon(), h = 1e-3 * horizon;
  // Within h of the last switch, and with room for a backward-Euler step of h before the stop.
  const bool transient = t < modes_changed_at_ + h && t + 2.0 * h <= t_stop;
  bool ahead = false, switched = false;  // rates_ahead_ holds this state's rates
  for (int l = 0; l < layout_.switch_forces; ++l) {
    if (!at(found, 2 * l) && !at(found, 2 * l + 1)) continue;
    const Edge& edge = switch_edge(l);
    std::int8_t& mode = at(modes_, l);
    double& held = at(held_, l);
    if (edge.kind == EdgeKind::slider && mode != 0 && transient) {
      if (!ahead) ahead = rates_ahead(t, horizon);
      if (ahead && elongation_rate(rates_ahead_.data(), drive, edge) * mode > 0.0) continue;  // slips on
    }
    switched = true;
    if (edge.kind == EdgeKind::slider) {
      if (mode == 0) {
        mode = at(y_, layout_.switch_force(l)) > 0.0 ? 1 : -1;
      } else {
        mode = 0;
        held = elongation(y_.data(), drive, edge);
      }
    } else if (mode == 0) {
      mode = at(found, 2 * l) ? 1 : -1;
      held = gap_stop(edge, mode);
    } else {
      mode = 0;
    }
  }
  ++events_;
  if (switched) {
    restart(t, true);
    return true;
  }
  for (int i = 0; i < layout_.size(); ++i) at(y_, i) += h * at(rates_ahead_, i);  // rates_ahead: that step's rates
  yp_ = rates_ahead_;
  time_ = t + h;
  restart(time_, false);
  return false;
}

void DaeIntegrator::resume() {
  collect_statistics();  // IDAReInit zeroes IDA's counters
  std::copy(y_.begin(), y_.end(), N_VGetArrayPointer(solver_->y.get()));
  std::copy(yp_.begin(), yp_.end(), N_VGetArrayPointer(solver_->yp.get()));
  sundials::check_ida(IDAReInit(solver_->ida.get(), time_, solver_->y.get(), solver_->yp.get()), "IDAReInit");
  first_step_ = true;
}

double DaeIntegrator::solve_to(double t_stop) {
  void* mem = solver_->ida.get();
  if (t_stop - time_ <= 4.0 * std::numeric_limits<double>::epsilon() * (std::abs(time_) + std::abs(t_stop))) {
    // Within IDA's round-off of the present (IDASolve: "tout too close to t0", as after an event
    // a few ulps before a sample): the state moves on by its rates.
    for (int i = 0; i < layout_.size(); ++i) at(y_, i) += (t_stop - time_) * at(yp_, i);
    time_ = t_stop;
    return time_;
  }
  sundials::check_ida(IDASetStopTime(mem, t_stop), "IDASetStopTime");
  double t_reached = time_;
  int flag = IDA_SUCCESS;
  if (first_step_) {
    // The first step after a restart leaves the algebraic unknowns out of IDA's error test:
    // IDACalcIC makes only the differential rates consistent, and the algebraic ones (a stuck
    // slider's force rising at k du/dt from a drive rate that just jumped) are stale, so the
    // predictor's error would be compared to their absolute tolerance alone (a stiff spring
    // before a weak slider failed IDA's error test down to h = 4e-12 s). The step is still
    // controlled by the differential unknowns, which fix the algebraic ones (index 1). Not with
    // Bouc-Wen states: their law reads the positions' rates, so positions are not algebraic
    // there (a bouc_wen at a drive reversal then failed IDA's corrector).
    first_step_ = false;
    const bool suppress = layout_.bouc_wen_states == 0;
    if (suppress) sundials::check_ida(IDASetSuppressAlg(mem, SUNTRUE), "IDASetSuppressAlg");
    flag = IDASolve(mem, t_stop, &t_reached, solver_->y.get(), solver_->yp.get(), IDA_ONE_STEP);
    if (suppress) sundials::check_ida(IDASetSuppressAlg(mem, SUNFALSE), "IDASetSuppressAlg");
  }
  if (flag == IDA_SUCCESS && t_reached < t_stop) flag = IDASolve(mem, t_stop, &t_reached, solver_->y.get(), solver_->yp.get(), IDA_NORMAL);
  if (flag == IDA_CONV_FAIL && !error_) {
    // The corrector failed with jacobian()'s tangents. A quadratic dashpot behind a spring whose
    // rate starts at 0 (from rest, or at a reversal) reaches v ~ sqrt(k u' t / cq): IDA's error
    // test wants steps so short that its Newton matrix, the tangent cq v_eps of the predictor at
    // v = 0, is far below the law's slope at the step's rate, and the corrector overshoots by that
    // ratio at every h (a 16090 N/mm spring and cq = 2.5e-4 N s^2/mm^2 at 30 mm/s). One
    // backward-Euler step of 1e-6 of the drive's time scale, by Newton with the matrix
    // recomputed at each iterate (euler_step), moves the rate off 0, and IDA restarts there from
    // tangents that hold along its steps.
    copy_from_solver();
    time_ = t_reached;
    const double horizon = time_horizon();
    euler_step(time_, std::min(1e-3 * horizon, 0.5 * (t_stop - time_)));
    restart(time_, false);
    first_step_ = false;
    sundials::check_ida(IDASetStopTime(mem, t_stop), "IDASetStopTime");
    flag = IDASolve(mem, t_stop, &t_reached, solver_->y.get(), solver_->yp.get(), IDA_NORMAL);
  }
  if (flag == IDA_CONV_FAIL && !error_) {
    // The corrector failed with jacobian()'s tangents: restart from the last step reached with
    // IDA's own Newton matrix, whose slope of a rate law is a secant over a rate increment of
    // c_j times the position's. From rest a quadratic dashpot's tangent cq v_eps is far below
    // what its rate reaches within a step, and Newton from the tangent overshoots by that ratio
    // (a 4163 N/mm spring in series at 30 mm/s failed at t = 1e-9 s); the steeper secant climbs to
    // the rate from below. At a reversal the tangents are what works (reproducer 04).
    copy_from_solver();
    time_ = t_reached;
    use_own_jacobian(false);
    restart(time_, false);
    first_step_ = false;
    sundials::check_ida(IDASetStopTime(mem, t_stop), "IDASetStopTime");
    flag = IDASolve(mem, t_stop, &t_reached, solver_->y.get(), solver_->yp.get(), IDA_NORMAL);
    use_own_jacobian(true);
  }
  if (flag < 0) {
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
    sundials::check_ida(flag, "IDASolve", fmt::format("model '{}' at t = {:g} s: {}", graph_.model, t_reached, last_message_));
  }
  copy_from_solver();
  time_ = t_reached;
  if (flag == IDA_ROOT_RETURN) {
    sundials::check_ida(IDAGetRootInfo(mem, roots_found_.data()), "IDAGetRootInfo");
    if (nested_bouc_wen_) {
      reverse_bouc_wen_directions(roots_found_);  // no sliders or gaps: Bouc-Wen roots only
      // IDA located the root inside its last step, taken on the old branch up to a sample past
      // the root. On a sine it starts again at the root from the state and rates it interpolated
      // there, which the new branch shares (the branches meet at the root, dae_bouc_wen.cpp); no
      // rates are solved anew, so the roots do not chatter. (Without, a bouc_wen saturated in a
      // chain with two springs, differential seed 2026's model 87 at 2 Hz, whose old branch holds
      // z, was 1.8e-3 deg off fixed steps' phase at 2048 samples a cycle.) Not on a history:
      // restarted at every root, the differential test's bouc_wen histories ran for minutes.
      if (drive_.kind == DriveSignal::Kind::sine) resume();
    } else {
      switch_modes(t_reached, t_stop, roots_found_);
    }
  }
  return t_reached;
}

// A slipping slider whose rate changes sign exactly at a sample of a piecewise-linear drive has
// no root inside a step to find (the drive rate, and often the slip rate, are constant between
// samples). A probe step of 1e-6 of the next interval shows the new sign; a reversed slider sticks
// at the sample and the integration restarts there.
void DaeIntegrator::stick_reversed_sliders() {
  bool slipping = false;
  for (int l = 0; l < layout_.switch_forces; ++l) slipping |= switch_edge(l).kind == EdgeKind::slider && at(modes_, l) != 0;
  if (!slipping) return;
  const double t0 = time_;
  y_saved_ = y_;  // same sizes: copies without allocation
  yp_saved_ = yp_;
  const long events_before = events_;
  const double interval = drive_.samples->time[segment_ + 1] - drive_.samples->time[segment_];
  solve_to(t0 + 1e-6 * interval);
  if (events_ != events_before) return;  // an event inside the probe step was handled there
  std::vector<double>& g = root_values_;
  roots(time_, y_.data(), yp_.data(), g.data());
  bool reversed = false;
  for (int l = 0; l < layout_.switch_forces; ++l) {
    const std::int8_t mode = at(modes_, l);
    if (switch_edge(l).kind != EdgeKind::slider || mode == 0 || at(g, 2 * l) * mode >= 0.0) continue;
    at(modes_, l) = 0;
    at(held_, l) = 0.0;
    reversed = true;
  }
  if (!reversed) return;
  y_ = y_saved_;
  yp_ = yp_saved_;
  time_ = t0;
  const DriveState drive = drive_at(t0);
  for (int l = 0; l < layout_.switch_forces; ++l)
    if (switch_edge(l).kind == EdgeKind::slider && at(modes_, l) == 0) at(held_, l) = elongation(y_.data(), drive, switch_edge(l));
  ++events_;
  restart(t0, true);
}

}  // namespace rheo::runtime
