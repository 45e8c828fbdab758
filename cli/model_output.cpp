#include "cli/model_output.hpp"

#include "lang/file_references.hpp"
#include "runtime/io/output.hpp"

namespace rheo::cli {

void write_model_file(const std::string& path, const std::string& text, const std::string& source_file) {
  runtime::write_output(path, lang::relocated_source(text, source_file, path));
}

}  // namespace rheo::cli
