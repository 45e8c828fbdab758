// The settings each simulate protocol accepts, their validation, and their decoding into the
// typed settings of protocol_settings.hpp (whose member initialisers are the defaults).
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
// present (missing ones reported at WHERE); the result's settings decoded from those given.
Protocol check_protocol(ProtocolKind kind, const std::vector<ast::SettingNode>& settings, const SourceLocation& where,
                        std::vector<Diagnostic>& errors);

// The typed settings of a KIND protocol from settings validated against its schema; absent ones
// take their defaults.
ProtocolSettings decode_protocol_settings(ProtocolKind kind, const std::vector<Setting>& written);

// PROTOCOL with SETTING (validated against its schema, e.g. by parse_setting) in place of the
// written one of the same key, or added; its settings decoded again.
void override_setting(Protocol& protocol, Setting setting);

}  // namespace rheo::lang
