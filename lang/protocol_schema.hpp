// The settings each simulate protocol accepts, and their validation. Defaults are not filled
// in here: the runtime applies them to settings that are absent.
#pragma once

#include "lang/ast.hpp"
#include "lang/diagnostics.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rheo::lang {

// "harmonic" -> ProtocolKind::harmonic, "static" -> static_triangle, ...; nullopt when unknown.
std::optional<ProtocolKind> protocol_kind(const std::string& name);
std::string protocol_name(ProtocolKind kind);
std::vector<std::string> protocol_names();
// The setting keys KIND accepts, in schema order (docs/language.md lists them).
std::vector<std::string> protocol_setting_keys(ProtocolKind kind);

// Validates one setting against KIND's schema (key known, value shape, dimension, range) and
// converts it to internal units. Reports to ERRORS and returns nullopt when invalid.
std::optional<Setting> check_setting(ProtocolKind kind, const ast::SettingNode& node, std::vector<Diagnostic>& errors);

// The protocol line `KIND SETTING, ...` as a whole: every setting, no duplicates, required ones
// present (missing ones reported at WHERE).
Protocol check_protocol(ProtocolKind kind, const std::vector<ast::SettingNode>& settings, const SourceLocation& where,
                        std::vector<Diagnostic>& errors);

}  // namespace rheo::lang
