// DaeIntegrator's Bouc-Wen laws and the events of their loading switch (the contract is in
// dae_integrator.hpp).
//
// z' = (k/fy) e' (1 - |z|^n (1 + sgn(z e'))/2) has two branches: loading (z e' > 0), whose slope
// dz'/de' = (k/fy) (1 - |z|^n) vanishes as |z| -> 1, and unloading, slope k/fy. Inside a block e'
// is a difference of node positions' rates, unknowns of the DAE, and where it reverses behind a
// nearly saturated bouc_wen (|z| = 0.999998, n = 3.8) the slope IDA's Newton matrix was formed
// with is off by up to 1e5 on the other side of e' = 0: the corrector failed at every step size
// (differential seed 37, model 85, IDA_CONV_FAIL 0.1 us after a drive sample). So each bouc_wen
// inside a block takes the branch of a direction d = +-1, the sign of e' assumed between events
// (loading where z d > 0): its law is smooth in e' within a step, and a root function e' (crossing
// from the side of d) ends the step where e' reverses; there d flips and IDA goes on (below). At z = 0,
// where loading starts again with e' of one sign, both branches have the same value and slope.
// A bouc_wen between the terminal and ground reads the drive's rate, which the residual knows
// exactly: it takes the branch of sgn(z u') as before (d = 0, no root).
#include "runtime/dae/dae_integrator.hpp"

#include "runtime/dae/dae_integrator_detail.hpp"

#include <cmath>

namespace rheo::runtime {

void DaeIntegrator::bouc_wen_residuals(const DriveState& drive, const double* y, const double* yp, double* r) const {
  const int z0 = layout_.bouc_wen_state(0);
  for (int b = 0; b < layout_.bouc_wen_states; ++b) {
    const Edge& edge = at(graph_.edges, at(graph_.bouc_wen_edges, b));
    const double k = edge.p[0], n = edge.p[1], fy = edge.p[2];
    const double z = y[z0 + b];
    const double rate = elongation_rate(yp, drive, edge);
    const int direction = at(bouc_wen_direction_, b);
    const double loading = z * (direction != 0 ? direction : rate) > 0.0 ? 1.0 : 0.0;
    r[z0 + b] = yp[z0 + b] - (k / fy) * rate * (1.0 - std::pow(std::abs(z), n) * loading);
  }
}

void DaeIntegrator::bouc_wen_roots(const DriveState& drive, const double* yp, double* g) const {
  const double band = bouc_wen_rate_band();
  for (int b = 0; b < layout_.bouc_wen_states; ++b) {
    const int direction = at(bouc_wen_direction_, b);
    g[b] = direction != 0 ? elongation_rate(yp, drive, at(graph_.edges, at(graph_.bouc_wen_edges, b))) + direction * band : 1.0;
  }
}

// A root reverses d only once e' is beyond this band on the other side, and a restart realigns d
// likewise. Without it, a bouc_wen whose e' decays to 0 (the one that carries the chain's force
// below its yield force while its saturated neighbour in series yields: e' = F'/k_t with F'
// -> 0) had IDA's rounding of e' cross zero every 1e-10 s, 7e5 events in 2 ms of seed 37, model
// 85; with the band its two-tone history in dae_bouc_wen_test takes 4. Inside the band the law may take the other
// branch: its z' is then off by at most (k/fy) |z|^n |e'|, so by (k/fy) times the elongation
// traversed there, at most the band times the duration: 1e-6 of the length scale over a history
// (whose velocity scale is the length over the duration), 2 pi 1e-6 of the amplitude a cycle.
double DaeIntegrator::bouc_wen_rate_band() const { return 100.0 * options_.relative_tolerance * options_.velocity_scale; }

void DaeIntegrator::start_bouc_wen_directions() {
  bouc_wen_direction_.assign(static_cast<std::size_t>(layout_.bouc_wen_states), 0);
  for (int b = 0; b < layout_.bouc_wen_states; ++b) {
    const Edge& edge = at(graph_.edges, at(graph_.bouc_wen_edges, b));
    if (edge.a >= 0 || edge.b >= 0) at(bouc_wen_direction_, b) = 1;  // aligned by the first restart
  }
}

void DaeIntegrator::set_bouc_wen_root_directions() {
  // e' may cross only from the side of d: IDA reports a crossing with the sign of -d.
  for (int b = 0; b < layout_.bouc_wen_states; ++b) at(root_direction_, 2 * layout_.switch_forces + b) = -at(bouc_wen_direction_, b);
}

// IDA goes on from the root without a restart: both branches give z' = (k/fy) e' (1 - |z|^n) or
// (k/fy) e' at e' = -d b, which differ by (k/fy) b |z|^n, 1e-6 of the law's scale, so IDA's history
// stays consistent, and its Newton matrix, formed on the old branch, is formed again where its
// corrector does not converge. A restart took the rates of a backward-Euler step of 1e-6 of the
// drive's time scale, whose positions' rates carry the balances' residual over that step
// (IDA's tolerance over 1e-6 of the time scale: far beyond the band): their e' could oppose the
// crossing IDA had just located, and the roots chattered (differential seed 41, model 11: 1e5
// events 5e-14 s apart in 10 s), or, kept, left a direction against e' (seed 41, model 38: z ran to -2.8).
void DaeIntegrator::reverse_bouc_wen_directions(const std::vector<int>& found) {
  for (int b = 0; b < layout_.bouc_wen_states; ++b)
    if (at(found, 2 * layout_.switch_forces + b) != 0) at(bouc_wen_direction_, b) = static_cast<std::int8_t>(-at(bouc_wen_direction_, b));
  set_bouc_wen_root_directions();
  sundials::check_ida(IDASetRootDirection(solver_->ida.get(), root_direction_.data()), "IDASetRootDirection");
  ++events_;
}

// The rates of one backward-Euler step under the current directions; where a bouc_wen's e' there
// is beyond the band against its d, d follows e' and the rates are taken again: at a start, at a
// drive sample, where the drive's rate jumps, and where solve_to restarts after a failure. A
// root with direction -d never sees such an e' cross, and the law would keep the wrong branch
// until the next sample. Where e' keeps changing sign between attempts (a reversal within the
// band's width) the last directions are kept.
void DaeIntegrator::bouc_wen_consistent_rates(double t, double horizon) {
  const DriveState drive = drive_at(t);
  const double band = bouc_wen_rate_band();
  bool aligned = false, flipped = false;
  for (int attempt = 0; attempt <= layout_.bouc_wen_states + 1 && !aligned; ++attempt) {
    initial_rates_by_euler_step(t, horizon);
    aligned = true;
    for (int b = 0; b < layout_.bouc_wen_states; ++b) {
      std::int8_t& direction = at(bouc_wen_direction_, b);
      if (direction == 0 || elongation_rate(yp_.data(), drive, at(graph_.edges, at(graph_.bouc_wen_edges, b))) * direction >= -band) continue;
      direction = static_cast<std::int8_t>(-direction);
      aligned = false;
      flipped = true;
    }
  }
  if (!aligned) initial_rates_by_euler_step(t, horizon);
  if (!flipped) return;
  set_bouc_wen_root_directions();
  sundials::check_ida(IDASetRootDirection(solver_->ida.get(), root_direction_.data()), "IDASetRootDirection");
}

}  // namespace rheo::runtime
