#include "cli/program_lookup.hpp"

#include "lang/names.hpp"
#include "lang/text_encoding.hpp"
#include "runtime/core/errors.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <vector>

namespace rheo::cli {

const lang::CheckedModel& chosen_model(const lang::Program& program, const std::string& file, const std::string& name, const std::string& purpose,
                                       const std::string& advice) {
  if (!name.empty()) {
    if (const lang::CheckedModel* m = program.find_model(name)) return *m;
    std::vector<std::string> names;
    for (const auto& m : program.models)
      if (!m.where.file.starts_with("<stdlib>")) names.push_back(m.name);
    throw runtime::UsageError(fmt::format("{} has no model '{}' (--model);{} its models are {}", file, lang::printable(name),
                                          lang::did_you_mean(name, names), lang::join(names)));
  }
  std::vector<const lang::CheckedModel*> user;
  for (const auto& m : program.models)
    if (!m.where.file.starts_with("<stdlib>")) user.push_back(&m);
  if (user.size() == 1) return *user.front();
  std::vector<std::string> names;
  for (const auto* m : user) names.push_back(m->name);
  throw runtime::UsageError(user.empty() ? fmt::format("{} defines no model {}", file, purpose)
                                         : fmt::format("{} defines {} models ({}); {}", file, user.size(), fmt::join(names, ", "), advice));
}

std::string relative_to(const std::string& base_file, const std::string& path) {
  if (path.empty() || std::filesystem::path(path).is_absolute()) return path;
  return (std::filesystem::path(base_file).parent_path() / path).string();
}

}  // namespace rheo::cli
