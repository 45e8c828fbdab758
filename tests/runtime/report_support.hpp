// Helpers of the report tests (rheo itself runs by cli_support.hpp): running another program
// (a browser), a minimal XML well-formedness check of generated SVG, and counting substrings of
// generated markup.
#pragma once

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

namespace rheo::test {

struct CommandResult {
  int code = -1;
  std::string output;  // standard output and standard error
};

// Runs a shell command line.
inline CommandResult run_command(const std::string& command_line) {
  CommandResult r;
  FILE* pipe = popen((command_line + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer{};
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// Empty when every tag of `xml` is closed in order (comments, <?...?> and <!...> skipped, no
// '<' or '&' outside tags and entities); else what is wrong.
inline std::string xml_problem(const std::string& xml) {
  std::vector<std::string> open;
  for (std::size_t i = 0; i < xml.size(); ++i) {
    if (xml[i] == '&') {
      const std::size_t semi = xml.find(';', i);
      if (semi == std::string::npos || semi - i > 8) return fmt::format("bare '&' at {}", i);
      continue;
    }
    if (xml[i] != '<') continue;
    const std::size_t end = xml.find('>', i);
    if (end == std::string::npos) return fmt::format("unclosed tag at {}", i);
    const std::string tag = xml.substr(i + 1, end - i - 1);
    if (tag.find('<') != std::string::npos) return fmt::format("'<' inside a tag at {}", i);
    if (tag.starts_with("?") || tag.starts_with("!")) {
      i = end;
      continue;
    }
    const std::string name = tag.substr(tag[0] == '/' ? 1 : 0, tag.find_first_of(" \t\n/", 1) - (tag[0] == '/' ? 1 : 0));
    if (tag[0] == '/') {
      if (open.empty() || open.back() != name) return fmt::format("</{}> closes <{}> at {}", name, open.empty() ? "" : open.back(), i);
      open.pop_back();
    } else if (tag.back() != '/') {
      open.push_back(name);
    }
    i = end;
  }
  return open.empty() ? std::string() : fmt::format("<{}> never closed", open.back());
}

}  // namespace rheo::test
