// The settings a fit block accepts, and the block's validation against the model it fits.
// Defaults are not filled in here: the runtime applies them to absent settings.
#pragma once

#include "lang/ast.hpp"
#include "lang/diagnostics.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rheo::lang {

// Checks FIT, whose model has been resolved to MODEL. CHECKED is that model, or nullptr when it
// is unknown or has errors of its own: then `free` and `fixed` are checked only for shape and the
// free set is left empty.
FitDirective check_fit(const ast::Fit& fit, const std::string& model, const CheckedModel* checked, std::vector<Diagnostic>& errors);

// One setting of the fit schema other than free/fixed (e.g. from the command line), checked and
// in internal units; nullopt when invalid.
std::optional<Setting> check_fit_setting(const ast::SettingNode& node, std::vector<Diagnostic>& errors);

// A data line (`data "FILE", KEY = VALUE, ...`, from a fit block or --data), checked: the
// file name and the data schema's settings, in internal units.
FitData check_data_line(const ast::FitLine& line, std::vector<Diagnostic>& errors);

// The roles a data line's `columns` setting may name a column for (runtime/io/column_roles.hpp).
const std::vector<std::string>& data_column_roles();

// A `columns` setting's ROLE = NAME pairs (a data line's, a history protocol's), each role one of
// ROLES and named once; empty, with an error at S, when they are not.
std::vector<ColumnName> check_columns(const Setting& s, const std::vector<std::string>& roles, std::vector<Diagnostic>& errors);

// Every key a fit settings line accepts, in schema order.
std::vector<std::string> fit_setting_keys();

}  // namespace rheo::lang
