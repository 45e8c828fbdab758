#include "runtime/protocols/run_protocols.hpp"

#include "lang/limits.hpp"
#include "lang/protocol_schema.hpp"
#include "runtime/protocols/run_history.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/dae/dae_protocols.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/io/column_roles.hpp"
#include "runtime/io/hdf5_history.hpp"
#include "runtime/io/history_csv.hpp"
#include "runtime/network/leaf_kernels.hpp"
#include "runtime/closed_form/periodic_closed_form.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace rheo::runtime {
namespace {

using lang::Protocol;

// The work limits of lang/limits.hpp, checked before a drive or grid is built.
void require_within(double amount, long limit, const Protocol& p, const char* what, const char* advice) {
  if (!(amount <= static_cast<double>(limit)))
    throw ModelError(fmt::format("{}the {} protocol asks for {:.4g} {}, more than the limit of {}; {}", error_at(p.where),
                                 lang::protocol_name(p.kind), amount, what, limit, advice));
}

// One protocol run: the network, the protocol line (for its location) and the result's header.
struct RunContext {
  const Network& network;
  const Protocol& protocol;
  const std::string& source_file;
  int threads;
  ResultHeader header;
};


ProtocolResult history_run(RunContext& c, const lang::CommonSettings& common, const Drive& drive, std::string description) {
  c.header.protocol = std::move(description) + history_solver_note(c.network, common.solver);
  History h = run_history(c.network, drive, common.elements, common.solver);
  double reach = 0.0;
  for (double u : h.displacement) reach = std::max(reach, std::abs(u));
  ProtocolResult result{c.header, std::move(h), 0, yeoh_softening_note(c.network, reach)};
  return result;
}

HarmonicOptions harmonic_options(const lang::HarmonicSettings& s, int threads) {
  HarmonicOptions options;
  options.definition = s.definition;
  options.steady_state = s.steady_state;
  options.steps_per_cycle = s.steps_per_cycle;
  options.max_cycles = s.cycles_max;
  options.tolerance = s.tolerance;
  options.solver = s.solver;
  options.threads = threads;
  return options;
}

void require_consistent(const RunContext& c, const HarmonicOptions& options) {
  const lang::SourceLocation& where = c.protocol.where;
  if (options.steady_state == SteadyState::closed_form && options.solver == SolverChoice::sundials)
    throw UsageError(
        fmt::format("{}:{}:{}: steady_state = closed_form and the SUNDIALS solver exclude each other; "
                    "drop one (solver = fixed with closed_form, or steady_state = auto)",
                    where.file, where.line, where.column));
  if (options.steady_state == SteadyState::closed_form && !has_closed_form_periodic_state(c.network))
    throw UsageError(
        fmt::format("{}:{}:{}: steady_state = closed_form needs every non-linear element of model '{}' in its "
                    "parallel body, and no quadratic_dashpot, gap or bouc_wen: use steady_state = auto or time_stepping",
                    where.file, where.line, where.column, c.network.model().name));
}

// The header line's description of how the grid's periodic states were found.
std::string harmonic_method(const Network& network, const HarmonicOptions& options) {
  if (uses_closed_form(network, options)) return "harmonic steady_state=closed_form";
  if (uses_sundials(network, options.solver))
    return fmt::format("harmonic solver=sundials (IDA, rtol {:g}) samples_per_cycle={} tolerance={:g}", kDaeRelativeTolerance,
                       options.steps_per_cycle, std::max(options.tolerance, 100.0 * kDaeRelativeTolerance));
  return fmt::format("harmonic steady_state=time_stepping steps_per_cycle={} tolerance={:g}", options.steps_per_cycle, options.tolerance);
}

// A stalled point on fixed steps with an inerter may be the step's own artefact: Newmark's
// relation (Tustin's map of b s^2, periodic_start.hpp) maps a mode far faster than the step (an
// inerter beside a dashpot with b/c << dt) to z near -1, barely damped (differential seed 2026,
// model 191: |z| = 0.997 a step at 128 steps a cycle, which settles in 41 cycles now that the
// geometric skip leaves such a turning mode alone, cycle_groups.hpp; the closer b/c/dt comes to 0,
// the closer |z| comes to 1). A refused skip (HarmonicPoint::skip_refused) is named first.
std::string harmonic_notes(const Network& network, const HarmonicOptions& options, const std::vector<HarmonicPoint>& points,
                           const std::vector<double>& amplitudes) {
  const bool stepped_inerter = has_inerter(network) && !uses_closed_form(network, options) && !uses_sundials(network, options.solver);
  std::string notes;
  for (const auto& point : points)
    if (!point.converged && point.skip_refused)
      notes += fmt::format(
          "warning: amplitude {:g} mm, frequency {:g} Hz did not reach steady state in {} cycles (residual {:.2e}): part of the "
          "state kept moving at a steady rate, and where that rate said it would settle IDA found no consistent state; it may "
          "drift rather than settle: a chain whose element yields further one way each cycle ratchets and has no periodic state, such as a slider whose "
          "yield forces differ (fy_pos, fy_neg) in series with elements that hold no static force (a springpot, a Maxwell "
          "element or a dashpot with no spring beside them): give the chain a spring in parallel, or check the yield forces; "
          "the measures are those of the last cycle\n",
          point.amplitude, point.frequency, point.cycles, point.residual);
    else if (!point.converged && point.stalled)
      notes += fmt::format(
          "warning: amplitude {:g} mm, frequency {:g} Hz did not reach steady state in {} cycles (residual {:.2e}, not falling: the "
          "state's change over a cycle did not halve from the second to the last quarter of the cycles); an undamped free oscillation, "
          "such as a mass on springs with no dashpot or slipping friction in its loop, has no unique periodic state: add damping to it, "
          "or raise cycles_max if a mode is that slow{}\n",
          point.amplitude, point.frequency, point.cycles, point.residual,
          stepped_inerter ? "; on fixed steps an inerter's step relation (Newmark's) also leaves a mode much faster than the step "
                            "ringing nearly undamped (an inerter beside a stiff dashpot): raise steps_per_cycle or take solver = sundials"
                          : "");
    else if (!point.converged)
      notes += fmt::format(
          "warning: amplitude {:g} mm, frequency {:g} Hz did not reach steady state in {} cycles (residual {:.2e}); "
          "raise cycles_max or loosen tolerance\n",
          point.amplitude, point.frequency, point.cycles, point.residual);
  for (const auto& point : points)
    if (point.measures.damping_clamped) {
      notes += fmt::format("warning: amplitude {:g} mm, frequency {:g} Hz: normalised damping {:.4f} > 1, phase reported as 90 deg\n",
                           point.amplitude, point.frequency, point.measures.damping);
      break;
    }
  return notes + yeoh_softening_note(network, *std::max_element(amplitudes.begin(), amplitudes.end()));
}

ProtocolResult run(RunContext& c, const lang::HarmonicSettings& s) {
  const HarmonicOptions options = harmonic_options(s, c.threads);
  require_consistent(c, options);
  require_within(static_cast<double>(s.amplitudes.size()) * static_cast<double>(s.frequencies.size()), lang::max_harmonic_points, c.protocol,
                 "points (amplitudes x frequencies)", "split the grid over several protocols");
  require_within(static_cast<double>(options.steps_per_cycle) * options.max_cycles, lang::max_steps_per_point, c.protocol,
                 "time steps per point (steps_per_cycle x cycles_max)", "lower steps_per_cycle or cycles_max");
  HarmonicGrid grid{simulate_harmonic_grid(c.network, s.amplitudes, s.frequencies, options, s.preload), options.definition};
  c.header.protocol = harmonic_method(c.network, options);
  int not_converged = 0;
  for (const auto& point : grid.points) not_converged += point.converged ? 0 : 1;
  std::vector<double> reach = s.amplitudes;  // the largest |u| each amplitude drives to
  for (double& u : reach) u += std::abs(s.preload);
  std::string notes = harmonic_notes(c.network, options, grid.points, reach);
  return ProtocolResult{c.header, std::move(grid), not_converged, std::move(notes)};
}

// The static triangle resampled at a fixed interval: each of its steps cut into
// ceil(step time / dt) parts.
Drive resampled(const Drive& drive, double dt) {
  Drive fine;
  fine.time.assign(1, 0.0);
  fine.displacement.assign(1, 0.0);
  for (std::size_t k = 1; k < drive.time.size(); ++k) {
    const int parts = std::max(1, static_cast<int>(std::ceil((drive.time[k] - drive.time[k - 1]) / dt - 1e-9)));
    Drive piece{{drive.time[k - 1], drive.time[k]}, {drive.displacement[k - 1], drive.displacement[k]}};
    Drive refined = refine(piece, parts);
    fine.time.insert(fine.time.end(), refined.time.begin() + 1, refined.time.end());
    fine.displacement.insert(fine.displacement.end(), refined.displacement.begin() + 1, refined.displacement.end());
  }
  return fine;
}

ProtocolResult run(RunContext& c, const lang::StaticSettings& s) {
  constexpr int steps_per_cycle = lang::StaticSettings::samples_per_cycle;
  double samples = 0.0;
  for (double a : s.amplitudes)
    samples += static_cast<double>(s.cycles) * steps_per_cycle *
               (s.dt ? std::max(1.0, std::ceil(4.0 * a / (steps_per_cycle * s.velocity * *s.dt))) : 1.0);
  require_within(samples, lang::max_drive_samples, c.protocol, "samples", "raise dt or velocity, or give fewer cycles or amplitudes");
  Drive drive = static_triangle(s.amplitudes, s.velocity, s.cycles, steps_per_cycle);
  if (s.dt) drive = resampled(drive, *s.dt);
  return history_run(c, s, drive, fmt::format("static velocity={:g} mm/s cycles={}", s.velocity, s.cycles));
}

ProtocolResult run(RunContext& c, const lang::QuasistaticSettings& s) {
  require_within(static_cast<double>(s.amplitudes.size()) * s.cycles * s.steps_per_cycle, lang::max_drive_samples, c.protocol, "samples",
                 "lower steps_per_cycle, or give fewer cycles or amplitudes");
  return history_run(c, s, quasistatic_sine(s.amplitudes, s.frequency, s.cycles, s.steps_per_cycle),
                     fmt::format("quasistatic frequency={:g} Hz cycles={}", s.frequency, s.cycles));
}

ProtocolResult run(RunContext& c, const lang::HistorySettings& s) {
  const std::string file = history_file(s, c.source_file);
  const bool from_rest = s.start == lang::HistoryStart::rest;
  const ColumnReading reading = column_reading(s.columns);
  const Drive measured = reads_as_hdf5(file) ? read_hdf5_drive(file, &s.file_where, reading, from_rest)
                                             : drive_from_table(read_table(file, &s.file_where), reading, from_rest);
  require_within((static_cast<double>(measured.time.size()) - 1.0) * s.substeps + 1.0, lang::max_drive_samples, c.protocol,
                 "samples (rows x substeps)", "lower substeps or split the file");
  return history_run(c, s, refine(measured, s.substeps), fmt::format("history file={}", file));
}

ProtocolResult run(RunContext& c, const lang::StepSettings& s) {
  require_within(std::ceil(s.duration / s.dt), lang::max_drive_samples, c.protocol, "samples (duration / dt)", "raise dt or shorten duration");
  return history_run(c, s, step_relaxation(s.amplitude, s.rise, s.duration, s.dt),
                     fmt::format("step amplitude={:g} mm duration={:g} s", s.amplitude, s.duration));
}

}  // namespace

// A yeoh in the root block follows the drive; past YeohLaw::softening_elongation its
// tangent is negative: the force is still the law's, but the law is extrapolated.
std::string yeoh_softening_note(const Network& network, double reach) {
  std::string note;
  for (const ElementProbe& probe : network.topology().probes) {
    if (probe.source != ElementProbe::Source::root_yeoh) continue;
    const auto& y = network.topology().yeohs[static_cast<std::size_t>(probe.index)];
    const YeohLaw law{network.parameter(y[0]), network.parameter(y[1]), network.parameter(y[2])};
    const double e = law.softening_elongation();
    if (e < reach)
      note += fmt::format(
          "warning: yeoh '{}' softens to zero tangent stiffness at |e| = {:.6g} mm (eq. 3.3) and the drive reaches "
          "{:g} mm: its force falls beyond that; {}\n",
          probe.path, e, reach, YeohLaw::monotone_advice);
  }
  return note;
}

std::string history_solver_note(const Network& network, SolverChoice solver) {
  return uses_sundials(network, solver) ? fmt::format(" solver=sundials (IDA, rtol {:g})", kDaeRelativeTolerance) : std::string();
}

std::string history_file(const lang::HistorySettings& s, const std::string& source_file) {
  std::filesystem::path file = s.file;
  if (file.is_relative()) file = std::filesystem::path(source_file).parent_path() / file;
  return file.string();
}

ProtocolResult run_protocol(const Network& network, const Protocol& p, const std::string& source_file, int threads) {
  RunContext context{network, p, source_file, threads, {network.model().name, source_file, lang::protocol_name(p.kind)}};
  return std::visit([&](const auto& settings) { return run(context, settings); }, p.settings);
}

}  // namespace rheo::runtime
