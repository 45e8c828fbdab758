// Models and data of the benchmarks, read from examples/ so that they are the ones users run.
#pragma once

#include "lang/model.hpp"
#include "runtime/io/fit_data.hpp"

#include <string>

namespace rheo::bench {

// The checked model `model` of examples/FILE.
lang::CheckedModel example_model(const std::string& file, const std::string& model);
runtime::FitDataSet example_data(const std::string& csv);

}  // namespace rheo::bench
