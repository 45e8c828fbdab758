#include "runtime/run_protocols.hpp"

#include "lang/limits.hpp"
#include "runtime/drives.hpp"
#include "runtime/errors.hpp"
#include "runtime/dae_protocols.hpp"
#include "runtime/harmonic.hpp"
#include "runtime/history_csv.hpp"
#include "runtime/leaf_kernels.hpp"
#include "runtime/output.hpp"
#include "runtime/periodic_closed_form.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace rheo::runtime {
namespace {

using lang::Protocol;

double number(const Protocol& p, const char* key, double fallback) {
  const lang::Setting* s = p.find(key);
  return s && !s->values.empty() ? s->values.front() : fallback;
}
std::vector<double> numbers(const Protocol& p, const char* key) {
  const lang::Setting* s = p.find(key);
  return s ? s->values : std::vector<double>{};
}
std::string word(const Protocol& p, const char* key, const char* fallback) {
  const lang::Setting* s = p.find(key);
  return s && !s->text.empty() ? s->text : fallback;
}

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
      note += fmt::format("warning: yeoh '{}' softens to zero tangent stiffness at |e| = {:.6g} mm (eq. 3.3) and the drive reaches "
                          "{:g} mm: its force falls beyond that; {}\n",
                          probe.path, e, reach, YeohLaw::monotone_advice);
  }
  return note;
}

void finish_history(const Network& network, const Protocol& p, const ResultHeader& header, const History& h, ProtocolRun& run) {
  run.points = static_cast<int>(h.time.size());
  run.content = word(p, "format", "csv") == "json" ? history_json(header, h) : history_csv(header, h);
  double reach = 0.0;
  for (double u : h.displacement) reach = std::max(reach, std::abs(u));
  run.notes += yeoh_softening_note(network, reach);
}

}  // namespace

const char* protocol_name(lang::ProtocolKind kind) {
  switch (kind) {
    case lang::ProtocolKind::harmonic: return "harmonic";
    case lang::ProtocolKind::static_triangle: return "static";
    case lang::ProtocolKind::quasistatic: return "quasistatic";
    case lang::ProtocolKind::history: return "history";
    case lang::ProtocolKind::step: return "step";
  }
  return "?";
}

namespace {
// The work limits of lang/limits.hpp, checked before a drive or grid is built.
void require_within(double amount, long limit, const Protocol& p, const char* what, const char* advice) {
  if (!(amount <= static_cast<double>(limit)))
    throw ModelError(fmt::format("{}the {} protocol asks for {:.4g} {}, more than the limit of {}; {}", error_at(p.where),
                                 protocol_name(p.kind), amount, what, limit, advice));
}

// Histories name the backend in their header when it is not the fixed-step one.
std::string solver_note(const Network& network, SolverChoice solver) {
  return uses_sundials(network, solver) ? fmt::format(" solver=sundials (IDA, rtol {:g})", kDaeRelativeTolerance) : std::string();
}
}  // namespace

ProtocolRun run_protocol(const Network& network, const Protocol& p, const std::string& source_file, int threads) {
  ProtocolRun run;
  ResultHeader header{network.model().name, source_file, protocol_name(p.kind)};
  const bool elements = word(p, "elements", "none") == "all";
  const SolverChoice solver = parse_solver_choice(word(p, "solver", "auto")).value_or(SolverChoice::automatic);
  switch (p.kind) {
    case lang::ProtocolKind::harmonic: {
      HarmonicOptions options;
      options.definition = word(p, "definition", "thesis") == "first_harmonic" ? HarmonicDefinition::first_harmonic
                                                                              : HarmonicDefinition::thesis;
      const std::string steady_state = word(p, "steady_state", "auto");
      options.steady_state = steady_state == "closed_form"     ? SteadyState::closed_form
                             : steady_state == "time_stepping" ? SteadyState::time_stepping
                                                               : SteadyState::automatic;
      options.steps_per_cycle = static_cast<int>(number(p, "steps_per_cycle", options.steps_per_cycle));
      options.max_cycles = static_cast<int>(number(p, "cycles_max", options.max_cycles));
      options.tolerance = number(p, "tolerance", options.tolerance);
      options.solver = solver;
      options.threads = threads;
      if (options.steady_state == SteadyState::closed_form && solver == SolverChoice::sundials)
        throw UsageError(fmt::format("{}:{}:{}: steady_state = closed_form and the SUNDIALS solver exclude each other; "
                                     "drop one (solver = fixed with closed_form, or steady_state = auto)",
                                     p.where.file, p.where.line, p.where.column));
      if (options.steady_state == SteadyState::closed_form && !has_closed_form_periodic_state(network))
        throw UsageError(fmt::format("{}:{}:{}: steady_state = closed_form needs every non-linear element of model '{}' in its "
                                     "parallel body, and no quadratic_dashpot, gap or bouc_wen: use steady_state = auto or time_stepping",
                                     p.where.file, p.where.line, p.where.column, network.model().name));
      require_within(static_cast<double>(numbers(p, "amplitude").size()) * static_cast<double>(numbers(p, "frequency").size()),
                     lang::max_harmonic_points, p, "points (amplitudes x frequencies)", "split the grid over several protocols");
      require_within(static_cast<double>(options.steps_per_cycle) * options.max_cycles, lang::max_steps_per_point, p,
                     "time steps per point (steps_per_cycle x cycles_max)", "lower steps_per_cycle or cycles_max");
      const auto points = simulate_harmonic_grid(network, numbers(p, "amplitude"), numbers(p, "frequency"), options);
      header.protocol = uses_closed_form(network, options) ? std::string("harmonic steady_state=closed_form")
                        : uses_sundials(network, solver)
                            ? fmt::format("harmonic solver=sundials (IDA, rtol {:g}) samples_per_cycle={} tolerance={:g}",
                                          kDaeRelativeTolerance, options.steps_per_cycle, std::max(options.tolerance, 100.0 * kDaeRelativeTolerance))
                            : fmt::format("harmonic steady_state=time_stepping steps_per_cycle={} tolerance={:g}",
                                          options.steps_per_cycle, options.tolerance);
      for (const auto& point : points)
        if (!point.converged) {
          ++run.not_converged;
          run.notes += fmt::format(
              "warning: amplitude {:g} mm, frequency {:g} Hz did not reach steady state in {} cycles (residual {:.2e}); "
              "raise cycles_max or loosen tolerance\n",
              point.amplitude, point.frequency, point.cycles, point.residual);
        }
      for (const auto& point : points)
        if (point.measures.damping_clamped) {
          run.notes += fmt::format("warning: amplitude {:g} mm, frequency {:g} Hz: normalised damping {:.4f} > 1, phase reported as 90 deg\n",
                                   point.amplitude, point.frequency, point.measures.damping);
          break;
        }
      const auto amplitudes = numbers(p, "amplitude");
      run.notes += yeoh_softening_note(network, *std::max_element(amplitudes.begin(), amplitudes.end()));
      run.points = static_cast<int>(points.size());
      run.content = word(p, "format", "csv") == "json" ? harmonic_json(header, points, options.definition)
                                                        : harmonic_csv(header, points, options.definition);
      return run;
    }
    case lang::ProtocolKind::static_triangle: {
      const auto amplitudes = numbers(p, "amplitude");
      const double velocity = number(p, "velocity", 0.0);
      const int cycles = static_cast<int>(number(p, "cycles", 2));
      constexpr int steps_per_cycle = 400;
      // With dt, each of a cycle's steps is cut into ceil(step time / dt) parts.
      const lang::Setting* dt = p.find("dt");
      double samples = 0.0;
      for (double a : amplitudes)
        samples += static_cast<double>(cycles) * steps_per_cycle *
                   (dt ? std::max(1.0, std::ceil(4.0 * a / (steps_per_cycle * velocity * dt->values.front()))) : 1.0);
      require_within(samples, lang::max_drive_samples, p, "samples", "raise dt or velocity, or give fewer cycles or amplitudes");
      Drive drive = static_triangle(amplitudes, velocity, cycles, steps_per_cycle);
      if (dt) {
        // A fixed sample interval: resample each quarter cycle with that step.
        Drive fine;
        fine.time.assign(1, 0.0);
        fine.displacement.assign(1, 0.0);
        for (std::size_t k = 1; k < drive.time.size(); ++k) {
          const int parts = std::max(1, static_cast<int>(std::ceil((drive.time[k] - drive.time[k - 1]) / dt->values.front() - 1e-9)));
          Drive piece{{drive.time[k - 1], drive.time[k]}, {drive.displacement[k - 1], drive.displacement[k]}};
          Drive refined = refine(piece, parts);
          fine.time.insert(fine.time.end(), refined.time.begin() + 1, refined.time.end());
          fine.displacement.insert(fine.displacement.end(), refined.displacement.begin() + 1, refined.displacement.end());
        }
        drive = std::move(fine);
      }
      header.protocol = fmt::format("static velocity={:g} mm/s cycles={}", velocity, cycles);
      header.protocol += solver_note(network, solver);
      const History h = run_history(network, drive, elements, solver);
      finish_history(network, p, header, h, run);
      return run;
    }
    case lang::ProtocolKind::quasistatic: {
      const int cycles = static_cast<int>(number(p, "cycles", 2));
      const int steps = static_cast<int>(number(p, "steps_per_cycle", 400));
      const double frequency = number(p, "frequency", 0.0);
      require_within(static_cast<double>(numbers(p, "amplitude").size()) * cycles * steps, lang::max_drive_samples, p, "samples",
                     "lower steps_per_cycle, or give fewer cycles or amplitudes");
      header.protocol = fmt::format("quasistatic frequency={:g} Hz cycles={}", frequency, cycles);
      header.protocol += solver_note(network, solver);
      const History h = run_history(network, quasistatic_sine(numbers(p, "amplitude"), frequency, cycles, steps), elements, solver);
      finish_history(network, p, header, h, run);
      return run;
    }
    case lang::ProtocolKind::history: {
      std::filesystem::path file = word(p, "file", "");
      if (file.is_relative()) file = std::filesystem::path(source_file).parent_path() / file;
      const Drive measured = drive_from_table(read_table(file.string(), &p.find("file")->where));
      const int substeps = static_cast<int>(number(p, "substeps", 1));
      require_within((static_cast<double>(measured.time.size()) - 1.0) * substeps + 1.0, lang::max_drive_samples, p,
                     "samples (rows x substeps)", "lower substeps or split the file");
      const Drive drive = refine(measured, substeps);
      header.protocol = fmt::format("history file={}", file.string());
      header.protocol += solver_note(network, solver);
      const History h = run_history(network, drive, elements, solver);
      finish_history(network, p, header, h, run);
      return run;
    }
    case lang::ProtocolKind::step: {
      const double duration = number(p, "duration", 1.0);
      const double dt = number(p, "dt", duration / 1000.0);
      const double amplitude = number(p, "amplitude", 0.0);
      require_within(std::ceil(duration / dt), lang::max_drive_samples, p, "samples (duration / dt)", "raise dt or shorten duration");
      header.protocol = fmt::format("step amplitude={:g} mm duration={:g} s", amplitude, duration);
      header.protocol += solver_note(network, solver);
      const History h = run_history(network, step_relaxation(amplitude, number(p, "rise", dt), duration, dt), elements, solver);
      finish_history(network, p, header, h, run);
      return run;
    }
  }
  throw std::logic_error("unknown protocol");
}

}  // namespace rheo::runtime
