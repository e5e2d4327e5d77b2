// The benchmarks' command lines: each argument `key=value` (or a bare word, whose key is
// the word and whose value is empty), in order.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

namespace h4::cam::bench {

struct Argument {
  std::string text;   ///< as given
  std::string key;    ///< before the first '=' (the whole text without one)
  std::string value;  ///< after it ("" without one)
  bool has_value = false;
};

inline std::vector<Argument> Arguments(int argc, char** argv) {
  std::vector<Argument> arguments;
  for (int i = 1; i < argc; ++i) {
    Argument a;
    a.text = argv[i];
    const size_t eq = a.text.find('=');
    a.has_value = eq != std::string::npos;
    a.key = a.text.substr(0, eq);
    a.value = a.has_value ? a.text.substr(eq + 1) : "";
    arguments.push_back(a);
  }
  return arguments;
}

/// A benchmark program's main: `read` parses the command line into an Args (false once it
/// has said on stderr what is wrong: exit status 1), then `run` measures and gives the exit
/// status. Stdout is line-buffered so that each row shows as soon as it is measured (a run
/// takes minutes), into a pipe or a file too.
template <typename Args>
int RunOnArguments(int argc, char** argv, bool (*read)(int, char**, Args*),
                   int (*run)(const Args&)) {
  std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
  Args args;
  if (!read(argc, argv, &args)) return 1;
  return run(args);
}

}  // namespace h4::cam::bench
