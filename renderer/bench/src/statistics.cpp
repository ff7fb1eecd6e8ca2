#include "lgh/bench/statistics.hpp"

#include <algorithm>

namespace lgh::bench {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

void TimingSamples::add(const std::string& name, double ms) {
  auto [it, inserted] = values_.try_emplace(name);
  if (inserted) order_.push_back(name);
  it->second.push_back(ms);
}

double TimingSamples::median(const std::string& name) const {
  const auto it = values_.find(name);
  return it == values_.end() ? 0.0 : bench::median(it->second);
}

TimingStats TimingSamples::stats(const std::string& name) const {
  const std::vector<double>& values = values_.at(name);
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  return {name, bench::median(values), *lo, *hi};
}

}  // namespace lgh::bench
