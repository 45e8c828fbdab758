// One co-simulation instance of an exported model: what the FMU binary's fmi2* and fmi3* entry
// points (fmi2_entry_points.cpp, fmi3_entry_points.cpp) serve, in C++ with typed errors, so that
// tests and benchmarks drive it without a host. The two versions differ only in how a host starts
// initialisation (FMI 3.0 passes the experiment's times to fmi3EnterInitializationMode) and in the
// function names the messages cite.
//
// Input path over a communication step [t, t + h] (docs/numerics.md#fmu-input-between-communication-points):
//   u(s) = u_n + v_n (s - t),
// u_n the input set before the step, v_n its derivative for this step (fmi2SetRealInputDerivatives;
// FMI 3.0 co-simulation has no such call) or else the input v as last set (0, its start value: zero-order hold). Where u_n differs from
// where the terminal is (the end of the last step), the terminal jumps to u_n at t. The kernels
// are the fixed-step ones of `rheo simulate --solver fixed` (stepping/simulator.hpp), exact for a
// piecewise-linear drive; a jump is taken
//   - exactly, where every element sits in the root parallel block and the input is held: the
//     step's coefficients become those of a jump followed by a hold (a Maxwell arm's
//     F <- a (F + k du), a root dashpot carries nothing at the step's end), one kernel pass;
//   - otherwise as a ramp over the first h / 2^10 of the step (kJumpFraction), then the rest of
//     the step: the two kernel passes, or where the input is held and every subtree is linear
//     or a capped-linear chain (the hydrobushing's fluid branch), both at once in one pass
//     (stepping/jump_hold.hpp), the same to rounding. For a Maxwell arm of time constant tau that differs from an
//     instantaneous jump by (h / 2^10) / (2 tau) of the jump's force in it. A shorter ramp would
//     be closer to the jump but ill-conditioned behind an inerter, whose step relation has the
//     slope 4 b / dt^2: at h / 2^20 the hydrobushing's force after 400 steps moves by 3e-8 of
//     itself when the ramp's length moves by 1e-9; at h / 2^10 by 1.4e-11, and it lies within
//     3e-6 of the limit of ever shorter ramps.
// The force F returned at t + h is the kernels' result for that path. A jump of a few ulps (a
// host's extrapolation that lands within rounding of its next input) is no jump.
//
// Errors (each a typed UserError, nothing changed by the call that throws it):
//   UsageError      a call out of sequence, an unknown value reference, a variable that cannot be
//                   set now, a step that does not start where the last ended, a step size <= 0,
//                   not finite, or past the stop time;
//   DataError       a value that is NaN, infinite or outside the variable's [min, max];
//   ModelError      parameter values the model cannot take (at the end of initialisation);
//   NumericalError  a step whose solve fails (tree_solver.hpp), named by its time.
#pragma once

#include "lang/limits.hpp"
#include "lang/model.hpp"
#include "runtime/fmu/fmu_variables.hpp"
#include "runtime/network/network.hpp"
#include "runtime/stepping/jump_hold.hpp"
#include "runtime/stepping/simulator.hpp"

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rheo::runtime::fmu {

// The fraction of a communication step over which a jump of the input is ramped (see above).
inline constexpr double kJumpFraction = 1.0 / 1024.0;  // 2^-10

// Co-simulation states (FMI 2.0 section 4.2.4; FMI 3.0 section 4.2, without event mode: stepping
// is its Step Mode), as far as they change what a call may do.
enum class Phase { instantiated, initialization, stepping, terminated };

// The standard whose entry points drive the instance: only the function names in messages differ.
enum class FmiVersion { fmi2 = 2, fmi3 = 3 };

// Everything a step changes, and the parameters: an FMU state (fmi2GetFMUstate, fmi3GetFMUState).
struct Snapshot {
  Phase phase = Phase::instantiated;
  double time = 0.0;               // s, the current communication point
  double input = 0.0;              // mm, u as last set
  double input_velocity = 0.0;     // mm/s, v as last set
  double input_rate = 0.0;         // mm/s, u's derivative for the next step, where set
  bool rate_set = false;           // whether it is (fmi2SetRealInputDerivatives since the last step)
  std::vector<double> parameters;  // the model's, internal units
  State state;                     // the network's at `time` (empty before initialisation ends)
};

class CoSimulation {
 public:
  // Compiles model MODEL_NAME of SOURCE (named FILE_NAME in messages). CompileError, ModelError.
  CoSimulation(const std::string& file_name, std::string_view source, const std::string& model_name, FmiVersion fmi = FmiVersion::fmi2);

  const lang::CheckedModel& model() const { return *model_; }
  const std::vector<Variable>& variables() const { return variables_; }
  Phase phase() const { return now_.phase; }
  double time() const { return now_.time; }

  void setup_experiment(double start_time, std::optional<double> stop_time);
  void enter_initialization();
  // FMI 3.0's fmi3EnterInitializationMode: setup_experiment and enter_initialization in one call,
  // which changes nothing when it throws.
  void enter_initialization(double start_time, std::optional<double> stop_time);
  // The network with the parameters as set, relaxed at the input u (stepping/relaxed_state.hpp).
  void exit_initialization();
  void terminate();
  void reset();  // back to instantiated, every variable at its start value

  void set_real(unsigned reference, double value) {
    if (!set_input_fast(reference, value)) set_real_checked(reference, value);
  }
  double get_real(unsigned reference) const {
    double value = 0.0;
    return get_output_fast(reference, value) ? value : get_real_checked(reference);
  }
  // ORDER 1: du/dt [mm/s] of u for the next step, in place of v (higher orders: UsageError).
  void set_input_derivative(unsigned reference, int order, double value) {
    if (!set_rate_fast(reference, order, value)) set_input_derivative_checked(reference, order, value);
  }
  // The calls a host makes every step, as they usually come: u or v set while stepping, F read
  // once stepping has begun, du/dt of u set while stepping. Each does what the call above does
  // and returns true, or changes nothing and returns false (the call above then decides, and
  // names what is wrong). The entry points try them before their guard (fmi2_entry_points.cpp).
  bool set_input_fast(unsigned reference, double value) noexcept {
    if (now_.phase != Phase::stepping) return false;
    if (reference == kInputU && std::abs(value) <= lang::max_amplitude) now_.input = value;
    else if (reference == kInputV && std::isfinite(value)) now_.input_velocity = value;
    else return false;
    return true;
  }
  bool get_output_fast(unsigned reference, double& value) const noexcept {
    if (reference != kOutputF || (now_.phase != Phase::stepping && now_.phase != Phase::terminated)) return false;
    value = now_.state.force;
    return true;
  }
  bool set_rate_fast(unsigned reference, int order, double value) noexcept {
    if (reference != kInputU || order != 1 || now_.phase != Phase::stepping || !std::isfinite(value)) return false;
    now_.input_rate = value;
    now_.rate_set = true;
    return true;
  }
  void do_step(double t, double h);

  Snapshot snapshot() const { return now_; }
  void restore(const Snapshot& s);
  // A byte string of S that deserialize() of an instance of the same model reads back;
  // deserialize throws DataError for bytes that are not one.
  std::string serialize(const Snapshot& s) const;
  Snapshot deserialize(std::string_view bytes) const;

 private:
  struct Plans {
    double h = 0.0;
    StepPlan whole, jump, rest, held;
    std::optional<JumpHoldStep> jump_hold;  // where jump_hold_ (the ramp and the hold in one pass)
  };

  void set_real_checked(unsigned reference, double value);
  double get_real_checked(unsigned reference) const;
  void set_input_derivative_checked(unsigned reference, int order, double value);
  const Variable& variable(unsigned reference) const;
  Network network_with(const std::vector<double>& parameters) const;
  void prepare_plans(double h);
  void start_network();
  [[noreturn]] void refuse_step(double t, double h) const;
  // "fmi2NAME" or "fmi3NAME", for messages.
  std::string call(const char* name) const;
  std::string phase_name(Phase p) const;

  std::shared_ptr<const lang::Program> program_;
  const lang::CheckedModel* model_ = nullptr;
  std::vector<Variable> variables_;
  std::unique_ptr<Network> compiled_;  // with the source's parameter values
  std::unique_ptr<Network> network_;   // with the values set, from the end of initialisation
  std::unique_ptr<Simulator> simulator_;
  Plans plans_;
  bool root_only_ = false;  // every element in the model's body: a held input's jump is exact in one pass
  bool jump_hold_ = false;  // every subtree piecewise affine: a held input's ramp and hold in one pass
  Snapshot now_;
  State mid_, next_;
  double start_time_ = 0.0;
  std::optional<double> stop_time_;
  FmiVersion fmi_ = FmiVersion::fmi2;
};

}  // namespace rheo::runtime::fmu
