// docs/equations.md is a promise: for every equation, the function that implements it, the test that checks
// it and the shaders that port it. This test keeps the promise true: every file it names exists, every function
// named is defined in its file, every quoted test case is in its test file, and the implementing file and every
// shader named cite the equation they claim to implement.
#include "markdown_fixtures.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
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

}  // namespace

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
