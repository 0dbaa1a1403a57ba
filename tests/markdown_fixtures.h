// Reading the tables of our Markdown docs, for the tests that keep them true (docs_equations_test.cpp,
// docs_buffers_test.cpp).
#pragma once

#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace test {

// The cells of a table row "| a | b |", each trimmed of spaces.
inline std::vector<std::string> split_row(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line.substr(1));  // drop the leading '|'
  for (std::string cell; std::getline(ss, cell, '|');) {
    const size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
    cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
  }
  return cells;
}

// Every `code span` in a cell.
inline std::vector<std::string> code_spans(const std::string& cell) {
  std::vector<std::string> spans;
  const std::regex span("`([^`]+)`");
  for (auto it = std::sregex_iterator(cell.begin(), cell.end(), span); it != std::sregex_iterator(); ++it)
    spans.push_back((*it)[1].str());
  return spans;
}

}  // namespace test
