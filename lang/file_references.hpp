// The files a .rheo text names, and the text moved to another folder with those names still
// naming the same files (#22 item 2: `rheo fit -o elsewhere/x.rheo` and the other commands that
// write a model file).
//
// A file is named by a fit block's `data "FILE"` and `output "FILE"` lines, a simulate block's
// `output "FILE"` lines and a history protocol's `file = "FILE"` setting. Relative names are
// relative to the folder of the .rheo file that holds them (docs/language.md).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rheo::lang {

struct FileReference {
  int begin = 0, end = 0;  // byte range of the name (the string literal's contents) in the text
  std::string name;        // as written
};

// Every file TEXT names, in text order. Throws CompileError where TEXT does not parse.
std::vector<FileReference> file_references(const std::string& file_name, std::string_view text);

// TEXT, written to be read from the folder of FROM_FILE, with every relative file name
// rewritten so that read from the folder of TO_FILE it names the same file (lexically: no
// symbolic link is followed). Names that are absolute, or that need no change, are kept byte
// for byte; so is everything else.
std::string relocated_source(std::string_view text, const std::string& from_file, const std::string& to_file);

}  // namespace rheo::lang
