// The checked program: what the language front-end hands to the runtime.
//
// Contract: a Program is produced only by check() (checker.hpp) from source that parsed and
// passed every semantic check. Every value in it is in the internal unit system
//   force N, length mm, time s  (so stiffness N/mm, damping N*s/mm, frequency Hz = 1/s)
// and every dimension has been verified. The runtime may trust it without re-checking.
#pragma once

#include "lang/fit_settings.hpp"
#include "lang/protocol_settings.hpp"
#include "lang/source_location.hpp"
#include "lang/units.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rheo::lang {

// A parameter value that may depend on other parameters of the same model, kept as a
// postfix program so that fitting can re-evaluate derived parameters when free ones change.
struct Expression {
  enum class Op : std::uint8_t { constant, parameter, add, subtract, multiply, divide, negate };
  struct Instruction {
    Op op;
    double constant = 0.0;  // Op::constant, internal units
    int parameter = -1;     // Op::parameter: index into CheckedModel::parameters
  };
  std::vector<Instruction> code;  // evaluated left to right on a stack

  // Evaluates with the given parameter values (internal units). Division by zero yields inf.
  double evaluate(const std::vector<double>& parameter_values) const;
  bool is_constant() const;  // true when no Op::parameter occurs
};

struct Parameter {
  std::string path;       // "m1.tau", "rubber.D10", or a model parameter "k0"
  Dimension dimension;    // e.g. stiffness
  double value = 0.0;     // evaluated, internal units
  Expression expression;  // how value is computed (a single constant for literals)
  bool free = false;      // declared with bounds: identified by `rheo fit`
  double lower = 0.0;     // bounds, internal units; meaningful when free
  double upper = 0.0;
  std::string unit;  // the unit the user wrote ("N/mm"), for reporting; may be empty
  SourceLocation where;
  // Byte range [value_begin, value_end) of the value expression in the text of where.file: the
  // argument's own value, or the override's in an instantiation. -1 when no text is written for
  // this parameter: generated ones (maxwell c from tau) and an instantiated model's defaults,
  // which every instance shares (stdlib or not).
  int value_begin = -1;
  int value_end = -1;
};

enum class ElementKind : std::uint8_t {
  spring,             // k [N/mm]:               F = k e
  yeoh,               // D10 [N/mm], D20 [N/mm^3], D30 [N/mm^5]: F = 2 (D10 + 2 D20 e^2 + 3 D30 e^4) e  (eq. 3.3)
  dashpot,            // c [N*s/mm]:             F = c de/dt
  maxwell,            // k [N/mm], c [N*s/mm]:   spring k in series with dashpot c (tau = c/k)   (eq. 2.3)
  friction,           // k [N/mm], fy [N]:       spring k in series with a slider slipping at |F| = fy (eq. 2.9);
                      //   or fy_pos, fy_neg [N]: slipping at F = fy_pos in tension, F = -fy_neg in compression
  slider,             // fy [N]:                 rigid-plastic Coulomb slider, |F| <= fy; or -fy_neg <= F <= fy_pos
  inerter,            // b [N*s^2/mm]:           two-terminal mass, F = b d2e/dt2 (a fluid column)
  quadratic_dashpot,  // cq [N*s^2/mm^2]: turbulent channel flow, F = cq |de/dt| de/dt
  gap,                // width, center [mm]:     free play: F = 0 for |e - center| < width/2, rigid at
                      //   e = center +- width/2; |center| <= width/2 (rest lies in the play)
  bouc_wen,           // k [N/mm], n [-], fy [N]: smooth friction, F = fy z,
                      //   dz/dt = (k/fy) de/dt (1 - |z|^n (1 + sgn(z de/dt)) / 2); n -> inf: friction(k, fy)
  poly_spring,        // k1 [N/mm], k2 [N/mm^2], k3 [N/mm^3]: F = k1 e + k2 e^2 + k3 e^3 (not odd when k2 != 0)
  springpot,          // k [N/mm], alpha [-], tau [s], f_low, f_high [Hz]: fractional derivative element,
                      //   K* = k (i w tau)^alpha, approximated over [f_low, f_high] by a Maxwell chain
                      //   (runtime/network/springpot.hpp)
  parallel,           // children share the elongation; forces add
  series,             // children share the force; elongations add
};

// The keyword of a kind as written in source: "spring", ..., "parallel", "series".
const char* kind_word(ElementKind kind);

// Parameter slots of each leaf kind, in this order, as indices into CheckedModel::parameters.
// The checker normalises alternatives: maxwell given tau stores c = k * tau (an Expression),
// friction and bouc_wen given uy store fy = k * uy. Optional parameters left out (springpot
// f_low, f_high; gap center; poly_spring k2, k3) are generated with their defaults.
//   spring: {k}   yeoh: {D10, D20, D30}   dashpot: {c}   maxwell: {k, c}
//   friction: {k, fy} or {k, fy_pos, fy_neg}   slider: {fy} or {fy_pos, fy_neg}   inerter: {b}
//   quadratic_dashpot: {cq}   gap: {width, center}   bouc_wen: {k, n, fy}   poly_spring: {k1, k2, k3}
//   springpot: {k, alpha, tau, f_low, f_high}   parallel/series: {}
// A friction or slider given fy_pos and fy_neg has one slot more than given fy (or uy): the
// runtime reads its compression yield force from the last slot either way.
struct Element {
  ElementKind kind = ElementKind::parallel;
  std::string name;             // explicit or generated ("maxwell2"); unique in its naming scope
  std::string path;             // "fluid.cap" from the model root; empty for the root block
  std::vector<int> parameters;  // see the slot table above
  std::vector<Element> children;
  SourceLocation where;
};

struct CheckedModel {
  std::string name;
  std::vector<Parameter> parameters;  // every parameter, model-level ones first
  Element root;                       // a parallel block: a model body's elements act in parallel
  SourceLocation where;
};

// One setting of a directive line: `frequency = 1 Hz .. 51 Hz step 2 Hz` or `definition = thesis`.
struct Setting {
  std::string key;
  std::vector<double> values;  // numbers, lists and ranges expanded, internal units
  Dimension dimension;         // of values (dimensionless for counts)
  std::string text;            // identifiers and strings: `thesis`, "road.csv"
  SourceLocation where;
};

enum class ProtocolKind : std::uint8_t { harmonic, static_triangle, quasistatic, history, step };

struct Protocol {
  ProtocolKind kind = ProtocolKind::harmonic;
  ProtocolSettings settings;     // the alternative of `kind`, defaults filled in (protocol_settings.hpp)
  std::vector<Setting> written;  // the settings as written, validated: what `settings` is decoded
                                 // from, and what a command-line override replaces (protocol_schema.hpp)
  std::string output;            // file named by the `output "..."` line after it; empty: stdout
  SourceLocation where;
};

struct SimulateDirective {
  std::string model;  // resolved model name (the file's only model when the block names none)
  std::vector<Protocol> protocols;
  SourceLocation where;
};

// A data line's `force_offset`: a constant the measured force carries (a load cell's zero),
// measured force = network force + offset.
struct ForceOffsetSetting {
  bool given = false;    // written on the line
  bool free = false;     // `force_offset = free`: fitted
  double value = 0.0;    // N, when given and not free
  SourceLocation where;  // of the value
  int value_begin = -1;  // byte range [value_begin, value_end) of the value in where.file's text
  int value_end = -1;
};

// A `data "FILE" [, setting]...` line of a fit block: how FILE is read.
struct FitData {
  std::string file;                 // as written: relative to the .rheo file, resolved by the runtime
  double weight = 1.0;              // >= 0
  SourceLocation where;             // of the file name
  std::vector<ColumnName> columns;  // columns named for roles
  std::string step;                 // a TRIOS export's step; empty: its only one
  std::optional<double> area;       // mm^2, loaded area of a material specimen
  std::optional<double> height;     // mm, its height (gap, thickness)
  std::optional<double> amplitude;  // mm, or a plain strain when amplitude_is_strain
  bool amplitude_is_strain = false;
  DuplicatePoints duplicates = DuplicatePoints::average;  // repeated points of a harmonic table
  ForceOffsetSetting force_offset;                        // of a history's force; no effect on a harmonic table
  int end = -1;  // byte offset just past the line's last setting (or its file name) in where.file's text; -1 for --data
};

// `fit [MODEL] { ... }`.
struct FitDirective {
  std::string model;          // resolved like SimulateDirective::model
  std::vector<FitData> data;  // may be empty: the command line can supply the data
  FitSettings settings;       // decoded from the block's settings lines, defaults filled in (fit_settings.hpp)
  std::vector<int> free;      // indices into the model's parameters, sorted: the free set after free/fixed
  std::string output;         // `output "..."`; empty when absent
  SourceLocation where;       // of the `fit` keyword
};

struct Program {
  std::vector<CheckedModel> models;  // in source order; imported stdlib models are included
  std::vector<SimulateDirective> simulations;
  std::vector<FitDirective> fits;

  const CheckedModel* find_model(const std::string& name) const;
};

// The free set of a fit without `free`/`fixed`: every parameter declared with bounds, sorted.
std::vector<int> default_free_parameters(const CheckedModel& model);

}  // namespace rheo::lang
