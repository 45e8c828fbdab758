#include "runtime/fmu/fmu_resources.hpp"

#include "lang/file_text.hpp"
#include "lang/limits.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/fmu/fmu_variables.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace rheo::runtime::fmu {
namespace {

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string read_resource(const std::string& folder, const char* name) {
  const std::string path = (std::filesystem::path(folder) / name).string();
  lang::FileText file = lang::read_file_text(path, lang::max_source_bytes);
  if (!file.failure.empty())
    throw DataError(
        fmt::format("{}: error: cannot read the FMU's resource ({}); the FMU is incomplete: export it again with rheo export", path, file.failure));
  return std::move(file.text);
}

}  // namespace

std::string resource_folder(std::string_view uri) {
  std::string_view rest = uri;
  if (!rest.starts_with("file:"))
    throw UsageError(fmt::format("fmuResourceLocation '{}' is not a file: URI; the FMU reads its resources from a local folder", uri));
  rest.remove_prefix(5);
  if (rest.starts_with("//")) {  // an authority: empty or localhost
    rest.remove_prefix(2);
    const auto slash = rest.find('/');
    const std::string_view host = rest.substr(0, slash);
    if (!host.empty() && host != "localhost")
      throw UsageError(fmt::format("fmuResourceLocation '{}' names host '{}'; the FMU reads its resources from a local folder", uri, host));
    rest = slash == std::string_view::npos ? std::string_view() : rest.substr(slash);
  }
  std::string path;
  for (std::size_t i = 0; i < rest.size(); ++i) {
    if (rest[i] != '%') {
      path += rest[i];
      continue;
    }
    const bool complete = i + 2 < rest.size();
    const int hi = complete ? hex_digit(rest[i + 1]) : -1, lo = complete ? hex_digit(rest[i + 2]) : -1;
    if (hi < 0 || lo < 0) throw UsageError(fmt::format("fmuResourceLocation '{}' has a malformed %-escape at character {}", uri, i + 1));
    path += static_cast<char>(hi * 16 + lo);
    i += 2;
  }
  if (path.empty()) throw UsageError(fmt::format("fmuResourceLocation '{}' names no folder", uri));
  return path;
}

std::unique_ptr<CoSimulation> load_cosimulation(const std::string& folder, std::string_view guid, std::string_view rheo_version) {
  const std::string source = read_resource(folder, kSourceResource);
  std::string name = read_resource(folder, kModelNameResource);
  while (!name.empty() && (name.back() == '\n' || name.back() == '\r')) name.pop_back();
  const std::string expected = fmu_guid(rheo_version, name, source);
  if (guid != expected)
    throw UsageError(
        fmt::format("the host passed GUID {}, but the FMU's resources (model '{}', rheo {}) have {}: the resources or "
                    "modelDescription.xml were changed or come from another FMU; export it again with rheo export",
                    guid, name, rheo_version, expected));
  return std::make_unique<CoSimulation>(kSourceResource, source, name);
}

}  // namespace rheo::runtime::fmu
