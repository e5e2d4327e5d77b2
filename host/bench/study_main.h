// The main() of a study program (a plain program whose figures the README quotes with its
// command line): a bad option or a failure ends it with one line on stderr and exit 1.
#pragma once

#include <cstdio>
#include <exception>

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

}  // namespace h4::host
