#include "runtime/fmu/cosimulation.hpp"

#include "lang/frontend.hpp"
#include "lang/limits.hpp"
#include "lang/names.hpp"
#include "lang/text_encoding.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/stepping/relaxed_state.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rheo::runtime::fmu {
namespace {

// Whether two communication times are the same point, within the rounding of a host that adds
// step sizes up.
bool same_time(double a, double b, double h) { return std::abs(a - b) <= 1e-9 * std::max({std::abs(a), std::abs(b), h}); }

// A jump of the input within a few ulps of where the terminal is (8 epsilon of the larger
// magnitude: 4 to 8 ulps): rounding, not a jump.
bool rounding_only(double from, double to) {
  return std::abs(to - from) <= 8.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(from), std::abs(to));
}

}  // namespace

std::string CoSimulation::call(const char* name) const { return fmt::format("fmi{}{}", static_cast<int>(fmi_), name); }

std::string CoSimulation::phase_name(Phase p) const {
  switch (p) {
    case Phase::instantiated: return fmt::format("instantiated (before {})", call("EnterInitializationMode"));
    case Phase::initialization: return "in initialisation mode";
    case Phase::stepping: return fmt::format("stepping (after {})", call("ExitInitializationMode"));
    case Phase::terminated: return "terminated";
  }
  return "?";
}

CoSimulation::CoSimulation(const std::string& file_name, std::string_view source, const std::string& model_name, FmiVersion fmi)
    : program_(std::make_shared<const lang::Program>(lang::compile_source(file_name, source))), fmi_(fmi) {
  model_ = program_->find_model(model_name);
  if (!model_) {
    std::vector<std::string> names;
    for (const auto& m : program_->models) names.push_back(m.name);
    throw ModelError(fmt::format("{}: error: there is no model '{}';{} the models are {}", file_name, lang::printable(model_name),
                                 lang::did_you_mean(model_name, names), lang::join(names)));
  }
  variables_ = fmu_variables(*model_);
  compiled_ = std::make_unique<Network>(Network::compile(*model_));
  root_only_ = compiled_->topology().subtrees.empty();
  jump_hold_ = !root_only_ && JumpHoldStep::applies(compiled_->topology());
  now_.parameters = compiled_->parameters();
}

const Variable& CoSimulation::variable(unsigned reference) const {
  if (reference >= variables_.size())
    throw UsageError(fmt::format("model '{}' has no variable of value reference {} (its references are 0 to {})", model_->name, reference,
                                 variables_.size() - 1));
  return variables_[reference];
}

Network CoSimulation::network_with(const std::vector<double>& parameters) const { return compiled_->with_parameters(parameters); }

void CoSimulation::setup_experiment(double start_time, std::optional<double> stop_time) {
  if (now_.phase != Phase::instantiated)
    throw UsageError(fmt::format("{} is called before initialisation, not {}", call("SetupExperiment"), phase_name(now_.phase)));
  if (!std::isfinite(start_time)) throw DataError(fmt::format("start time {} s: it must be a finite number", start_time));
  if (stop_time && !(*stop_time >= start_time))
    throw DataError(fmt::format("stop time {} s lies before the start time {} s", *stop_time, start_time));
  start_time_ = start_time;
  stop_time_ = stop_time;
  now_.time = start_time;
}

void CoSimulation::enter_initialization() {
  if (now_.phase != Phase::instantiated)
    throw UsageError(fmt::format("{} is called once after instantiation, not {}", call("EnterInitializationMode"), phase_name(now_.phase)));
  now_.phase = Phase::initialization;
}

void CoSimulation::enter_initialization(double start_time, std::optional<double> stop_time) {
  if (now_.phase != Phase::instantiated)
    throw UsageError(fmt::format("{} is called once after instantiation, not {}", call("EnterInitializationMode"), phase_name(now_.phase)));
  setup_experiment(start_time, stop_time);
  now_.phase = Phase::initialization;
}

void CoSimulation::start_network() {
  auto network = std::make_unique<Network>(network_with(now_.parameters));
  State relaxed = relaxed_state(*network, now_.input);
  simulator_ = std::make_unique<Simulator>(*network);
  network_ = std::move(network);
  now_.parameters = network_->parameters();
  now_.state = std::move(relaxed);
  mid_ = next_ = now_.state;
  plans_ = Plans{};
}

void CoSimulation::exit_initialization() {
  if (now_.phase != Phase::initialization)
    throw UsageError(fmt::format("{} is called in initialisation mode, not {}", call("ExitInitializationMode"), phase_name(now_.phase)));
  start_network();
  now_.phase = Phase::stepping;
  now_.time = start_time_;
}

void CoSimulation::terminate() {
  if (now_.phase != Phase::stepping)
    throw UsageError(fmt::format("{} is called after initialisation, not {}", call("Terminate"), phase_name(now_.phase)));
  now_.phase = Phase::terminated;
}

void CoSimulation::reset() {
  now_ = Snapshot{};
  now_.parameters = compiled_->parameters();
  network_.reset();
  simulator_.reset();
  start_time_ = 0.0;
  stop_time_.reset();
  plans_ = Plans{};
}

void CoSimulation::set_real_checked(unsigned reference, double value) {
  const Variable& v = variable(reference);
  switch (v.causality) {
    case Causality::output: throw UsageError(fmt::format("{} is the FMU's output: it cannot be set", v.name));
    case Causality::calculated_parameter:
      throw UsageError(fmt::format("{} is computed from other parameters (a calculatedParameter): set those instead", v.name));
    case Causality::parameter:
      if (now_.phase != Phase::instantiated && now_.phase != Phase::initialization)
        throw UsageError(fmt::format("parameter {} is fixed once initialisation ends; the FMU is {}: set it before {}", v.name,
                                     phase_name(now_.phase), call("ExitInitializationMode")));
      break;
    case Causality::input:
      if (now_.phase == Phase::terminated) throw UsageError(fmt::format("input {} cannot be set: the FMU is terminated", v.name));
      break;
    case Causality::independent:
      throw UsageError(fmt::format("{} is the independent variable: {} sets it, {} advances it", v.name,
                                   call(fmi_ == FmiVersion::fmi2 ? "SetupExperiment" : "EnterInitializationMode"), call("DoStep")));
  }
  if (std::isnan(value) || std::isinf(value)) throw DataError(fmt::format("{} = {}: it must be a finite number", v.name, value));
  if ((v.min && value < *v.min) || (v.max && value > *v.max))
    throw DataError(fmt::format("{} = {} {} lies outside its range [{}, {}] (modelDescription.xml min and max)", v.name, value, v.unit,
                                v.min ? fmt::format("{}", *v.min) : std::string("-inf"), v.max ? fmt::format("{}", *v.max) : std::string("inf")));
  if (reference == kInputU) now_.input = value;
  else if (reference == kInputV) now_.input_velocity = value;
  else now_.parameters[static_cast<std::size_t>(v.parameter)] = value;
}

double CoSimulation::get_real_checked(unsigned reference) const {
  const bool started = now_.phase == Phase::stepping || now_.phase == Phase::terminated;
  const Variable& v = variable(reference);
  switch (v.causality) {
    case Causality::input: return reference == kInputU ? now_.input : now_.input_velocity;
    case Causality::output:
      if (started) return now_.state.force;
      return relaxed_state(network_with(now_.parameters), now_.input).force;  // what initialisation will start from
    case Causality::calculated_parameter:
      if (!started) return network_with(now_.parameters).parameters()[static_cast<std::size_t>(v.parameter)];
      break;
    case Causality::parameter: break;
    case Causality::independent: return now_.time;
  }
  return now_.parameters[static_cast<std::size_t>(v.parameter)];
}

void CoSimulation::set_input_derivative_checked(unsigned reference, int order, double value) {
  const Variable& v = variable(reference);
  if (reference != kInputU) throw UsageError(fmt::format("{} is not the input u: only u takes input derivatives", v.name));
  if (order != 1)
    throw UsageError(fmt::format("derivative of order {} of u: the FMU follows the first derivative only (a ramp over the step)", order));
  if (now_.phase != Phase::stepping && now_.phase != Phase::initialization)
    throw UsageError(fmt::format("input derivatives are set between steps; the FMU is {}", phase_name(now_.phase)));
  if (!std::isfinite(value)) throw DataError(fmt::format("du/dt = {} mm/s: it must be a finite number", value));
  now_.input_rate = value;
  now_.rate_set = true;
}

void CoSimulation::prepare_plans(double h) {
  const Network& n = *network_;
  const double delta = h * kJumpFraction;
  plans_.h = h;
  plans_.whole = StepPlan::make(n, h);
  plans_.jump = StepPlan::make(n, delta);
  plans_.rest = StepPlan::make(n, h - delta);
  // Jump then hold, for root blocks only: a Maxwell arm F <- a (F + k du), a dashpot nothing.
  plans_.held = plans_.whole;
  const auto& k = n.coefficients().maxwell_k;
  for (std::size_t i = 0; i < k.size(); ++i) plans_.held.maxwell_b[i] = plans_.held.maxwell_a[i] * k[i];
  plans_.held.dashpot_c_over_dt = 0.0;
  if (jump_hold_) plans_.jump_hold.emplace(n, h, delta);
  else plans_.jump_hold.reset();
}

// Why a step cannot be taken (the same tests as do_step's, one at a time, off its path).
void CoSimulation::refuse_step(double t, double h) const {
  if (now_.phase != Phase::stepping)
    throw UsageError(fmt::format("{} is called after initialisation, not {}", call("DoStep"), phase_name(now_.phase)));
  if (!(h > 0.0) || !std::isfinite(h)) throw UsageError(fmt::format("communication step size {} s: it must be a positive, finite number", h));
  if (!std::isfinite(t) || !same_time(t, now_.time, h))
    throw UsageError(
        fmt::format("{} from t = {} s, but the FMU is at t = {} s (the end of its last step); restore an FMU state ({}) to step from elsewhere",
                    call("DoStep"), t, now_.time, fmi_ == FmiVersion::fmi2 ? "fmi2SetFMUstate" : "fmi3SetFMUState"));
  if (!(t + h > t)) throw UsageError(fmt::format("communication step size {} s is below the resolution of the time t = {} s", h, t));
  if (stop_time_ && !(t + h <= *stop_time_) && !same_time(t + h, *stop_time_, h))
    throw UsageError(fmt::format("a step of {} s from t = {} s ends past the stop time {} s ({})", h, t, *stop_time_,
                                 call(fmi_ == FmiVersion::fmi2 ? "SetupExperiment" : "EnterInitializationMode")));
  const double u = now_.input, rate = now_.rate_set ? now_.input_rate : now_.input_velocity, target = u + rate * h;
  throw DataError(fmt::format("u = {} mm with du/dt = {} mm/s reaches {} mm at the step's end, outside [-{}, {}] mm", u, rate, target,
                              lang::max_amplitude, lang::max_amplitude));
}

void CoSimulation::do_step(double t, double h) {
  const double u = now_.input, rate = now_.rate_set ? now_.input_rate : now_.input_velocity, target = u + rate * h;
  const bool ok = now_.phase == Phase::stepping && h > 0.0 && h <= std::numeric_limits<double>::max() &&
                  (t == now_.time || same_time(t, now_.time, h)) && t + h > t &&
                  (!stop_time_ || t + h <= *stop_time_ || same_time(t + h, *stop_time_, h)) && std::abs(target) <= lang::max_amplitude;
  if (!ok) refuse_step(t, h);
  if (plans_.h == 0.0 || std::abs(h - plans_.h) > 1e-9 * h) prepare_plans(h);  // the tolerance of run_history.cpp
  const State& before = now_.state;
  if (before.u == u || rounding_only(before.u, u)) {
    simulator_->step(plans_.whole, before, target, next_, t + h);
  } else if (rate == 0.0 && root_only_) {
    simulator_->step(plans_.held, before, u, next_, t + h);
  } else if (rate == 0.0 && jump_hold_) {
    plans_.jump_hold->step(*simulator_, before, u, next_);
  } else {
    const double delta = h * kJumpFraction;
    simulator_->step(plans_.jump, before, u + rate * delta, mid_, t + delta);
    simulator_->step(plans_.rest, mid_, target, next_, t + h);
  }
  now_.state.values.swap(next_.values);
  now_.state.u = next_.u;
  now_.state.force = next_.force;
  now_.time = t + h;
  now_.input_rate = 0.0;
  now_.rate_set = false;
}

void CoSimulation::restore(const Snapshot& s) {
  const bool started = s.phase == Phase::stepping || s.phase == Phase::terminated;
  if (s.parameters.size() != model_->parameters.size() ||
      (started && s.state.values.size() != static_cast<std::size_t>(compiled_->topology().state_size)))
    throw DataError(fmt::format("the FMU state is not one of model '{}' (its sizes differ)", model_->name));
  if (started && (!network_ || network_->parameters() != s.parameters)) {
    auto network = std::make_unique<Network>(network_with(s.parameters));
    simulator_ = std::make_unique<Simulator>(*network);
    network_ = std::move(network);
    plans_ = Plans{};
  }
  now_ = s;
  if (started) mid_ = next_ = now_.state;
}

}  // namespace rheo::runtime::fmu
