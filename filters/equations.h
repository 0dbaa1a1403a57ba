// The equations the probe's terms cite, typeset: for each key ("SVGF17 Eq. 5", "TRMV21 Sec. 5", "EAW10"), the
// TeX of what the golden pass computes under that key, in the symbols of its code and its probe terms. This table
// is the one place the TeX lives: `rtdr view` typesets it beside each probed term (KaTeX), and
// tests/docs_equations_test.cpp keeps it true: every key a note() in filters/ cites has its TeX here, every key
// here is cited by some note(), and every key is one of the papers of docs/equations.md.
//
// A key is a paper's key and, where the paper numbers it, "Eq. N" or "Sec. N": the forms docs/equations.md's
// first two columns use. An equation that spans sections (SVGF's temporal accumulation, Sec. 4.1) is written as
// the code computes it, with the choices the paper leaves open (the max(alpha, 1/n) of the first frames).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rtdr {

struct EquationTex {
  std::string_view key;  // "SVGF17 Eq. 3"
  std::string_view tex;  // KaTeX-compatible TeX, display style
};

// Every typeset equation, by paper and then by number.
const std::vector<EquationTex>& equation_tex();

// The keys a free-text citation names, in order, each once: "[ASVGF18 Eq. 12, Eq. 13]" gives "ASVGF18 Eq. 12" and
// "ASVGF18 Eq. 13"; "[SVGF17 Sec. 4.1, 4.2]" gives "SVGF17 Sec. 4.1" and "SVGF17 Sec. 4.2"; "[ASVGF18 Eq. 9-10]"
// gives Eq. 9 and Eq. 10; "[ASVGF18 Eq. 9] = [SVGF17 Eq. 4]" both papers' keys; "[EAW10] normal" and "Karis14:
// clip" the paper alone, "EAW10" and "Karis14". Papers are those of kPaperKeys; other text is ignored.
std::vector<std::string> cited_equations(std::string_view cite);

// The keys of the papers and other sources docs/equations.md lists.
inline constexpr std::string_view kPaperKeys[] = {"SVGF17", "ASVGF18", "TRMV21", "Reinhard02",
                                                   "Karis14", "Wang04", "EAW10"};

}  // namespace rtdr
