// The typeset equations the probe's terms cite, and the parser of citations. See equations.h.
#include "filters/equations.h"

#include <algorithm>
#include <cctype>

namespace rtdr {

const std::vector<EquationTex>& equation_tex() {
  static const std::vector<EquationTex> table = {
      // SVGF17: C. Schied et al. 2017, Spatiotemporal Variance-Guided Filtering.
      {"SVGF17 Sec. 3", R"tex(c = e + \max(a, 0.001)\,\big(L_{\mathrm{direct}} + L_{\mathrm{indirect}}\big))tex"},
      {"SVGF17 Sec. 4.1",
       R"tex(C'_i(p) = \alpha\,C_i(p) + (1 - \alpha)\,C'_{i-1}(p'), \qquad \alpha \leftarrow \max\!\big(\alpha, \tfrac{1}{n_i}\big))tex"},
      {"SVGF17 Sec. 4.2",
       R"tex(\mu'_{1,i} = \alpha\,l_i + (1-\alpha)\,\mu'_{1,i-1}, \quad \mu'_{2,i} = \alpha\,l_i^2 + (1-\alpha)\,\mu'_{2,i-1}, \quad \sigma'^2_i = \mu'_{2,i} - \mu'^2_{1,i})tex"},
      {"SVGF17 Sec. 4.3",
       R"tex(\operatorname{Var}(c_{i+1}(p)) = \frac{\sum_{q \in \Omega} h(q)^2\,w(p,q)^2\,\operatorname{Var}(c_i(q))}{\big(\sum_{q \in \Omega} h(q)\,w(p,q)\big)^2})tex"},
      {"SVGF17 Sec. 4.4",
       R"tex(g_{3\times3}(\operatorname{Var})(p) = \sum_{q \in 3\times3} g(q)\,\operatorname{Var}(q), \quad g = \tfrac{1}{16}\begin{pmatrix}1&2&1\\2&4&2\\1&2&1\end{pmatrix})tex"},
      {"SVGF17 Eq. 1",
       R"tex(c_{i+1}(p) = \frac{\sum_{q \in \Omega} h(q)\,w(p,q)\,c_i(q)}{\sum_{q \in \Omega} h(q)\,w(p,q)})tex"},
      {"SVGF17 Eq. 2", R"tex(w(p,q) = w_z\,w_n\,w_l)tex"},
      {"SVGF17 Eq. 3",
       R"tex(w_z = \exp\!\left(-\frac{|z(p) - z(q)|}{\sigma_z\,|\nabla z(p) \cdot (p - q)| + \varepsilon}\right))tex"},
      {"SVGF17 Eq. 4", R"tex(w_n = \max\!\big(0,\, n(p) \cdot n(q)\big)^{\sigma_n})tex"},
      {"SVGF17 Eq. 5",
       R"tex(w_l = \exp\!\left(-\frac{|l_i(p) - l_i(q)|}{\sigma_l \sqrt{g_{3\times3}(\operatorname{Var}(l_i(p)))} + \varepsilon}\right))tex"},
      // ASVGF18: C. Schied, C. Peters, C. Dachsbacher 2018, Gradient Estimation for Real-Time Adaptive Temporal
      // Filtering.
      {"ASVGF18 Sec. 3.3",
       R"tex(\text{stratum } (s_x, s_y) = \big(\lfloor x / s \rfloor, \lfloor y / s \rfloor\big), \quad \text{at most one gradient sample per } s \times s \text{ stratum})tex"},
      {"ASVGF18 Sec. 3.4",
       R"tex(\hat l^{(0)} = \frac{1}{|S|}\sum_{p \in S} l(p), \quad \operatorname{Var}\big(\hat l^{(0)}\big) = \frac{1}{|S|}\sum_{p \in S} l(p)^2 - \big(\hat l^{(0)}\big)^2, \quad S \text{ the stratum's pixels})tex"},
      {"ASVGF18 Sec. 3.5",
       R"tex(\lambda_{\max}(p) = \max_{|d_x|, |d_y| \le r} \lambda(s_p + d))tex"},
      {"ASVGF18 Sec. 4",
       R"tex(h = \tfrac{1}{9}\,\mathbf{1}_{3\times3}, \qquad n_i = (1 - \lambda)\,n_{i-1} + 1)tex"},
      {"ASVGF18 Sec. 5", R"tex(\alpha = 0.1)tex"},
      {"ASVGF18 Eq. 2",
       R"tex(f_i\big(\tilde G_{i,j}, \xi_{i-1,j}\big): \text{ the sample } j \text{ of frame } i-1 \text{, forward-projected to } \tilde G_{i,j} \text{ and shaded with its old seed})tex"},
      {"ASVGF18 Eq. 3",
       R"tex(\delta_{i,j} = f_i\big(\tilde G_{i,j}, \xi_{i-1,j}\big) - f_{i-1}\big(G_{i-1,j}, \xi_{i-1,j}\big))tex"},
      {"ASVGF18 Eq. 7",
       R"tex(\hat l^{(k+1)}(p) = \frac{\sum_{q \in \Omega} h(q)\,w^{(k)}(p,q)\,\hat l^{(k)}(q)}{\sum_{q \in \Omega} h(q)\,w^{(k)}(p,q)})tex"},
      {"ASVGF18 Eq. 9", R"tex(w_n = \max\!\big(0,\, n(p) \cdot n(q)\big)^{\sigma_n})tex"},
      {"ASVGF18 Eq. 10",
       R"tex(w_z = \exp\!\left(-\frac{|z(p) - z(q)|}{\sigma_z\,|\nabla z(p) \cdot (p - q)| + \varepsilon}\right))tex"},
      {"ASVGF18 Eq. 11",
       R"tex(w_l^{(k)} = \exp\!\left(-\frac{|\hat l^{(k)}(p) - \hat l^{(k)}(q)|}{\sigma_l \sqrt{g_{3\times3}(\operatorname{Var}(\hat l^{(k)}(p)))} + \varepsilon}\right))tex"},
      {"ASVGF18 Eq. 12",
       R"tex(\hat\delta^{(k+1)}(p) = \frac{\sum_{q} h(q)\,w^{(k)}(p,q)\,\hat\delta^{(k)}(q)}{\sum_{q} h(q)\,w^{(k)}(p,q)}, \quad \hat\Delta^{(k+1)} \text{ likewise})tex"},
      {"ASVGF18 Eq. 13",
       R"tex(\Delta_{i,j} = \max\!\big(f_i(\tilde G_{i,j}, \xi_{i-1,j}),\; f_{i-1}(G_{i-1,j}, \xi_{i-1,j})\big))tex"},
      {"ASVGF18 Eq. 14", R"tex(\lambda(p) = \min\!\left(1, \frac{|\hat\delta(p)|}{\hat\Delta(p)}\right))tex"},
      {"ASVGF18 Eq. 15", R"tex(\alpha_i(p) = \big(1 - \lambda(p)\big)\,\alpha + \lambda(p))tex"},
      // TRMV21: Z. Zeng et al. 2021, Temporally Reliable Motion Vectors for Real-time Ray Tracing.
      {"TRMV21 Sec. 4.1",
       R"tex(m^V \text{ splatted: each pixel in shadow writes its } m^V \text{ over the } 9 \times 9 \text{ pixels around it})tex"},
      {"TRMV21 Sec. 4.3",
       R"tex(L'_k = \sum_{l} \frac{\Omega(a_{kl})}{\sum_{m} \Omega(a_{km})}\,L_l \quad \text{(the cones at } x^O \text{, re-oriented to } n\text{)})tex"},
      {"TRMV21 Sec. 5",
       R"tex(\tilde c = \text{separable joint bilateral } G(k; 0, \sigma)\,w_z\,w_n, \quad \bar c^*_{i-1} = \operatorname{clamp}\big(\bar c_{i-1}, \mu - \gamma\sigma, \mu + \gamma\sigma\big), \quad \mathrm{std} = \min(w_A + w_C, 5))tex"},
      {"TRMV21 Eq. 1", R"tex(x_{i-1} = P_{i-1}\,T^{-1}\,P_i^{-1}\,x_i, \qquad m = x_{i-1} - x_i)tex"},
      {"TRMV21 Eq. 2", R"tex(\bar c_i(x_i) = \alpha\,\tilde c_i(x_i) + (1 - \alpha)\,\bar c^*_{i-1}(x_{i-1}))tex"},
      {"TRMV21 Eq. 3",
       R"tex(x^V_{i-1} = P_{i-1}\Big(\big[T^{-1} l_i \to T^{-1} b_i\big] \cap T^{-1}\,\mathrm{plane}(s_i)\Big), \qquad m^V = x^V_{i-1} - x_i)tex"},
      {"TRMV21 Eq. 4",
       R"tex(\alpha^V = 1 - G\big(\theta - \tfrac{\pi}{2};\, 0, \sigma\big)\,(1 - \alpha), \quad \theta = \angle\big(n(s_i),\, s_i \to s^V_{i-1}\big))tex"},
      {"TRMV21 Eq. 6",
       R"tex(x^O_{i-1} = y + (x_i - z), \quad y = P_{i-1}\,T^{-1}(x_i)\,P_i^{-1}\,x_i, \quad z = P_i\,T(y)\,P_{i-1}^{-1}\,y)tex"},
      {"TRMV21 Eq. 7", R"tex(w_A = \big(\alpha^V - \alpha\big)^2)tex"},
      {"TRMV21 Eq. 8",
       R"tex(w_C = \frac{\big|\bar c^*_{i-1}(x_{i-1}) - \bar c_{i-1}(x_{i-1})\big|}{\bar c_{i-1}(x_{i-1}) + \epsilon})tex"},
      {"TRMV21 Eq. 11", R"tex(L_o = \frac{1}{\pi}\sum_{k=1}^{6} c_k\,L_k)tex"},
      // Other sources.
      {"Reinhard02 Sec. 3.1", R"tex(L_w = 0.2126\,R + 0.7152\,G + 0.0722\,B)tex"},
      {"Reinhard02 Eq. 2", R"tex(L = \mathrm{exposure} \cdot L_w)tex"},
      {"Reinhard02 Eq. 3", R"tex(L_d = \frac{L}{1 + L}, \qquad c_d = \operatorname{clamp}\!\Big(\frac{L_d}{L_w}\,c,\, 0, 1\Big))tex"},
      {"Karis14",
       R"tex(o = \alpha\,c + (1 - \alpha)\,\operatorname{clip}\big(h,\, [\min_{3\times3}, \max_{3\times3}]\big) \quad \text{in YCoCg})tex"},
      {"EAW10",
       R"tex(c_{i+1}(p) = \frac{\sum_q h(q)\,w(p,q)\,c_i(q)}{\sum_q h(q)\,w(p,q)}, \quad w = w_{rt}\,w_n\,w_x, \quad w_\cdot = \exp\!\Big(-\frac{\lVert \cdot_p - \cdot_q \rVert^2}{\sigma_\cdot^2}\Big))tex"},
  };
  return table;
}

namespace {

bool starts_with_at(std::string_view text, size_t at, std::string_view prefix) {
  return text.substr(at, prefix.size()) == prefix;
}

// The number at `at` ("4", "4.2"; a trailing dot is not part of it), or "" when there is none.
std::string_view number_at(std::string_view text, size_t at) {
  size_t end = at;
  while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) {
    ++end;
    if (end + 1 < text.size() && text[end] == '.' && std::isdigit(static_cast<unsigned char>(text[end + 1]))) ++end;
  }
  return text.substr(at, end - at);
}

void add_once(std::vector<std::string>& keys, std::string key) {
  if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(std::move(key));
}

// The keys named by the items after a paper key, from `at`: " Eq. N" or " Sec. N" first, then any of ", Eq. N",
// ", Sec. N", ", N" (the same kind again) and "-N" (a range of equations). Stops at the first other text.
std::vector<std::string> items_after(std::string_view paper, std::string_view text, size_t at) {
  std::vector<std::string> keys;
  std::string_view kind;  // "Eq." or "Sec." of the last item
  int last = 0;           // the last equation number, for a range
  const auto add = [&](std::string_view number) {
    add_once(keys, std::string(paper) + " " + std::string(kind) + " " + std::string(number));
    if (number.find('.') == std::string_view::npos) last = std::stoi(std::string(number));
  };
  // The kind of item at `p` ("Eq. ", "Sec. "), moving `p` past it; "" when there is none.
  const auto read_kind = [&](size_t& p) {
    for (std::string_view k : {std::string_view("Eq. "), std::string_view("Sec. ")})
      if (starts_with_at(text, p, k)) {
        p += k.size();
        return k.substr(0, k.size() - 1);
      }
    return std::string_view();
  };
  for (bool first = true;; first = false) {
    size_t p = at;
    if (!first && kind == "Eq." && starts_with_at(text, p, "-")) {  // "Eq. 9-10"
      const std::string_view n = number_at(text, p + 1);
      if (n.empty()) break;
      for (int i = last + 1; i <= std::stoi(std::string(n)) && i <= last + 32; ++i) add(std::to_string(i));
      at = p + 1 + n.size();
      continue;
    }
    if (!starts_with_at(text, p, first ? " " : ", ")) break;
    p += first ? 1 : 2;
    const std::string_view k = read_kind(p);
    if (k.empty() && first) break;
    if (!k.empty()) kind = k;
    const std::string_view n = number_at(text, p);
    if (n.empty()) break;
    add(n);
    at = p + n.size();
  }
  return keys;
}

}  // namespace

std::vector<std::string> cited_equations(std::string_view cite) {
  std::vector<std::string> keys;
  for (size_t at = 0; at < cite.size(); ++at) {
    for (std::string_view paper : kPaperKeys) {
      if (!starts_with_at(cite, at, paper)) continue;
      // A whole word: "SVGF17" but not the end of "ASVGF17".
      if (at > 0 && std::isalnum(static_cast<unsigned char>(cite[at - 1]))) continue;
      const std::vector<std::string> items = items_after(paper, cite, at + paper.size());
      if (items.empty()) add_once(keys, std::string(paper));
      for (const std::string& key : items) add_once(keys, key);
      at += paper.size() - 1;
      break;
    }
  }
  return keys;
}

}  // namespace rtdr
