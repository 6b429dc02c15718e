#include "common/core/idl_text.hpp"

#include <regex>
#include <set>
#include <sstream>

namespace slam {
namespace {

const IdlFile* find_file(std::string_view name) {
  for (const IdlFile& f : idl_files())
    if (f.name == name) return &f;
  return nullptr;
}

// Appends `file` after the files it includes (depth first, each once); drops the #include lines.
Status append_with_includes(const IdlFile& file, std::set<std::string_view>& done, std::string& out) {
  if (!done.insert(file.name).second) return {};
  static const std::regex include_line(R"re(^\s*#include\s+"([^"]+)"\s*$)re");
  std::string body;
  std::istringstream lines{std::string(file.text)};
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_match(line, m, include_line)) {
      const IdlFile* included = find_file(m[1].str());
      if (!included)
        return Error{std::string(file.name) + " includes " + m[1].str() + ", which is not embedded"};
      SLAM_TRY(append_with_includes(*included, done, out));
      continue;
    }
    body += line;
    body += '\n';
  }
  out += "// " + std::string(file.name) + "\n" + body;
  return {};
}

}  // namespace

Result<std::string> omgidl_schema(std::string_view type_name) {
  const size_t sep = type_name.rfind("::");
  const std::string local(sep == std::string_view::npos ? type_name : type_name.substr(sep + 2));
  const std::regex definition("\\b(struct|union|enum)\\s+" + local + "\\b\\s*\\{");
  for (const IdlFile& f : idl_files()) {
    if (!std::regex_search(f.text.begin(), f.text.end(), definition)) continue;
    std::set<std::string_view> done;
    std::string text;
    SLAM_TRY(append_with_includes(f, done, text));
    return text;
  }
  return Error{"no IDL file defines " + std::string(type_name)};
}

}  // namespace slam
