#include "description/text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace lcm_control {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

std::vector<std::string> split_words(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  std::string w;
  while (in >> w) out.push_back(w);
  return out;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out(1);
  for (char c : s) {
    if (c == sep)
      out.emplace_back();
    else
      out.back() += c;
  }
  return out;
}

bool parse_double(const std::string& text, double& out) {
  const std::string t = trim(text);
  if (t.empty()) return false;
  char* end = nullptr;
  out = std::strtod(t.c_str(), &end);
  return end && *end == '\0' && std::isfinite(out);
}

std::string join(const std::vector<std::string>& items, const std::string& sep) {
  std::string s;
  for (size_t k = 0; k < items.size(); ++k) s += (k ? sep : "") + items[k];
  return s;
}

std::string join_some(const std::vector<std::string>& items, size_t max_items, const std::string& sep) {
  if (items.size() <= max_items) return join(items, sep);
  std::string s = join(std::vector<std::string>(items.begin(), items.begin() + long(max_items)), sep);
  return s + (s.empty() ? "" : " ") + "(and " + std::to_string(items.size() - max_items) + " more)";
}

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string closest_name(const std::string& name, const std::vector<std::string>& candidates, size_t max_distance) {
  std::string best;
  size_t best_d = max_distance + 1;
  for (const auto& c : candidates) {
    const size_t d = edit_distance(name, c);
    if (d < best_d) best_d = d, best = c;
  }
  return best;
}

std::vector<std::string> closest_names(const std::string& name, const std::vector<std::string>& candidates, size_t most,
                                       size_t max_distance) {
  std::vector<std::pair<size_t, std::string>> near;
  for (const auto& c : candidates) {
    const size_t d = edit_distance(name, c);
    if (d <= max_distance && std::none_of(near.begin(), near.end(), [&](const auto& n) { return n.second == c; }))
      near.emplace_back(d, c);
  }
  std::stable_sort(near.begin(), near.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> out;
  for (size_t k = 0; k < near.size() && k < most; ++k) out.push_back(near[k].second);
  return out;
}

}  // namespace lcm_control
