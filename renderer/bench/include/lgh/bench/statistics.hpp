// Statistics shared by the benchmarks: timings sampled per named step or pass over repeated runs,
// reduced to median, minimum and maximum.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace lgh::bench {

// The median of `values` (the mean of the middle two for an even count); 0 when empty.
double median(std::vector<double> values);

// One named timing over the timed iterations, in milliseconds.
struct TimingStats {
  std::string name;
  double medianMs = 0.0;
  double minMs = 0.0;
  double maxMs = 0.0;
};

// Milliseconds per name, collected over repeated runs; names keep their first-seen order.
class TimingSamples {
 public:
  void add(const std::string& name, double ms);

  const std::vector<std::string>& names() const { return order_; }
  // The median of the name's samples; 0 for a name never added.
  double median(const std::string& name) const;
  // Median, minimum and maximum of a name that was added.
  TimingStats stats(const std::string& name) const;

 private:
  std::vector<std::string> order_;
  std::map<std::string, std::vector<double>> values_;
};

}  // namespace lgh::bench
