// docs/equations.md is a promise: for every equation, the function that implements it, the test that checks
// it and the shaders that port it. This test keeps the promise true: every file it names exists, every function
// named is defined in its file, every quoted test case is in its test file, and the implementing file and every
// shader named cite the equation they claim to implement. And the TeX of the equations the probe's terms cite
// (filters/equations.h, typeset by `rtdr view`) covers exactly the keys that the golden passes' note() calls cite.
#include "filters/equations.h"
#include "markdown_fixtures.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

using test::code_spans;
using test::split_row;

struct Row {
  std::string paper, equation, function, test, shader;
};

// The rows of the table: | paper | equation | function | test | shader |.
std::vector<Row> table_rows() {
  std::vector<Row> rows;
  std::istringstream doc(read(fs::path(RTDR_SOURCE_DIR) / "docs/equations.md"));
  for (std::string line; std::getline(doc, line);) {
    if (line.rfind("| ", 0) != 0 || line.find("---") != std::string::npos) continue;
    const std::vector<std::string> c = split_row(line);
    if (c.size() < 5 || c[0] == "paper") continue;
    rows.push_back({c[0], c[1], c[2], c[3], c[4]});
  }
  return rows;
}

// Every key that a note() call's string literals cite, over the golden passes in filters/, with a file citing it.
// A note() call runs from "note(probe," to its ");" (a ';' inside a literal does not end it); its first literal is
// the term's name, the others its cite.
std::map<std::string, std::string> keys_cited_by_notes() {
  std::map<std::string, std::string> keys;
  const std::regex call("\\bnote\\(probe,((?:[^;\"]|\"(?:[^\"\\\\]|\\\\.)*\")*)\\);"), literal("\"((?:[^\"\\\\]|\\\\.)*)\"");
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(RTDR_SOURCE_DIR) / "filters")) {
    if (entry.path().extension() != ".cpp") continue;
    const std::string code = read(entry.path());
    for (auto c = std::sregex_iterator(code.begin(), code.end(), call); c != std::sregex_iterator(); ++c) {
      const std::string args = (*c)[1].str();
      auto l = std::sregex_iterator(args.begin(), args.end(), literal);
      if (l == std::sregex_iterator()) continue;
      for (++l; l != std::sregex_iterator(); ++l)
        for (const std::string& key : rtdr::cited_equations((*l)[1].str())) keys.emplace(key, entry.path().string());
    }
  }
  return keys;
}

}  // namespace

TEST_CASE("cited_equations reads the keys of the citations the probe's terms carry") {
  using V = std::vector<std::string>;
  CHECK(rtdr::cited_equations("[SVGF17 Eq. 3]") == V{"SVGF17 Eq. 3"});
  CHECK(rtdr::cited_equations("[ASVGF18 Eq. 12, Eq. 13]") == V{"ASVGF18 Eq. 12", "ASVGF18 Eq. 13"});
  CHECK(rtdr::cited_equations("[SVGF17 Sec. 4.1, 4.2]") == V{"SVGF17 Sec. 4.1", "SVGF17 Sec. 4.2"});
  CHECK(rtdr::cited_equations("[TRMV21 Sec. 5, Eq. 7-9]") == V{"TRMV21 Sec. 5", "TRMV21 Eq. 7", "TRMV21 Eq. 8", "TRMV21 Eq. 9"});
  CHECK(rtdr::cited_equations("[ASVGF18 Eq. 9] = [SVGF17 Eq. 4]") == V{"ASVGF18 Eq. 9", "SVGF17 Eq. 4"});
  CHECK(rtdr::cited_equations("TRMV21 Eq. 1, between jittered screens") == V{"TRMV21 Eq. 1"});
  CHECK(rtdr::cited_equations("Reinhard02 Sec. 3.1: world luminance") == V{"Reinhard02 Sec. 3.1"});
  CHECK(rtdr::cited_equations("[EAW10] colour, sigma_rt 2^-i") == V{"EAW10"});
  CHECK(rtdr::cited_equations("Karis14: clip towards the mean") == V{"Karis14"});
  CHECK(rtdr::cited_equations("[SVGF17 Eq. 5]. Then [SVGF17 Eq. 5] again") == V{"SVGF17 Eq. 5"});
  CHECK(rtdr::cited_equations("Malvar and Sullivan 2003").empty());
  CHECK(rtdr::cited_equations("XSVGF17 Eq. 1").empty());
}

TEST_CASE("the typeset equations cover exactly the keys the golden passes' probe terms cite") {
  const std::map<std::string, std::string> cited = keys_cited_by_notes();
  REQUIRE(cited.size() >= 30);
  std::set<std::string> typeset;
  for (const rtdr::EquationTex& e : rtdr::equation_tex()) {
    INFO(e.key);
    CHECK(typeset.insert(std::string(e.key)).second);  // each key once
    CHECK(cited.count(std::string(e.key)) == 1);        // and cited by some note(): no TeX for nothing
    CHECK(rtdr::cited_equations(e.key) == std::vector<std::string>{std::string(e.key)});  // a key in its own form
    // Balanced braces, and no character KaTeX reads as the end of the formula.
    int depth = 0;
    for (char ch : e.tex) {
      depth += ch == '{' ? 1 : ch == '}' ? -1 : 0;
      CHECK(depth >= 0);
    }
    CHECK(depth == 0);
    CHECK(e.tex.find('$') == std::string_view::npos);
  }
  for (const auto& [key, file] : cited) {
    INFO(key << ", cited in " << file);
    CHECK(typeset.count(key) == 1);
  }
}

TEST_CASE("docs/equations.md names functions, tests and shaders that exist, in files that cite the equation") {
  const std::vector<Row> rows = table_rows();
  REQUIRE(rows.size() >= 15);
  for (const Row& row : rows) {
    INFO(row.paper << " " << row.equation);
    // Function cell: `path/file.cpp` followed by one or more `function_name`.
    const std::vector<std::string> fn = code_spans(row.function);
    REQUIRE(fn.size() >= 2);
    const fs::path source = fs::path(RTDR_SOURCE_DIR) / fn[0];
    REQUIRE(fs::exists(source));
    const std::string code = read(source);
    for (size_t i = 1; i < fn.size(); ++i) {
      INFO("function " << fn[i] << " in " << fn[0]);
      CHECK(std::regex_search(code, std::regex("\\b" + fn[i] + "\\s*\\(")));
    }
    // The implementing file cites the paper and the equation or section as the row names it.
    const std::string citation = row.paper + " " + row.equation;
    INFO("citation '" << citation << "' in " << fn[0]);
    CHECK(code.find(citation) != std::string::npos);
    // Test cell: `tests/<folder>_<stem>_test.cpp`, optionally followed by "a test case name".
    const std::vector<std::string> test = code_spans(row.test);
    REQUIRE(!test.empty());
    const fs::path test_file = fs::path(RTDR_SOURCE_DIR) / test[0];
    REQUIRE(fs::exists(test_file));
    std::smatch quoted;
    if (std::regex_search(row.test, quoted, std::regex("\"([^\"]+)\""))) {
      INFO("test case \"" << quoted[1].str() << "\" in " << test[0]);
      CHECK(read(test_file).find(quoted[1].str()) != std::string::npos);
    }
    // Shader cell: "-" until the port is written, else the shaders (`*.comp`) that port it, each of which exists
    // and cites the equation as the golden file does.
    for (const std::string& span : code_spans(row.shader)) {
      if (!span.ends_with(".comp")) continue;
      const fs::path shader = fs::path(RTDR_SOURCE_DIR) / span;
      INFO("shader " << span);
      REQUIRE(fs::exists(shader));
      CHECK(read(shader).find(citation) != std::string::npos);
    }
  }
}
