#include "bench_support.hpp"

#include "lang/frontend.hpp"

#include <stdexcept>

namespace rheo::bench {

lang::CheckedModel example_model(const std::string& file, const std::string& model) {
  const lang::Program program = lang::load_program(std::string(RHEO_EXAMPLES_DIR) + "/" + file);
  const lang::CheckedModel* m = program.find_model(model);
  if (!m) throw std::runtime_error("no model " + model + " in " + file);
  return *m;
}

runtime::FitDataSet example_data(const std::string& csv) { return runtime::read_fit_data(std::string(RHEO_EXAMPLES_DIR) + "/data/" + csv, 1.0); }

}  // namespace rheo::bench
