// Small string helpers every reader of user files needs (trimming, joining,
// close-name suggestions), so messages are built the same way everywhere.
#pragma once

#include <string>
#include <vector>

namespace lcm_control {

std::string trim(const std::string& s);
// Whitespace-separated words.
std::vector<std::string> split_words(const std::string& s);
// Fields between `sep`s, empty ones kept ("a,,b" -> a, "", b; "" -> one empty field).
std::vector<std::string> split(const std::string& s, char sep);
// A finite number and nothing else (blanks around it allowed); false for "", "1x", "nan", "inf".
bool parse_double(const std::string& text, double& out);
std::string join(const std::vector<std::string>& items, const std::string& sep = ", ");
// The first max_items joined, then "(and N more)": lists in answers and log lines that must stay short.
std::string join_some(const std::vector<std::string>& items, size_t max_items, const std::string& sep = ", ");
// Levenshtein distance, for "did you mean" suggestions.
size_t edit_distance(const std::string& a, const std::string& b);
// The candidate closest to `name`, "" if none is within `max_distance` edits.
std::string closest_name(const std::string& name, const std::vector<std::string>& candidates, size_t max_distance);
// Up to `most` distinct candidates nearest to `name`, nearest first (ties in the candidates' order), each within
// `max_distance` edits: the list a "did you mean" hint offers.
std::vector<std::string> closest_names(const std::string& name, const std::vector<std::string>& candidates, size_t most,
                                       size_t max_distance);

}  // namespace lcm_control
