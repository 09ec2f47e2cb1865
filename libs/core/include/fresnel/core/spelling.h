#pragma once
// "Did you mean": the nearest of a set of names to a mistyped word, for error messages (unknown
// commands, flags, setting keys, choices).
#include <string>
#include <vector>

namespace fresnel {

// The nearest of `names` to `word` by edit distance (Levenshtein, case-insensitive), or "" when
// none is within max(2, |word| / 3) edits.
std::string nearest_name(const std::string& word, const std::vector<std::string>& names);

// " (did you mean 'NAME'?)" for the nearest name, or "" when there is none.
std::string did_you_mean(const std::string& word, const std::vector<std::string>& names);

}  // namespace fresnel
