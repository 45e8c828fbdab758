// What the commands look up in a loaded program: the model they work on, and the paths a
// .rheo file names (relative to that file).
#pragma once

#include "lang/model.hpp"

#include <string>

namespace rheo::cli {

// The model named `name` (--model), else the file's only model that is not from the standard
// library. UsageError otherwise, naming `file` and the models, ending with `advice` (e.g.
// "choose one with --model"); `purpose` completes "defines no model ..." ("to fit").
const lang::CheckedModel& chosen_model(const lang::Program& program, const std::string& file, const std::string& name, const std::string& purpose,
                                       const std::string& advice);

// `path` as written in `base_file`: relative to that file's directory unless absolute or empty.
std::string relative_to(const std::string& base_file, const std::string& path);

}  // namespace rheo::cli
