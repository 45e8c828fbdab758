#include "cli/data_option.hpp"

#include "lang/frontend.hpp"
#include "lang/text_encoding.hpp"
#include "runtime/core/errors.hpp"

#include <fmt/format.h>

namespace rheo::cli {

runtime::FitDataSet read_data_option(const std::string& text) {
  lang::FitData data;
  try {
    data = lang::parse_data_option(text);
  } catch (const lang::CompileError& e) {
    throw runtime::UsageError(fmt::format("--data '{}':\n{}", lang::printable(text), e.what()));
  }
  return runtime::read_fit_data(data.file, data.weight, nullptr, runtime::reading_of(data));
}

}  // namespace rheo::cli
