// Writing a model file (.rheo) somewhere else than the file it came from.
#pragma once

#include <string>

namespace rheo::cli {

// Writes TEXT, a .rheo text whose relative file names are read from the folder of
// SOURCE_FILE, to PATH with those names rewritten so that they name the same files from
// PATH's folder (lang/file_references.hpp), through runtime::write_output (no half-written
// file).
void write_model_file(const std::string& path, const std::string& text, const std::string& source_file);

}  // namespace rheo::cli
