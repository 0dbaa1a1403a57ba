// A probe records every term a golden pass computes at one pixel, each labelled with its paper and
// equation, so that a person porting the pass to a shader can compare their numbers line by line
// (`rtdr probe`, and a click in `rtdr view`). Golden per-pixel functions take a `Probe*`; it is null in normal
// runs, and `note()` then does nothing, so the math is written once and probed where it stands. Each term also
// records the file and line of the note() that made it: the line of the golden function that computed it.
#pragma once

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace rtdr {

// Where a term was computed: the file and line of the note() call (Probe::term makes the file relative to the
// repository). Taken by default arguments at the call site; __builtin_FILE and
// __builtin_LINE rather than std::source_location, which the clang of the fuzz build (14) lacks.
struct SourceLine {
  const char* file = "";
  int line = 0;
};

class Probe {
 public:
  // Starts a group of terms, e.g. "tap (-2, 0)"; terms before the first group belong to "".
  void group(const std::string& label) { group_ = label; }
  void term(const std::string& name, float value, const std::string& cite = "", SourceLine where = {});
  void term(const std::string& name, const glm::vec2& value, const std::string& cite = "", SourceLine where = {});
  void term(const std::string& name, const glm::vec3& value, const std::string& cite = "", SourceLine where = {});

  // One term per line, "group | name = value | cite", values with 9 significant digits (enough to
  // reproduce a float exactly), in the order computed: made to be diffed (so without the source lines, which
  // move with every edit).
  std::string text() const;
  // [{"group": ..., "name": ..., "value": [..], "cite": ..., "equations": [..], "file": ..., "line": ...}, ...]:
  // "equations" are the keys the cite names (filters/equations.h cited_equations), "file" and "line" the note().
  nlohmann::json json() const;

  struct Term {
    std::string group, name, cite;
    std::vector<float> value;
    std::string file;
    int line = 0;
  };
  const std::vector<Term>& terms() const { return terms_; }
  // The first term called `name` in `group` (throws std::out_of_range when there is none): for tests.
  const Term& find(const std::string& name, const std::string& group = "") const;

 private:
  std::string group_;
  std::vector<Term> terms_;
};

// Records a term when a probe is attached, with the file and line of this call.
template <class T>
inline void note(Probe* probe, const char* name, const T& value, const char* cite = "",
                 const char* file = __builtin_FILE(), int line = __builtin_LINE()) {
  if (probe) probe->term(name, value, cite, SourceLine{file, line});
}
inline void note_group(Probe* probe, const std::string& label) {
  if (probe) probe->group(label);
}

}  // namespace rtdr
