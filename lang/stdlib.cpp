#include "lang/stdlib.hpp"

#include "stdlib/embedded.hpp"

namespace rheo::lang {

std::optional<std::string_view> stdlib_source(std::string_view name) {
  for (const auto& m : stdlib::modules())
    if (m.name == name) return m.text;
  return std::nullopt;
}

std::vector<std::string> stdlib_names() {
  std::vector<std::string> out;
  for (const auto& m : stdlib::modules()) out.emplace_back(m.name);
  return out;
}

std::string stdlib_path(std::string_view name) { return "<stdlib>/" + std::string(name) + ".rheo"; }

}  // namespace rheo::lang
