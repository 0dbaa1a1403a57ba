#include "filters/probe.h"

#include "filters/equations.h"

#include <cstdio>
#include <stdexcept>
#include <string_view>

namespace rtdr {
namespace {

// The path of a source file relative to the repository. The compiler names it as it was given: absolute, or
// relative to the build folder ("../filters/svgf/atrous.cpp", as Ninja or ccache's base_dir write it).
std::string repository_path(std::string_view file) {
  const std::string_view root = RTDR_SOURCE_DIR "/";
  if (file.substr(0, root.size()) == root) file.remove_prefix(root.size());
  while (file.substr(0, 3) == "../") file.remove_prefix(3);
  return std::string(file);
}

}  // namespace

void Probe::term(const std::string& name, float value, const std::string& cite, SourceLine where) {
  terms_.push_back({group_, name, cite, {value}, repository_path(where.file), where.line});
}
void Probe::term(const std::string& name, const glm::vec2& v, const std::string& cite, SourceLine where) {
  terms_.push_back({group_, name, cite, {v.x, v.y}, repository_path(where.file), where.line});
}
void Probe::term(const std::string& name, const glm::vec3& v, const std::string& cite, SourceLine where) {
  terms_.push_back({group_, name, cite, {v.x, v.y, v.z}, repository_path(where.file), where.line});
}

std::string Probe::text() const {
  std::string out;
  char number[32];
  for (const Term& t : terms_) {
    std::string values;
    for (size_t i = 0; i < t.value.size(); ++i) {
      std::snprintf(number, sizeof number, "%.9g", double(t.value[i]));
      values += (i ? ", " : "") + std::string(number);
    }
    if (t.value.size() > 1) values = "(" + values + ")";
    out += (t.group.empty() ? std::string("-") : t.group) + " | " + t.name + " = " + values +
           (t.cite.empty() ? "" : " | " + t.cite) + "\n";
  }
  return out;
}

nlohmann::json Probe::json() const {
  nlohmann::json out = nlohmann::json::array();
  for (const Term& t : terms_)
    out.push_back({{"group", t.group},
                   {"name", t.name},
                   {"value", t.value},
                   {"cite", t.cite},
                   {"equations", cited_equations(t.cite)},
                   {"file", t.file},
                   {"line", t.line}});
  return out;
}

const Probe::Term& Probe::find(const std::string& name, const std::string& group) const {
  for (const Term& t : terms_)
    if (t.name == name && t.group == group) return t;
  throw std::out_of_range("probe has no term '" + name + "' in group '" + group + "'");
}

}  // namespace rtdr
