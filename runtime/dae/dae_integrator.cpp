#include "runtime/dae/dae_integrator.hpp"

#include "runtime/dae/dae_integrator_detail.hpp"
#include "runtime/network/leaf_kernels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace rheo::runtime {

void capture_ida_message(int, const char*, const char* function, char* message, void* user_data) {
  auto* self = static_cast<DaeIntegrator*>(user_data);
  self->last_message_ = fmt::format("{}: {}", function ? function : "IDA", message ? message : "");
}

namespace {

// C trampolines: exceptions never cross the C library; they are stored and rethrown after the
// call returns (a negative return makes IDA stop with IDA_RES_FAIL / IDA_RTFUNC_FAIL).
struct Callbacks {
  static int residual(realtype t, N_Vector y, N_Vector yp, N_Vector r, void* data) noexcept;
  static int roots(realtype t, N_Vector y, N_Vector yp, realtype* g, void* data) noexcept;
  static int jacobian(realtype t, realtype cj, N_Vector y, N_Vector yp, N_Vector r, SUNMatrix jacobian, void* data, N_Vector, N_Vector,
                      N_Vector) noexcept;
};

}  // namespace

namespace {
DaeIntegrator* self(void* data) { return static_cast<DaeIntegrator*>(data); }

// How far above the rounding of its node balances a gap force's Newton tolerance must stay.
constexpr double kRoundingMargin = 10.0;
}  // namespace

DaeLayout DaeLayout::of(const DaeGraph& graph) {
  DaeLayout l;
  l.positions = graph.internal_nodes;
  l.switch_forces = static_cast<int>(graph.switch_edges.size());
  l.rate_coordinates = static_cast<int>(graph.rate_edges.size());
  for (int e : graph.rate_edges) l.inerter_velocities += at(graph.edges, e).kind == EdgeKind::inerter ? 1 : 0;
  l.bouc_wen_states = static_cast<int>(graph.bouc_wen_edges.size());
  return l;
}

DaeLayout::Block DaeLayout::block_of(int i) const {
  if (i < switch_force(0)) return Block::position;
  if (i < rate_coordinate(0)) return Block::switch_force;
  if (i < inerter_velocity(0)) return Block::rate_coordinate;
  if (i < bouc_wen_state(0)) return Block::inerter_velocity;
  return Block::bouc_wen_state;
}

const Edge& DaeIntegrator::switch_edge(int l) const { return at(graph_.edges, at(graph_.switch_edges, l)); }

int Callbacks::residual(realtype t, N_Vector y, N_Vector yp, N_Vector r, void* data) noexcept {
  try {
    self(data)->residual(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), N_VGetArrayPointer(r));
    return 0;
  } catch (...) {
    self(data)->store_error(std::current_exception());
    return -1;
  }
}

int Callbacks::jacobian(realtype t, realtype cj, N_Vector y, N_Vector yp, N_Vector r, SUNMatrix jacobian, void* data, N_Vector, N_Vector,
                        N_Vector) noexcept {
  try {
    self(data)->jacobian(t, cj, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), N_VGetArrayPointer(r), SUNDenseMatrix_Data(jacobian));
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

DaeIntegrator::DaeIntegrator(const DaeGraph& graph, const DaeOptions& options) : graph_(graph), options_(options), layout_(DaeLayout::of(graph)) {
  const auto ne = graph.edges.size();
  auto index_of_edge = [ne](const std::vector<int>& list) {
    std::vector<int> index(ne, -1);
    for (std::size_t i = 0; i < list.size(); ++i) at(index, list[i]) = static_cast<int>(i);
    return index;
  };
  rate_of_edge_ = index_of_edge(graph.rate_edges);
  switch_of_edge_ = index_of_edge(graph.switch_edges);
  bouc_wen_of_edge_ = index_of_edge(graph.bouc_wen_edges);
  const int n = layout_.size();
  const auto roots = static_cast<std::size_t>(root_count());
  rate_.assign(graph.rate_edges.size(), 0.0);
  acceleration_.assign(graph.rate_edges.size(), 0.0);
  force_.assign(ne, 0.0);
  y_.assign(static_cast<std::size_t>(n), 0.0);
  yp_ = y_;
  y_saved_ = y_;
  yp_saved_ = y_;
  root_values_.assign(roots, 0.0);
  y_probe_ = y_;
  yp_probe_ = y_;
  r_probe_ = y_;
  y_probe_initial_ = y_;
  r_initial_ = y_;
  rates_ahead_ = y_;
  scale_ = y_;
  for (int e : graph.bouc_wen_edges) nested_bouc_wen_ |= at(graph.edges, e).a >= 0 || at(graph.edges, e).b >= 0;
  root_direction_.assign(roots, 0);
  roots_found_.assign(roots, 0);
  if (n == 0) return;  // purely algebraic: forces follow the drive directly

  using namespace sundials;
  solver_ = std::make_unique<Solver>();
  SUNContext ctx = nullptr;
  check_sundials(SUNContext_Create(nullptr, &ctx), "SUNContext_Create");
  solver_->context.reset(ctx);
  solver_->y.reset(owned(N_VNew_Serial(n, ctx), "N_VNew_Serial"));
  solver_->yp.reset(owned(N_VNew_Serial(n, ctx), "N_VNew_Serial"));
  solver_->id.reset(owned(N_VNew_Serial(n, ctx), "N_VNew_Serial"));
  solver_->tolerance.reset(owned(N_VNew_Serial(n, ctx), "N_VNew_Serial"));
  N_VConst(0.0, solver_->y.get());
  N_VConst(0.0, solver_->yp.get());
  double* id = N_VGetArrayPointer(solver_->id.get());
  double* atol = N_VGetArrayPointer(solver_->tolerance.get());
  const double rtol = options_.relative_tolerance;
  for (int i = 0; i < n; ++i) {
    id[i] = layout_.differential(i) ? 1.0 : 0.0;
    double scale = 1.0;   // Bouc-Wen states
    double newton = 1.0;  // the absolute tolerance is rtol * scale * this
    switch (layout_.block_of(i)) {
      case DaeLayout::Block::position:
      case DaeLayout::Block::rate_coordinate: scale = options_.length_scale; break;
      case DaeLayout::Block::switch_force: {
        // A stuck slider's force spans up to its yield force, whatever the network's force
        // scale: a quadratic dashpot behind a stuck 12 N slider and a 16090 N/mm spring carries
        // 3.5e-3 N, and an absolute tolerance of 1e-8 of that on the slider's force (returned
        // through the stiff spring's elongation) failed IDA's error test at nearly every step
        // (2e7 steps a cycle; now 551, the same K* to 1e-9).
        const Edge& edge = switch_edge(i - layout_.switch_force(0));
        if (edge.kind == EdgeKind::slider) {
          scale = std::max(options_.force_scale, 0.5 * (edge.p[0] + edge.p[1]));
          // IDA's Newton coefficient, lowered below its default 0.33 so that positions behind
          // stiff springs balance forces (dae_newton_tolerance), applies to every unknown. A
          // slider's force is itself a force: its Newton updates need only the default share of
          // its tolerance, and IDA's corrector reads its coefficient times the absolute
          // tolerance, so that tolerance is raised by 0.33 / coefficient (IDA's error test then
          // weighs the force little; it is algebraic, fixed by the rates and positions that
          // Newton converges). Below it, the second-order term of a rate correction through a
          // quadratic dashpot beside the stuck slider, cq dv^2, moved the force back and forth
          // by the same amount at every Newton iteration: 8.4e-11 N against a threshold of
          // 5.5e-13 N (a 2.05 N slider beside a 8017 N/mm spring, cq = 0.0031 N s^2/mm^2,
          // dv = 1.6e-4 mm/s, the predictor's rate error in a fast transient after a drive
          // sample, which does not shrink with h): IDA took the ratio of 1 for divergence and
          // failed the corrector down to its smallest step (differential seed 61, model 151).
          newton = std::max(1.0, kIdaNewtonCoefficient / options_.newton_tolerance);
        } else {
          // A gap's force, rigid in contact, has no scale of its own; it is kept above what
          // rounding leaves in it. It balances node forces in which a position's last bit is
          // multiplied by up to the stiffest spring's force F_k, and Newton must bring its
          // update below newton_tolerance of the tolerance. A gap closing behind a 35366 N/mm
          // spring and a quadratic dashpot carrying 0.011 N at the history's rate scale had an
          // absolute tolerance of 1.1e-10 N, 1e-6 of it for Newton, against 2.7e-12 N of
          // rounding, and the corrector failed at every h (IDA_CONV_FAIL). (Not for sliders:
          // their yield force scales them, and their stick-slip roots read the force.)
          const double rounding = kRoundingMargin * std::numeric_limits<double>::epsilon() * stiffest_spring_force(graph_, options_.length_scale);
          scale = std::max(options_.force_scale, rounding / (rtol * options_.newton_tolerance));
        }
        break;
      }
      case DaeLayout::Block::inerter_velocity: scale = options_.velocity_scale; break;
      case DaeLayout::Block::bouc_wen_state: break;
    }
    atol[i] = rtol * scale * newton;
    at(scale_, i) = scale;
  }
  solver_->ida.reset(owned(IDACreate(ctx), "IDACreate"));
  void* mem = solver_->ida.get();
  check_ida(IDASetErrHandlerFn(mem, capture_ida_message, this), "IDASetErrHandlerFn");
  check_ida(IDAInit(mem, Callbacks::residual, 0.0, solver_->y.get(), solver_->yp.get()), "IDAInit");
  check_ida(IDASVtolerances(mem, rtol, solver_->tolerance.get()), "IDASVtolerances");
  check_ida(IDASetUserData(mem, this), "IDASetUserData");
  check_ida(IDASetId(mem, solver_->id.get()), "IDASetId");
  check_ida(IDASetMaxNumSteps(mem, options_.max_steps), "IDASetMaxNumSteps");
  solver_->jacobian.reset(owned(SUNDenseMatrix(n, n, ctx), "SUNDenseMatrix"));
  solver_->linear_solver.reset(owned(SUNLinSol_Dense(solver_->y.get(), solver_->jacobian.get(), ctx), "SUNLinSol_Dense"));
  check_ida(IDASetLinearSolver(mem, solver_->linear_solver.get(), solver_->jacobian.get()), "IDASetLinearSolver");
  use_own_jacobian(true);
  solver_->euler_matrix.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0.0);
  solver_->euler_lu = Eigen::PartialPivLU<Eigen::MatrixXd>(n);
  check_ida(IDASetNonlinConvCoef(mem, options_.newton_tolerance), "IDASetNonlinConvCoef");
  if (root_count() > 0) {
    check_ida(IDARootInit(mem, root_count(), Callbacks::roots), "IDARootInit");
    check_ida(IDASetNoInactiveRootWarn(mem), "IDASetNoInactiveRootWarn");
  }
}

DaeIntegrator::~DaeIntegrator() = default;

double DaeIntegrator::elongation(const double* y, const DriveState& drive, const Edge& edge) {
  auto position = [&](int node) { return node >= 0 ? y[node] : node == kTerminal ? drive.u : 0.0; };
  return position(edge.a) - position(edge.b);
}

double DaeIntegrator::elongation_rate(const double* yp, const DriveState& drive, const Edge& edge) {
  auto velocity = [&](int node) { return node >= 0 ? yp[node] : node == kTerminal ? drive.du : 0.0; };
  return velocity(edge.a) - velocity(edge.b);
}

void DaeIntegrator::edge_forces(const DriveState& drive, const double* y, const double* yp, double* force) const {
  const double* s_rate = yp + layout_.rate_coordinate(0);
  const double* w_rate = yp + layout_.inerter_velocity(0);
  const int q = kinematics_.coordinates;
  for (int i = 0; i < layout_.rate_coordinates; ++i) {
    const double* alpha = kinematics_.alpha.data() + static_cast<std::size_t>(i) * static_cast<std::size_t>(q);
    double rate = at(kinematics_.beta, i) * drive.du;
    double acceleration = at(kinematics_.beta, i) * drive.ddu;
    for (int j = 0; j < q; ++j) {
      rate += alpha[j] * s_rate[j];
      const int slot = at(kinematics_.velocity_slot, j);
      if (slot >= 0) acceleration += alpha[j] * w_rate[slot];
    }
    at(rate_, i) = rate;
    at(acceleration_, i) = acceleration;
  }
  for (std::size_t i = 0; i < graph_.edges.size(); ++i) {
    const Edge& edge = graph_.edges[i];
    const double e = elongation(y, drive, edge);
    const int rate_index = rate_of_edge_[i];
    switch (edge.kind) {
      case EdgeKind::spring: force[i] = edge.p[0] * e; break;
      case EdgeKind::yeoh: force[i] = YeohLaw{edge.p[0], edge.p[1], edge.p[2]}.force(e); break;
      case EdgeKind::poly_spring: force[i] = PolyLaw{edge.p[0], edge.p[1], edge.p[2]}.force(e); break;
      case EdgeKind::dashpot: force[i] = edge.p[0] * at(rate_, rate_index); break;
      case EdgeKind::quadratic_dashpot: {
        const double v = at(rate_, rate_index);
        force[i] = edge.p[0] * v * std::sqrt(v * v + kQuadraticDashpotVelocityEps * kQuadraticDashpotVelocityEps);
        break;
      }
      case EdgeKind::inerter: force[i] = edge.p[0] * at(acceleration_, rate_index); break;
      case EdgeKind::bouc_wen: force[i] = edge.p[2] * y[layout_.bouc_wen_state(bouc_wen_of_edge_[i])]; break;
      case EdgeKind::slider:
      case EdgeKind::gap: force[i] = y[layout_.switch_force(switch_of_edge_[i])]; break;
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
  std::fill(r, r + layout_.positions, 0.0);
  for (std::size_t i = 0; i < graph_.edges.size(); ++i) {
    const Edge& edge = graph_.edges[i];
    if (edge.a >= 0) r[edge.a] -= force_[i];
    if (edge.b >= 0) r[edge.b] += force_[i];
  }
  for (int l = 0; l < layout_.switch_forces; ++l) {
    const Edge& edge = switch_edge(l);
    const std::int8_t mode = at(modes_, l);
    const int i = layout_.switch_force(l);
    const double lambda = y[i];
    if (is_rigid(edge, mode)) r[i] = elongation(y, drive, edge) - at(held_, l);
    else if (edge.kind == EdgeKind::slider) r[i] = lambda - slip_force(edge, mode);
    else r[i] = lambda;
  }
  const int s0 = layout_.rate_coordinate(0), w0 = layout_.inerter_velocity(0);
  for (int k = 0; k < layout_.rate_coordinates; ++k) {
    if (k < kinematics_.coordinates) {
      const Edge& edge = at(graph_.edges, at(graph_.rate_edges, at(kinematics_.coordinate_rate, k)));
      r[s0 + k] = y[s0 + k] - elongation(y, drive, edge);
    } else {
      r[s0 + k] = yp[s0 + k];
    }
  }
  for (int v = 0; v < layout_.inerter_velocities; ++v) r[w0 + v] = yp[w0 + v];
  for (int j = 0; j < kinematics_.coordinates; ++j) {
    const int slot = at(kinematics_.velocity_slot, j);
    if (slot >= 0) r[w0 + slot] = y[w0 + slot] - yp[s0 + j];
  }
  bouc_wen_residuals(drive, y, yp, r);
}

void DaeIntegrator::use_own_jacobian(bool own) {
  sundials::check_ida(IDASetJacFn(solver_->ida.get(), own ? Callbacks::jacobian : nullptr), "IDASetJacFn");
}

// J = dr/dy + cj dr/dy' by differences, each part with its own increment. IDA's built-in
// difference quotient moves y_j by s and y'_j by cj s together, and cj = alpha/h grows as the
// step shrinks: y'_j then moves by far more than a rate's own size, and a law that is non-linear
// in a rate (the quadratic dashpot, whose tangent 2 cq |v| falls to cq v_eps at a reversal) gets
// the slope of a long secant. With that matrix the corrector converged ever slower as h fell,
// down to h = 1e-25 s (tests/corpus/repro/backends 04). Increments: sqrt(eps) times the
// unknown's size or its tolerance scale, and for y' that scale over the drive's time scale.
void DaeIntegrator::jacobian(double t, double cj, const double* y, const double* yp, const double* r, double* matrix) {
  const int n = layout_.size();
  const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  const double per_second = options_.velocity_scale / options_.length_scale;  // 1/s: omega, or 1 / the history's duration
  std::copy(y, y + n, y_probe_.begin());
  std::copy(yp, yp + n, yp_probe_.begin());
  for (int j = 0; j < n; ++j) {
    double* column = matrix + static_cast<std::ptrdiff_t>(j) * n;
    const double scale = at(scale_, j);
    double& yj = at(y_probe_, j);
    yj = y[j] + root_eps * std::max(std::abs(y[j]), scale);
    const double dy = yj - y[j];
    residual(t, y_probe_.data(), yp_probe_.data(), r_probe_.data());
    for (int i = 0; i < n; ++i) column[i] = (at(r_probe_, i) - r[i]) / dy;
    yj = y[j];
    // Rates of switch forces appear in no residual; those of positions only in Bouc-Wen laws.
    const DaeLayout::Block block = layout_.block_of(j);
    if (block == DaeLayout::Block::switch_force || (block == DaeLayout::Block::position && layout_.bouc_wen_states == 0)) continue;
    double& ypj = at(yp_probe_, j);
    ypj = yp[j] + root_eps * std::max(std::abs(yp[j]), scale * per_second);
    const double dyp = ypj - yp[j];
    residual(t, y_probe_.data(), yp_probe_.data(), r_probe_.data());
    for (int i = 0; i < n; ++i) column[i] += cj * (at(r_probe_, i) - r[i]) / dyp;
    ypj = yp[j];
  }
}

void DaeIntegrator::roots(double t, const double* y, const double* yp, double* g) {
  const DriveState drive = drive_at(t);
  for (int l = 0; l < layout_.switch_forces; ++l) {
    const Edge& edge = switch_edge(l);
    const std::int8_t mode = at(modes_, l);
    const double lambda = y[layout_.switch_force(l)];
    double* out = g + 2 * l;
    if (edge.kind == EdgeKind::slider) {
      if (mode == 0) out[0] = lambda - edge.p[0] * (1.0 + kSlack), out[1] = lambda + edge.p[1] * (1.0 + kSlack);
      else out[0] = elongation_rate(yp, drive, edge), out[1] = 1.0;
    } else {
      const double e = elongation(y, drive, edge) - edge.p[1];  // from the centre of the play
      if (mode == 0) out[0] = e - edge.p[0] * (1.0 + kGapSlack), out[1] = e + edge.p[0] * (1.0 + kGapSlack);
      else out[0] = lambda, out[1] = 1.0;
    }
  }
  bouc_wen_roots(drive, yp, g + 2 * layout_.switch_forces);
}

void DaeIntegrator::element_outputs(std::vector<double>& force, std::vector<double>& element_elongation) const {
  const DriveState drive = drive_at(time_);
  edge_forces(drive, y_.data(), yp_.data(), force_.data());
  force.resize(graph_.probes.size());
  element_elongation.resize(graph_.probes.size());
  for (std::size_t i = 0; i < graph_.probes.size(); ++i) {
    const EdgeProbe& probe = graph_.probes[i];
    force[i] = 0.0;
    for (int edge : probe.force_edges) force[i] += at(force_, edge);
    double e = 0.0;
    for (int edge : probe.edges) e += elongation(y_.data(), drive, at(graph_.edges, edge));
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
  for (int i = 0; i < layout_.size(); ++i) {
    double scale = 1.0;  // Bouc-Wen states
    switch (layout_.block_of(i)) {
      case DaeLayout::Block::rate_coordinate: continue;  // events re-choose them
      case DaeLayout::Block::position: scale = length; break;
      case DaeLayout::Block::switch_force: scale = force; break;
      case DaeLayout::Block::inerter_velocity: scale = velocity; break;
      case DaeLayout::Block::bouc_wen_state: break;
    }
    change = std::max(change, std::abs(at(y_, i) - at(start, i)) / scale);
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
