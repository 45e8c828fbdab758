// Variable-step integration of a DaeGraph with SUNDIALS IDA (variable-order BDF), with events
// where an element switches.
//
// Unknowns y = [x (internal node positions, mm, algebraic) | lambda (slider and gap forces, N,
// algebraic) | s (rate coordinates, mm, differential; dae_modes.hpp) | w (velocities of inerter
// coordinates, mm/s, differential) | z (Bouc-Wen states, -, differential)]. Residuals:
//   node balance      sum of edge forces pulling the node = 0
//   slider / gap      stuck or closed: e - e_held = 0;  slipping: lambda -+ fy = 0;  open: lambda = 0
//   coordinate j      s_j - e_j(x, u) = 0                (slots beyond q: s' = 0)
//   inerter coord j   w_j - s_j' = 0                     (unused slots: w' = 0)
//   Bouc-Wen          z' - (k/fy) e' (1 - |z|^n (1 + sgn(z d))/2) = 0, e' from the node rates,
//                     d = +-1 the direction of e' fixed between events (dae_bouc_wen.cpp); the
//                     sign of the drive's rate u' for a bouc_wen between terminal and ground
// Events (IDA root functions, two per switch edge, then one per Bouc-Wen state): a stuck
// slider's force reaches +-fy; a slipping slider's rate crosses zero; an open gap's elongation
// reaches +-w/2; a closed gap's force changes sign; a bouc_wen's e' crosses a band around zero
// against d. At an event the mode changes, the coordinates are re-chosen, IDA is re-initialised
// and IDACalcIC makes the algebraic unknowns and the rates consistent; at a Bouc-Wen root d
// flips and IDA goes on (the law is continuous there; dae_bouc_wen.cpp).
//
// The drive is a sine (its rate and acceleration exact) or piecewise linear: each sample is a
// stop time at which the rate jumps, and the integration restarts there.
#pragma once

#include "runtime/dae/dae_graph.hpp"
#include "runtime/dae/dae_linear_start.hpp"
#include "runtime/dae/dae_modes.hpp"
#include "runtime/core/drive.hpp"

#include <exception>
#include <memory>
#include <string>
#include <vector>

namespace rheo::runtime {

struct DriveSignal {
  enum class Kind { sine, samples } kind = Kind::sine;
  double amplitude = 0.0;          // sine: u = amplitude sin(omega t) [mm]
  double omega = 0.0;              // rad/s
  const Drive* samples = nullptr;  // samples: linear between them; not owned
  double offset = 0.0;             // sine: u = offset + amplitude sin(omega t) [mm]
  // samples: the whole drive's duration [s] where `samples` holds a window of it (slide()); 0:
  // that of `samples`. It sets the time scale of restarts (time_horizon).
  double duration = 0.0;
};

struct DaeOptions {
  double relative_tolerance = 1e-8;
  double length_scale = 1.0;    // mm: absolute tolerance of positions is rtol * this
  double force_scale = 1.0;     // N
  double velocity_scale = 1.0;  // mm/s
  // IDA's Newton convergence coefficient (IDASetNonlinConvCoef; IDA's default 0.33): the
  // corrector stops when its estimated error is this fraction of the local error weights.
  double newton_tolerance = 0.33;
  long max_steps = 500000;  // per advance()
};

// Where each block of the unknowns lies in y (the layout above): positions x, then switch forces
// lambda, rate coordinates s, inerter velocities w and Bouc-Wen states z, each block in the
// order of its DaeGraph list (switch_edges, rate_edges, bouc_wen_edges).
struct DaeLayout {
  enum class Block { position, switch_force, rate_coordinate, inerter_velocity, bouc_wen_state };
  int positions = 0, switch_forces = 0, rate_coordinates = 0, inerter_velocities = 0, bouc_wen_states = 0;

  static DaeLayout of(const DaeGraph& graph);
  int switch_force(int l) const { return positions + l; }
  int rate_coordinate(int k) const { return switch_force(switch_forces) + k; }
  int inerter_velocity(int v) const { return rate_coordinate(rate_coordinates) + v; }
  int bouc_wen_state(int b) const { return inerter_velocity(inerter_velocities) + b; }
  int size() const { return bouc_wen_state(bouc_wen_states); }
  Block block_of(int i) const;
  // IDA's id vector: s, w and z are differential, x and lambda algebraic.
  bool differential(int i) const { return i >= rate_coordinate(0); }
};

struct DaeStatistics {
  long steps = 0;
  long residual_evaluations = 0;
  long events = 0;
};

class DaeIntegrator {
 public:
  DaeIntegrator(const DaeGraph& graph, const DaeOptions& options);
  ~DaeIntegrator();
  DaeIntegrator(const DaeIntegrator&) = delete;
  DaeIntegrator& operator=(const DaeIntegrator&) = delete;

  // Starts at the drive's first time under `drive`: from rest (every position, force and rate
  // zero), or with POSITIONS (one per internal node, mm) from that configuration at rest (rates
  // zero): sliders stuck where they are, gaps closed where an elongation is at a stop.
  void start(const DriveSignal& drive, const std::vector<double>* positions = nullptr);
  // Starts a sine drive from START's positions and rate-edge rates (dae_linear_start.hpp): the
  // periodic state of the network's linearisation; sliders stuck where they are.
  void start(const DriveSignal& drive, const DaeLinearStart& start);
  // Integrates to time t [s] (> the current time); returns the terminal force [N] at t. On a
  // sampled drive the force at a sample time is its left limit: rates are those of the piece
  // ending there (the fixed-step convention, run_history.hpp), as are element_outputs().
  double advance(double t);
  // Sampled drives given a window at a time (a history streamed from its file): continues on
  // WINDOW, a later stretch of the same drive (its times and displacements those of the drive,
  // bit for bit), whose interval SEGMENT is the one the current time lies in or, where the last
  // advance() stopped on a sample, ends at. The window must hold a sample after every time
  // advance() is asked for before the next slide() (as the whole drive does but at its end), and
  // outlive its use. The same advance() calls then give the numbers of the whole drive.
  void slide(const Drive& window, std::size_t segment);

  double time() const { return time_; }
  // The unknowns y at the current time (layout above) and their rates.
  const std::vector<double>& state() const { return y_; }
  // Force [N] and elongation [mm] of each element the user wrote, at the current time.
  void element_outputs(std::vector<double>& force, std::vector<double>& elongation) const;
  DaeStatistics statistics() const;
  // Largest change of the state since `start` (a copy of state()), each unknown relative to its
  // scale: positions to `length` [mm], forces to `force` [N], velocities to `velocity` [mm/s],
  // Bouc-Wen states to 1. Rate coordinates are left out: events re-choose them.
  double change_since(const std::vector<double>& start, double length, double force, double velocity) const;

  // The unknowns a harmonic point's settling extrapolates (dae_settling.hpp): the node positions
  // [mm] and the Bouc-Wen states [-]; forces, rate coordinates and rates follow from them. Empty
  // where a restart cannot make a moved state consistent: with a nested bouc_wen, whose restart
  // takes the state as it is (IDACalcIC holds node rates fixed, dae_initial_rates.cpp).
  std::vector<double> settling_state() const;
  // Moves to SETTLING (settling_state()'s layout) at the current time and restarts IDA there:
  // each stuck slider holds its new elongation, the coordinates are chosen anew and IDACalcIC
  // makes forces and rates consistent (a slider then beyond its yield force slips).
  void move_to(const std::vector<double>& settling);

  // Residual and root functions, called by the C trampolines.
  void residual(double t, const double* y, const double* yp, double* r);
  void roots(double t, const double* y, const double* yp, double* g);
  // The Newton matrix dr/dy + cj dr/dy' at (t, y, y') with residual r there, into MATRIX (n x n,
  // column-major, n = the number of unknowns).
  void jacobian(double t, double cj, const double* y, const double* yp, const double* r, double* matrix);
  // Keeps an exception thrown inside a callback until the C call returns.
  void store_error(std::exception_ptr error) { error_ = std::move(error); }

 private:
  struct Solver;  // the SUNDIALS handles
  struct DriveState {
    double u, du, ddu;  // mm, mm/s, mm/s^2
  };
  DriveState drive_at(double t) const;
  static double elongation(const double* y, const DriveState& drive, const Edge& edge);
  static double elongation_rate(const double* yp, const DriveState& drive, const Edge& edge);
  void edge_forces(const DriveState& drive, const double* y, const double* yp, double* force) const;
  double terminal_force(const double* force) const;
  const Edge& switch_edge(int l) const;
  void restart(double t, bool modes_changed);
  // 1e-3 of the drive's time scale [s]: of 1/w for a sine, of the duration for samples.
  double time_horizon() const;
  // Consistent rates yp_ at t for the current y_ (consistent there) from one backward-Euler step
  // of 1e-3 HORIZON [s], where IDACalcIC cannot find them (dae_initial_rates.cpp).
  void initial_rates_by_euler_step(double t, double horizon);
  // yp_ := the rates v of one backward-Euler step of H [s] from (T, y_): F(t + h, y_ + h v, v) = 0.
  void euler_rates(double t, double h);
  // euler_rates without the exception: false (yp_ then undefined) where Newton did not converge.
  bool try_euler_rates(double t, double h);
  // After IDACalcIC: the rates of a backward-Euler step of 1e-3 HORIZON [s] into rates_ahead_
  // (yp_ kept); false where that Newton did not converge. A consistent state's rates to O(h y''):
  // what each unknown does within h.
  bool rates_ahead(double t, double horizon);
  // A slipping slider whose rate over the next 1e-3 HORIZON opposes its slip sticks (true: modes
  // changed); else the algebraic rates of yp_ (which IDACalcIC leaves stale, and which the slip
  // roots read) become those rates, and IDA is re-initialised with them.
  bool stick_stopping_sliders(double t, double horizon);
  std::vector<double> rates_ahead_;  // scratch of rates_ahead: y' over the next step
  // The Bouc-Wen rows of the residual, on the branch of each state's direction (dae_bouc_wen.cpp).
  void bouc_wen_residuals(const DriveState& drive, const double* y, const double* yp, double* r) const;
  // The Bouc-Wen root functions into G (one per state): e' where it has a direction, else 1.
  void bouc_wen_roots(const DriveState& drive, const double* yp, double* g) const;
  // Directions at a start: +1 inside a block (the first restart aligns them), 0 between terminal
  // and ground.
  void start_bouc_wen_directions();
  // root_direction_'s Bouc-Wen entries: e' may cross zero only from the side of its direction.
  void set_bouc_wen_root_directions();
  // At a root: flips the direction of each bouc_wen whose root FOUND (IDAGetRootInfo's layout)
  // reports, and IDA goes on without a restart (dae_bouc_wen.cpp).
  void reverse_bouc_wen_directions(const std::vector<int>& found);
  // At a restart: yp_ consistent at T for y_ (initial_rates_by_euler_step), with each bouc_wen's
  // direction that of its e' there wherever e' is beyond bouc_wen_rate_band() against it.
  void bouc_wen_consistent_rates(double t, double horizon);
  // [mm/s]: how far e' must cross zero against d (dae_bouc_wen.cpp).
  double bouc_wen_rate_band() const;
  // Per Bouc-Wen state: +1 or -1, the sign of e' whose branch its law takes until its next root
  // (a bouc_wen inside a block); 0 between terminal and ground (the branch of the drive's rate).
  std::vector<std::int8_t> bouc_wen_direction_;
  int root_count() const { return 2 * layout_.switch_forces + layout_.bouc_wen_states; }
  // y_ := y_ + H v and time_ := T + H, v from euler_rates.
  void euler_step(double t, double h);
  void rechoose_coordinates(double t);
  // The rates of the rate edges' elongations the next rechoose_coordinates takes instead of those
  // of the current coordinates (a start from a moving state); empty otherwise.
  std::vector<double> start_rates_;
  bool switch_inconsistent_modes(double t, double horizon);
  void copy_from_solver();
  // At roots FOUND (IDAGetRootInfo's layout) at T: the modes switch and IDA restarts (true).
  // Within h = 1e-3 of the time horizon of the last switch, a slipping slider whose slip rate
  // crossed zero slips on where its rate over the next h still points its way (rates_ahead): the
  // root was the switch's fast transient's (the force drops by kSlack fy as the slider starts to
  // slip, and a stiff spring beside a quadratic dashpot relaxes in 1e-9 s). Where no mode
  // switched, that backward-Euler step passes the transient and IDA restarts at its end (false).
  // Not within 2 h of T_STOP, the next stop: there the slider sticks.
  bool switch_modes(double t, double t_stop, const std::vector<int>& found);
  // Integrates to T_STOP (a stop time of IDA) or to the first event before it; returns the time
  // reached.
  double solve_to(double t_stop);
  // Restarts IDA at time_ from y_ and yp_ as they are, its step history dropped.
  void resume();
  void collect_statistics();
  void stick_reversed_sliders();
  // IDA's Newton matrix from jacobian() (true), or from IDA's own difference quotient (false).
  void use_own_jacobian(bool own);

  const DaeGraph& graph_;
  DaeOptions options_;
  DriveSignal drive_;
  std::size_t segment_ = 0;  // samples: the interval [time[segment_], time[segment_ + 1]]
  // samples: advance() stopped on a sample, still on the piece ending there (so that the force
  // it returns is the left limit at that sample); the next advance() restarts on the next piece.
  bool rate_jump_pending_ = false;
  DaeLayout layout_;
  std::vector<int> rate_of_edge_, switch_of_edge_, bouc_wen_of_edge_;  // -1 where not
  SwitchModes modes_;
  std::vector<double> held_;  // elongation held by each rigid switch edge
  ModeKinematics kinematics_;
  std::vector<double> y_, yp_;
  mutable std::vector<double> rate_, acceleration_, force_;  // scratch per residual call
  std::vector<double> y_saved_, yp_saved_, root_values_;     // scratch of stick_reversed_sliders
  std::vector<double> y_probe_, yp_probe_, r_probe_;         // scratch of jacobian
  std::vector<double> y_probe_initial_, r_initial_;          // scratch of initial_rates_by_euler_step
  // A bouc_wen between internal nodes: its law reads positions' rates, which IDACalcIC holds
  // fixed, so restarts take initial_rates_by_euler_step instead (no sliders or gaps then).
  bool nested_bouc_wen_ = false;
  std::vector<double> scale_;                      // each unknown's scale (its absolute tolerance / rtol)
  std::vector<int> root_direction_, roots_found_;  // scratch of restart and solve_to
  double time_ = 0.0;
  bool first_step_ = false;        // the next IDA step is the first since a restart (solve_to)
  double modes_changed_at_ = 0.0;  // [s]: the last restart with new modes (switch_modes)
  long events_ = 0;
  DaeStatistics totals_;  // steps and residual evaluations before the last re-initialisation
  std::exception_ptr error_;
  std::string last_message_;
  std::unique_ptr<Solver> solver_;

  friend void capture_ida_message(int, const char*, const char*, char*, void*);
};

}  // namespace rheo::runtime
