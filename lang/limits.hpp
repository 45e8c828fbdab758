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

}  // namespace rheo::lang
