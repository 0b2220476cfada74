// disco — "did you mean" for a mistyped word: the candidates closest to it.
//
// closest() returns the candidates within max(1, size/3) edits (insertions, deletions,
// substitutions, transpositions of adjacent letters: the optimal string alignment
// distance) of `word`, nearest first, ties in the candidates' order. A candidate whose
// last dotted part equals `word` ("zeta_max" for "elastic.zeta_max") counts as 1 edit.
// did_you_mean() turns them into " (did you mean 'a' or 'b'?)", or "" when none is close.
#pragma once

#include <string>
#include <vector>

namespace disco {

std::vector<std::string> closest(const std::string& word, const std::vector<std::string>& candidates);
std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace disco
