// The language front-end's public API: source -> checked Program.
#pragma once

#include "lang/diagnostics.hpp"
#include "lang/errors.hpp"
#include "lang/model.hpp"

#include <stdexcept>
#include <string>
#include <string_view>

namespace rheo::lang {

// A source file that cannot be read (missing, a directory, no permission): what() is
// "FILE: error: cannot read it (REASON); ADVICE" (lang/file_text.hpp). A data error (exit 4).
struct UnreadableSource : DataError {
  using DataError::DataError;
};

// The bytes of a source FILE, at most max_source_bytes (limits.hpp), without a leading UTF-8
// byte-order mark; UnreadableSource otherwise.
std::string read_source(const std::string& path);

// Reads, parses and checks FILE (imports resolved from the embedded stdlib). Throws
// CompileError with EVERY semantic error found (parse errors: the first). Throws
// UnreadableSource if FILE cannot be read.
Program load_program(const std::string& path);
Program compile_source(const std::string& file_name, std::string_view text);

// Parses one protocol setting given on the command line, e.g.
// "frequency = 1 Hz .. 51 Hz step 2 Hz", with the same value grammar and the schema of KIND;
// throws CompileError (file name "<command line>").
Setting parse_setting(ProtocolKind kind, std::string_view text);
// The same for a fit setting (`method = approximate`), with the fit schema; free/fixed excluded.
Setting parse_fit_setting(std::string_view text);

// A data file as `--data` gives it: TEXT without a comma is the file name, as it stands;
// otherwise the name runs to the first comma (or is in double quotes, for a name holding one)
// and a data line's settings follow, `sweep.txt, step = "Amplitude sweep", area = 314 mm^2`,
// with the grammar and the checks of a `data` line. Throws CompileError (file name
// "<command line>").
FitData parse_data_option(std::string_view text);

}  // namespace rheo::lang
