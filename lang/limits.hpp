// Bounds on how deep and how large a model may be, whatever the input: every pass over a
// model's tree (parser, checker, network compiler, solvers, destructors) recurses over its
// nesting, and instantiation copies models into each other. Within these bounds no input can
// exhaust the stack or multiply a small file into a huge model; past them the front-end reports
// an error naming where (docs/errors.md#limits).
#pragma once

#include <cstddef>

namespace rheo::lang {

// Levels of blocks: a block in a model's body is level 1, a block in it level 2, ... An
// instantiated model is a block of its own, so its levels add to those around the instance.
inline constexpr int max_block_depth = 200;

// Levels of an expression: a number or a name is level 1; each pair of parentheses, unary minus
// and binary operator around it adds one (`2 * (a + 1)` has 4, a chain `a + b + c` 3).
inline constexpr int max_expression_depth = 200;

// Elements and parameters of one model once the models it instantiates are copied into it.
inline constexpr std::size_t max_model_size = 100000;

// Bytes read from one file: a .rheo source (the 10 MB of the hostile-input tests and far more
// than any model needs) and a CSV table (about 25 million rows of a measured history).
inline constexpr std::size_t max_source_bytes = std::size_t{64} << 20;
inline constexpr std::size_t max_table_bytes = std::size_t{512} << 20;

// Errors printed for one file; the rest are counted ("... and N more errors").
inline constexpr std::size_t max_printed_errors = 100;

// Physical ranges of what a test rig drives and measures, internal units, wide enough for any
// time-temperature master curve (20 to 30 decades of reduced frequency, 1e-14 to 1e14 Hz is
// routine) and any specimen: a modulus from 1 mPa (a melt's terminal zone) to 1 TPa times a
// geometry factor area/height from 1e-4 mm (a thin fibre) to 1e4 mm (a wide, thin shear
// sandwich) is 1e-13 to 1e10 N/mm. Each range is 1e-20 to 1e20, so that every product a closed
// form or a time-stepping path forms stays far inside double range (1e-308 to 1e308): the force
// amplitude k u0 and the rate omega u0 within 1e+-41, the hysteresis energy ~ k u0^2 (eq. 1.2)
// within 1e+-60, omega tau for relaxation times of 1e-20 to 1e20 s within 1e+-41 (and
// (omega tau)^2 within 1e+-82). What cannot be computed accurately at an extreme (time stepping
// 1e20 cycles) is bounded by the work limits below, not here. A protocol setting or a data row
// outside is an error naming where.
inline constexpr double min_amplitude = 1e-20;  // mm
inline constexpr double max_amplitude = 1e20;   // mm
inline constexpr double min_frequency = 1e-20;  // Hz
inline constexpr double max_frequency = 1e20;   // Hz
inline constexpr double min_stiffness = 1e-20;  // N/mm, a measured |K*|
inline constexpr double max_stiffness = 1e20;   // N/mm

// Work a protocol may ask for, so that no setting makes rheo run out of memory or seemingly
// hang: samples of one drive (rows of a history result), points of a harmonic grid, time
// steps of one harmonic point (steps_per_cycle x cycles_max), and the whole-number settings.
inline constexpr long max_drive_samples = 10'000'000;
inline constexpr long max_harmonic_points = 1'000'000;
inline constexpr long max_steps_per_point = 100'000'000;
inline constexpr int max_steps_per_cycle = 1'000'000;
inline constexpr int max_cycles = 100'000;
inline constexpr int max_substeps = 100'000;

}  // namespace rheo::lang
