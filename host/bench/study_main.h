// What the study programs (plain programs whose figures the README quotes with their command
// lines) share: their main(), where a bad option or a failure ends it with one line on stderr
// and exit 1; their command line of FLAG VALUE pairs; the median they report.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <fmt/core.h>

namespace h4::host {

/// Runs the study `run` with the options `parse` reads from the command line; 0 when it
/// ends, 1 after printing "<program>: <what went wrong>".
template <typename Options>
int StudyMain(const char* program, int argc, char** argv, Options (*parse)(int, char**),
              void (*run)(const Options&)) {
  try {
    run(parse(argc, argv));
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}: {}\n", program, e.what());
    return 1;
  }
}

/// Calls on_pair(flag, value) for each FLAG VALUE pair of the command line, in order; a last
/// flag without a value is ignored. on_pair throws on a flag or value it does not take.
template <typename OnPair>
void ForEachFlagAndValue(int argc, char** argv, OnPair on_pair) {
  for (int i = 1; i + 1 < argc; i += 2) on_pair(std::string(argv[i]), std::string(argv[i + 1]));
}

/// The median (the mean of the middle two for an even count); NaN when there is no value.
inline double Median(std::vector<double> values) {
  if (values.empty()) return NAN;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace h4::host
