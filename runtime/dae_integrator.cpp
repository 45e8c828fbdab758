#include "runtime/dae_integrator.hpp"

#include "runtime/leaf_kernels.hpp"
#include "runtime/sundials_owners.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rheo::runtime {

void capture_ida_message(int, const char*, const char* function, char* message, void* user_data) {
  auto* self = static_cast<DaeIntegrator*>(user_data);
  self->last_message_ = fmt::format("{}: {}", function ? function : "IDA", message ? message : "");
}

namespace {

// A stuck slider slips when |F| exceeds fy (1 + kSlack) and stays stuck after a velocity reversal
// while |F| <= fy (1 + kSlack/2); the margin keeps the switch from chattering on roundoff at the
// instant of reversal, where |F| = fy. A gap closes when |e| exceeds w/2 (1 + kGapSlack).
constexpr double kSlack = 1e-6;
constexpr double kGapSlack = 1e-9;

// C trampolines: exceptions never cross the C library; they are stored and rethrown after the
// call returns (a negative return makes IDA stop with IDA_RES_FAIL / IDA_RTFUNC_FAIL).
struct Callbacks {
  static int residual(realtype t, N_Vector y, N_Vector yp, N_Vector r, void* data) noexcept;
  static int roots(realtype t, N_Vector y, N_Vector yp, realtype* g, void* data) noexcept;
};

}  // namespace

struct DaeIntegrator::Solver {
  sundials::Context context;
  sundials::Vector y, yp, id, tolerance;
  sundials::Matrix jacobian;
  sundials::LinearSolver linear_solver;
  sundials::IdaMemory ida;
};

namespace {
DaeIntegrator* self(void* data) { return static_cast<DaeIntegrator*>(data); }
}  // namespace

int Callbacks::residual(realtype t, N_Vector y, N_Vector yp, N_Vector r, void* data) noexcept {
  try {
    self(data)->residual(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), N_VGetArrayPointer(r));
    return 0;
  } catch (...) {
    self(data)->store_error(std::current_exception());
    return -1;
  }
}

int Callbacks::roots(realtype t, N_Vector y, N_Vector yp, realtype* g, void* data) noexcept {
  try {
    self(data)->roots(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), g);
    return 0;
  } catch (...) {
    self(data)->store_error(std::current_exception());
    return -1;
  }
}

DaeIntegrator::DaeIntegrator(const DaeGraph& graph, const DaeOptions& options) : graph_(graph), options_(options) {
  nx_ = graph.internal_nodes;
  nl_ = static_cast<int>(graph.switch_edges.size());
  ns_ = static_cast<int>(graph.rate_edges.size());
  nw_ = 0;
  for (int e : graph.rate_edges) nw_ += graph.edges[static_cast<std::size_t>(e)].kind == EdgeKind::inerter ? 1 : 0;
  nz_ = static_cast<int>(graph.bouc_wen_edges.size());
  n_ = nx_ + nl_ + ns_ + nw_ + nz_;
  const auto ne = graph.edges.size();
  rate_of_edge_.assign(ne, -1);
  switch_of_edge_.assign(ne, -1);
  bouc_wen_of_edge_.assign(ne, -1);
  for (std::size_t i = 0; i < graph.rate_edges.size(); ++i) rate_of_edge_[static_cast<std::size_t>(graph.rate_edges[i])] = static_cast<int>(i);
  for (std::size_t i = 0; i < graph.switch_edges.size(); ++i) switch_of_edge_[static_cast<std::size_t>(graph.switch_edges[i])] = static_cast<int>(i);
  for (std::size_t i = 0; i < graph.bouc_wen_edges.size(); ++i) bouc_wen_of_edge_[static_cast<std::size_t>(graph.bouc_wen_edges[i])] = static_cast<int>(i);
  rate_.assign(static_cast<std::size_t>(ns_), 0.0);
  acceleration_.assign(static_cast<std::size_t>(ns_), 0.0);
  force_.assign(ne, 0.0);
  y_.assign(static_cast<std::size_t>(n_), 0.0);
  yp_ = y_;
  y_saved_ = y_;
  yp_saved_ = y_;
  root_values_.assign(static_cast<std::size_t>(2 * nl_), 0.0);
  if (n_ == 0) return;  // purely algebraic: forces follow the drive directly

  using namespace sundials;
  solver_ = std::make_unique<Solver>();
  SUNContext ctx = nullptr;
  check_sundials(SUNContext_Create(nullptr, &ctx), "SUNContext_Create");
  solver_->context.reset(ctx);
  solver_->y.reset(owned(N_VNew_Serial(n_, ctx), "N_VNew_Serial"));
  solver_->yp.reset(owned(N_VNew_Serial(n_, ctx), "N_VNew_Serial"));
  solver_->id.reset(owned(N_VNew_Serial(n_, ctx), "N_VNew_Serial"));
  solver_->tolerance.reset(owned(N_VNew_Serial(n_, ctx), "N_VNew_Serial"));
  N_VConst(0.0, solver_->y.get());
  N_VConst(0.0, solver_->yp.get());
  double* id = N_VGetArrayPointer(solver_->id.get());
  double* atol = N_VGetArrayPointer(solver_->tolerance.get());
  const double rtol = options_.relative_tolerance;
  for (int i = 0; i < n_; ++i) {
    const bool differential = i >= nx_ + nl_;
    id[i] = differential ? 1.0 : 0.0;
    const double scale = i < nx_ ? options_.length_scale
                         : i < nx_ + nl_ ? options_.force_scale
                         : i < nx_ + nl_ + ns_ ? options_.length_scale
                         : i < nx_ + nl_ + ns_ + nw_ ? options_.velocity_scale
                                                     : 1.0;
    atol[i] = rtol * scale;
  }
  solver_->ida.reset(owned(IDACreate(ctx), "IDACreate"));
  void* mem = solver_->ida.get();
  check_ida(IDASetErrHandlerFn(mem, capture_ida_message, this), "IDASetErrHandlerFn");
  check_ida(IDAInit(mem, Callbacks::residual, 0.0, solver_->y.get(), solver_->yp.get()), "IDAInit");
  check_ida(IDASVtolerances(mem, rtol, solver_->tolerance.get()), "IDASVtolerances");
  check_ida(IDASetUserData(mem, this), "IDASetUserData");
  check_ida(IDASetId(mem, solver_->id.get()), "IDASetId");
  check_ida(IDASetMaxNumSteps(mem, options_.max_steps), "IDASetMaxNumSteps");
  solver_->jacobian.reset(owned(SUNDenseMatrix(n_, n_, ctx), "SUNDenseMatrix"));
  solver_->linear_solver.reset(owned(SUNLinSol_Dense(solver_->y.get(), solver_->jacobian.get(), ctx), "SUNLinSol_Dense"));
  check_ida(IDASetLinearSolver(mem, solver_->linear_solver.get(), solver_->jacobian.get()), "IDASetLinearSolver");
  check_ida(IDASetNonlinConvCoef(mem, options_.newton_tolerance), "IDASetNonlinConvCoef");
  if (nl_ > 0) {
    check_ida(IDARootInit(mem, 2 * nl_, Callbacks::roots), "IDARootInit");
    check_ida(IDASetNoInactiveRootWarn(mem), "IDASetNoInactiveRootWarn");
  }
}

DaeIntegrator::~DaeIntegrator() = default;

DaeIntegrator::DriveState DaeIntegrator::drive_at(double t) const {
  if (drive_.kind == DriveSignal::Kind::sine) {
    const double s = std::sin(drive_.omega * t), c = std::cos(drive_.omega * t);
    const double a = drive_.amplitude, w = drive_.omega;
    return {a * s, a * w * c, -a * w * w * s};
  }
  const Drive& d = *drive_.samples;
  const std::size_t k = std::min(segment_, d.time.size() - 2);
  const double du = (d.displacement[k + 1] - d.displacement[k]) / (d.time[k + 1] - d.time[k]);
  return {d.displacement[k] + du * (t - d.time[k]), du, 0.0};
}

double DaeIntegrator::elongation(const double* y, const DriveState& drive, const Edge& edge) {
  auto position = [&](int node) { return node >= 0 ? y[node] : node == kTerminal ? drive.u : 0.0; };
  return position(edge.a) - position(edge.b);
}

double DaeIntegrator::elongation_rate(const double* yp, const DriveState& drive, const Edge& edge) {
  auto velocity = [&](int node) { return node >= 0 ? yp[node] : node == kTerminal ? drive.du : 0.0; };
  return velocity(edge.a) - velocity(edge.b);
}

void DaeIntegrator::edge_forces(const DriveState& drive, const double* y, const double* yp, double* force) const {
  const double* s_rate = yp + nx_ + nl_;
  const double* w_rate = yp + nx_ + nl_ + ns_;
  const int q = kinematics_.coordinates;
  for (int i = 0; i < ns_; ++i) {
    const double* alpha = kinematics_.alpha.data() + static_cast<std::size_t>(i) * static_cast<std::size_t>(q);
    double rate = kinematics_.beta[static_cast<std::size_t>(i)] * drive.du;
    double acceleration = kinematics_.beta[static_cast<std::size_t>(i)] * drive.ddu;
    for (int j = 0; j < q; ++j) {
      rate += alpha[j] * s_rate[j];
      const int slot = kinematics_.velocity_slot[static_cast<std::size_t>(j)];
      if (slot >= 0) acceleration += alpha[j] * w_rate[slot];
    }
    rate_[static_cast<std::size_t>(i)] = rate;
    acceleration_[static_cast<std::size_t>(i)] = acceleration;
  }
  for (std::size_t i = 0; i < graph_.edges.size(); ++i) {
    const Edge& edge = graph_.edges[i];
    const double e = elongation(y, drive, edge);
    const int rate_index = rate_of_edge_[i];
    switch (edge.kind) {
      case EdgeKind::spring: force[i] = edge.p[0] * e; break;
      case EdgeKind::yeoh: force[i] = YeohLaw{edge.p[0], edge.p[1], edge.p[2]}.force(e); break;
      case EdgeKind::dashpot: force[i] = edge.p[0] * rate_[static_cast<std::size_t>(rate_index)]; break;
      case EdgeKind::quadratic_dashpot: {
        const double v = rate_[static_cast<std::size_t>(rate_index)];
        force[i] = edge.p[0] * v * std::sqrt(v * v + kQuadraticDashpotVelocityEps * kQuadraticDashpotVelocityEps);
        break;
      }
      case EdgeKind::inerter: force[i] = edge.p[0] * acceleration_[static_cast<std::size_t>(rate_index)]; break;
      case EdgeKind::bouc_wen: force[i] = edge.p[2] * y[nx_ + nl_ + ns_ + nw_ + bouc_wen_of_edge_[i]]; break;
      case EdgeKind::slider:
      case EdgeKind::gap: force[i] = y[nx_ + switch_of_edge_[i]]; break;
    }
  }
}

double DaeIntegrator::terminal_force(const double* force) const {
  double f = 0.0;
  for (std::size_t i = 0; i < graph_.edges.size(); ++i) {
    if (graph_.edges[i].a == kTerminal) f += force[i];
    if (graph_.edges[i].b == kTerminal) f -= force[i];
  }
  return f;
}

void DaeIntegrator::residual(double t, const double* y, const double* yp, double* r) {
  const DriveState drive = drive_at(t);
  edge_forces(drive, y, yp, force_.data());
  std::fill(r, r + nx_, 0.0);
  for (std::size_t i = 0; i < graph_.edges.size(); ++i) {
    const Edge& edge = graph_.edges[i];
    if (edge.a >= 0) r[edge.a] -= force_[i];
    if (edge.b >= 0) r[edge.b] += force_[i];
  }
  for (int l = 0; l < nl_; ++l) {
    const Edge& edge = graph_.edges[static_cast<std::size_t>(graph_.switch_edges[static_cast<std::size_t>(l)])];
    const std::int8_t mode = modes_[static_cast<std::size_t>(l)];
    const double lambda = y[nx_ + l];
    if (is_rigid(edge, mode)) r[nx_ + l] = elongation(y, drive, edge) - held_[static_cast<std::size_t>(l)];
    else if (edge.kind == EdgeKind::slider) r[nx_ + l] = lambda - mode * edge.p[0];
    else r[nx_ + l] = lambda;
  }
  const int s0 = nx_ + nl_, w0 = s0 + ns_, z0 = w0 + nw_;
  for (int k = 0; k < ns_; ++k) {
    if (k < kinematics_.coordinates) {
      const Edge& edge = graph_.edges[static_cast<std::size_t>(graph_.rate_edges[static_cast<std::size_t>(kinematics_.coordinate_rate[static_cast<std::size_t>(k)])])];
      r[s0 + k] = y[s0 + k] - elongation(y, drive, edge);
    } else {
      r[s0 + k] = yp[s0 + k];
    }
  }
  for (int v = 0; v < nw_; ++v) r[w0 + v] = yp[w0 + v];
  for (int j = 0; j < kinematics_.coordinates; ++j) {
    const int slot = kinematics_.velocity_slot[static_cast<std::size_t>(j)];
    if (slot >= 0) r[w0 + slot] = y[w0 + slot] - yp[s0 + j];
  }
  for (int b = 0; b < nz_; ++b) {
    const Edge& edge = graph_.edges[static_cast<std::size_t>(graph_.bouc_wen_edges[static_cast<std::size_t>(b)])];
    const double k = edge.p[0], n = edge.p[1], fy = edge.p[2];
    const double z = y[z0 + b];
    const double rate = elongation_rate(yp, drive, edge);
    const double loading = z * rate > 0.0 ? 1.0 : 0.0;
    r[z0 + b] = yp[z0 + b] - (k / fy) * rate * (1.0 - std::pow(std::abs(z), n) * loading);
  }
}

void DaeIntegrator::roots(double t, const double* y, const double* yp, double* g) {
  const DriveState drive = drive_at(t);
  for (int l = 0; l < nl_; ++l) {
    const Edge& edge = graph_.edges[static_cast<std::size_t>(graph_.switch_edges[static_cast<std::size_t>(l)])];
    const std::int8_t mode = modes_[static_cast<std::size_t>(l)];
    const double lambda = y[nx_ + l];
    double* out = g + 2 * l;
    if (edge.kind == EdgeKind::slider) {
      if (mode == 0) out[0] = lambda - edge.p[0] * (1.0 + kSlack), out[1] = lambda + edge.p[0] * (1.0 + kSlack);
      else out[0] = elongation_rate(yp, drive, edge), out[1] = 1.0;
    } else {
      const double e = elongation(y, drive, edge);
      if (mode == 0) out[0] = e - edge.p[0] * (1.0 + kGapSlack), out[1] = e + edge.p[0] * (1.0 + kGapSlack);
      else out[0] = lambda, out[1] = 1.0;
    }
  }
}

void DaeIntegrator::start(const DriveSignal& drive) {
  drive_ = drive;
  segment_ = 0;
  time_ = drive.kind == DriveSignal::Kind::samples ? drive.samples->time.front() : 0.0;
  events_ = 0;
  totals_ = {};
  modes_.assign(static_cast<std::size_t>(nl_), 0);  // sliders stuck, gaps open
  held_.assign(static_cast<std::size_t>(nl_), 0.0);
  std::fill(y_.begin(), y_.end(), 0.0);
  std::fill(yp_.begin(), yp_.end(), 0.0);
  kinematics_ = ModeKinematics::make(graph_, modes_);
  restart(time_, true);
}

// Re-chooses the coordinates for the current modes (mapping s and w from the positions and the
// previous rates), re-initialises IDA at t and makes the state consistent. Sliders found stuck
// beyond their yield force, or gaps closed under tension, are switched and the step repeated.
void DaeIntegrator::restart(double t, bool modes_changed) {
  if (!solver_) {
    kinematics_ = ModeKinematics::make(graph_, modes_);
    return;
  }
  void* mem = solver_->ida.get();
  const int s0 = nx_ + nl_, w0 = s0 + ns_;
  for (int attempt = 0;; ++attempt) {
    if (modes_changed) {
      const DriveState drive = drive_at(t);
      edge_forces(drive, y_.data(), yp_.data(), force_.data());  // rates of every rate edge, old coordinates
      const std::vector<double> old_rate = rate_;
      kinematics_ = ModeKinematics::make(graph_, modes_);
      for (int k = 0; k < ns_; ++k) y_[static_cast<std::size_t>(s0 + k)] = yp_[static_cast<std::size_t>(s0 + k)] = 0.0;
      for (int v = 0; v < nw_; ++v) y_[static_cast<std::size_t>(w0 + v)] = yp_[static_cast<std::size_t>(w0 + v)] = 0.0;
      for (int j = 0; j < kinematics_.coordinates; ++j) {
        const int rate_index = kinematics_.coordinate_rate[static_cast<std::size_t>(j)];
        const Edge& edge = graph_.edges[static_cast<std::size_t>(graph_.rate_edges[static_cast<std::size_t>(rate_index)])];
        y_[static_cast<std::size_t>(s0 + j)] = elongation(y_.data(), drive, edge);
        yp_[static_cast<std::size_t>(s0 + j)] = old_rate[static_cast<std::size_t>(rate_index)];
        const int slot = kinematics_.velocity_slot[static_cast<std::size_t>(j)];
        if (slot >= 0) y_[static_cast<std::size_t>(w0 + slot)] = old_rate[static_cast<std::size_t>(rate_index)];
      }
      std::vector<int> direction(static_cast<std::size_t>(2 * nl_), 0);
      for (int l = 0; l < nl_; ++l) {
        const Edge& edge = graph_.edges[static_cast<std::size_t>(graph_.switch_edges[static_cast<std::size_t>(l)])];
        const int mode = modes_[static_cast<std::size_t>(l)];
        int* d = direction.data() + 2 * l;
        if (edge.kind == EdgeKind::slider) {
          if (mode == 0) d[0] = 1, d[1] = -1;
          else d[0] = -mode;
        } else {
          if (mode == 0) d[0] = 1, d[1] = -1;
          else d[0] = -mode;
        }
      }
      if (nl_ > 0) sundials::check_ida(IDASetRootDirection(mem, direction.data()), "IDASetRootDirection");
    }
    std::copy(y_.begin(), y_.end(), N_VGetArrayPointer(solver_->y.get()));
    std::copy(yp_.begin(), yp_.end(), N_VGetArrayPointer(solver_->yp.get()));
    collect_statistics();  // IDAReInit zeroes IDA's counters
    sundials::check_ida(IDAReInit(mem, t, solver_->y.get(), solver_->yp.get()), "IDAReInit");
    const double horizon = drive_.kind == DriveSignal::Kind::sine ? 1e-3 / std::max(drive_.omega, 1e-12)
                                                                   : 1e-3 * (drive_.samples->time.back() - drive_.samples->time.front());
    const int flag = IDACalcIC(mem, IDA_YA_YDP_INIT, t + horizon);
    if (flag < 0) {
      if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
      sundials::check_ida(flag, "IDACalcIC", fmt::format("no consistent state of model '{}' at t = {:g} s after an element switched; {}",
                                                         graph_.model, t, last_message_));
    }
    sundials::check_ida(IDAGetConsistentIC(mem, solver_->y.get(), solver_->yp.get()), "IDAGetConsistentIC");
    const double* y = N_VGetArrayPointer(solver_->y.get());
    const double* yp = N_VGetArrayPointer(solver_->yp.get());
    std::copy(y, y + n_, y_.begin());
    std::copy(yp, yp + n_, yp_.begin());

    bool consistent = true;
    for (int l = 0; l < nl_; ++l) {
      const Edge& edge = graph_.edges[static_cast<std::size_t>(graph_.switch_edges[static_cast<std::size_t>(l)])];
      std::int8_t& mode = modes_[static_cast<std::size_t>(l)];
      const double lambda = y_[static_cast<std::size_t>(nx_ + l)];
      if (edge.kind == EdgeKind::slider && mode == 0 && std::abs(lambda) > edge.p[0] * (1.0 + 0.5 * kSlack)) {
        mode = lambda > 0.0 ? 1 : -1;
        consistent = false;
      } else if (edge.kind == EdgeKind::gap && mode != 0 && lambda * mode < -1e-12 * options_.force_scale) {
        mode = 0;
        consistent = false;
      }
    }
    if (consistent) return;
    if (attempt > 2 * nl_ + 2)
      throw NumericalError(fmt::format("model '{}': the sliders and gaps find no consistent state at t = {:g} s", graph_.model, t));
    modes_changed = true;
  }
}

void DaeIntegrator::switch_modes(double t, const std::vector<int>& found) {
  const DriveState drive = drive_at(t);
  for (int l = 0; l < nl_; ++l) {
    if (!found[static_cast<std::size_t>(2 * l)] && !found[static_cast<std::size_t>(2 * l + 1)]) continue;
    const Edge& edge = graph_.edges[static_cast<std::size_t>(graph_.switch_edges[static_cast<std::size_t>(l)])];
    std::int8_t& mode = modes_[static_cast<std::size_t>(l)];
    double& held = held_[static_cast<std::size_t>(l)];
    if (edge.kind == EdgeKind::slider) {
      if (mode == 0) {
        mode = y_[static_cast<std::size_t>(nx_ + l)] > 0.0 ? 1 : -1;
      } else {
        mode = 0;
        held = elongation(y_.data(), drive, edge);
      }
    } else if (mode == 0) {
      mode = found[static_cast<std::size_t>(2 * l)] ? 1 : -1;
      held = mode * edge.p[0];
    } else {
      mode = 0;
    }
  }
  ++events_;
  restart(t, true);
}

double DaeIntegrator::solve_to(double t_stop) {
  void* mem = solver_->ida.get();
  sundials::check_ida(IDASetStopTime(mem, t_stop), "IDASetStopTime");
  double t_reached = time_;
  const int flag = IDASolve(mem, t_stop, &t_reached, solver_->y.get(), solver_->yp.get(), IDA_NORMAL);
  if (flag < 0) {
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
    sundials::check_ida(flag, "IDASolve", fmt::format("model '{}' at t = {:g} s: {}", graph_.model, t_reached, last_message_));
  }
  const double* y = N_VGetArrayPointer(solver_->y.get());
  const double* yp = N_VGetArrayPointer(solver_->yp.get());
  std::copy(y, y + n_, y_.begin());
  std::copy(yp, yp + n_, yp_.begin());
  time_ = t_reached;
  if (flag == IDA_ROOT_RETURN) {
    std::vector<int> found(static_cast<std::size_t>(2 * nl_), 0);
    sundials::check_ida(IDAGetRootInfo(mem, found.data()), "IDAGetRootInfo");
    switch_modes(t_reached, found);
  }
  return t_reached;
}

// A slipping slider whose rate changes sign exactly at a sample of a piecewise-linear drive has
// no root inside a step to find (the drive rate, and often the slip rate, are constant between
// samples). A probe step of 1e-6 of the next interval shows the new sign; a reversed slider sticks
// at the sample and the integration restarts there.
void DaeIntegrator::stick_reversed_sliders() {
  bool slipping = false;
  for (int l = 0; l < nl_; ++l)
    slipping |= graph_.edges[static_cast<std::size_t>(graph_.switch_edges[static_cast<std::size_t>(l)])].kind == EdgeKind::slider &&
                modes_[static_cast<std::size_t>(l)] != 0;
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
  for (int l = 0; l < nl_; ++l) {
    const Edge& edge = graph_.edges[static_cast<std::size_t>(graph_.switch_edges[static_cast<std::size_t>(l)])];
    const std::int8_t mode = modes_[static_cast<std::size_t>(l)];
    if (edge.kind != EdgeKind::slider || mode == 0 || g[static_cast<std::size_t>(2 * l)] * mode >= 0.0) continue;
    modes_[static_cast<std::size_t>(l)] = 0;
    held_[static_cast<std::size_t>(l)] = 0.0;
    reversed = true;
  }
  if (!reversed) return;
  y_ = y_saved_;
  yp_ = yp_saved_;
  time_ = t0;
  const DriveState drive = drive_at(t0);
  for (int l = 0; l < nl_; ++l) {
    const Edge& edge = graph_.edges[static_cast<std::size_t>(graph_.switch_edges[static_cast<std::size_t>(l)])];
    if (edge.kind == EdgeKind::slider && modes_[static_cast<std::size_t>(l)] == 0)
      held_[static_cast<std::size_t>(l)] = elongation(y_.data(), drive, edge);
  }
  ++events_;
  restart(t0, true);
}

double DaeIntegrator::advance(double t) {
  const bool samples = drive_.kind == DriveSignal::Kind::samples;
  if (!solver_) {
    time_ = t;
    if (samples)
      while (segment_ + 2 < drive_.samples->time.size() && drive_.samples->time[segment_ + 1] < t) ++segment_;
  }
  while (solver_ && time_ < t) {
    double stop = t;
    const bool at_breakpoint = samples && segment_ + 2 < drive_.samples->time.size() && drive_.samples->time[segment_ + 1] <= t;
    if (at_breakpoint) stop = drive_.samples->time[segment_ + 1];
    solve_to(stop);
    if (at_breakpoint && time_ >= stop) {
      ++segment_;
      restart(time_, false);  // the drive rate jumps here
      stick_reversed_sliders();
    }
  }
  edge_forces(drive_at(time_), y_.data(), yp_.data(), force_.data());
  return terminal_force(force_.data());
}

void DaeIntegrator::element_outputs(std::vector<double>& force, std::vector<double>& element_elongation) const {
  const DriveState drive = drive_at(time_);
  edge_forces(drive, y_.data(), yp_.data(), force_.data());
  force.resize(graph_.probes.size());
  element_elongation.resize(graph_.probes.size());
  for (std::size_t i = 0; i < graph_.probes.size(); ++i) {
    const EdgeProbe& probe = graph_.probes[i];
    force[i] = 0.0;
    for (int edge : probe.force_edges) force[i] += force_[static_cast<std::size_t>(edge)];
    double e = 0.0;
    for (int edge : probe.edges) e += elongation(y_.data(), drive, graph_.edges[static_cast<std::size_t>(edge)]);
    element_elongation[i] = e;
  }
}

void DaeIntegrator::collect_statistics() {
  if (!solver_) return;
  long steps = 0, residuals = 0;
  IDAGetNumSteps(solver_->ida.get(), &steps);
  IDAGetNumResEvals(solver_->ida.get(), &residuals);
  totals_.steps += steps;
  totals_.residual_evaluations += residuals;
}

double DaeIntegrator::change_since(const std::vector<double>& start, double length, double force, double velocity) const {
  double change = 0.0;
  for (int i = 0; i < n_; ++i) {
    if (i >= nx_ + nl_ && i < nx_ + nl_ + ns_) continue;  // rate coordinates
    const double scale = i < nx_ ? length : i < nx_ + nl_ ? force : i < nx_ + nl_ + ns_ + nw_ ? velocity : 1.0;
    const auto k = static_cast<std::size_t>(i);
    change = std::max(change, std::abs(y_[k] - start[k]) / scale);
  }
  return change;
}

DaeStatistics DaeIntegrator::statistics() const {
  DaeStatistics s = totals_;
  s.events = events_;
  if (!solver_) return s;
  long steps = 0, residuals = 0;
  IDAGetNumSteps(solver_->ida.get(), &steps);
  IDAGetNumResEvals(solver_->ida.get(), &residuals);
  s.steps += steps;
  s.residual_evaluations += residuals;
  return s;
}

}  // namespace rheo::runtime
