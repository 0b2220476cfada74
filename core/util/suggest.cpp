#include "core/util/suggest.h"

#include <algorithm>
#include <cstddef>

namespace disco {
namespace {

// The optimal string alignment distance (Levenshtein with adjacent transpositions).
std::size_t edits(const std::string& a, const std::string& b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

}  // namespace

std::vector<std::string> closest(const std::string& word, const std::vector<std::string>& candidates) {
  const std::size_t limit = std::max<std::size_t>(1, word.size() / 3);
  std::vector<std::pair<std::size_t, std::size_t>> scored;  // (edits, index)
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const std::string& c = candidates[k];
    const std::size_t dot = c.rfind('.');
    std::size_t e = edits(word, c);
    if (dot != std::string::npos && c.substr(dot + 1) == word) e = std::min<std::size_t>(e, 1);
    if (e <= limit && c != word) scored.emplace_back(e, k);
  }
  std::stable_sort(scored.begin(), scored.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::string> out;
  for (const auto& [e, k] : scored)
    if (std::find(out.begin(), out.end(), candidates[k]) == out.end()) out.push_back(candidates[k]);
  return out;
}

std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates) {
  const std::vector<std::string> near = closest(word, candidates);
  if (near.empty()) return "";
  std::string text = " (did you mean '" + near[0] + "'";
  if (near.size() > 1) text += " or '" + near[1] + "'";
  return text + "?)";
}

}  // namespace disco
