// Test helpers for the file format readers: check that a call throws a FormatError that
// names the right source, line and field (and says what was expected), and give each
// test its own temporary file path.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include "common/formats/format_error.h"

namespace h4 {

/// Success when `call` throws FormatError with this line and field, whose message names
/// `source` and contains `expected_text` (when not empty).
template <typename Call>
::testing::AssertionResult FailsWith(Call&& call, const std::string& source, int line,
                                     const std::string& field,
                                     const std::string& expected_text = "") {
  try {
    call();
  } catch (const FormatError& e) {
    const std::string what = e.what();
    if (e.file() != source || what.find(source) == std::string::npos) {
      return ::testing::AssertionFailure() << "wrong file in: " << what;
    }
    if (e.line() != line) {
      return ::testing::AssertionFailure()
             << "line " << e.line() << ", expected " << line << ", in: " << what;
    }
    if (e.field() != field) {
      return ::testing::AssertionFailure()
             << "field '" << e.field() << "', expected '" << field << "', in: " << what;
    }
    if (!expected_text.empty() && what.find(expected_text) == std::string::npos) {
      return ::testing::AssertionFailure() << "message lacks '" << expected_text << "': " << what;
    }
    return ::testing::AssertionSuccess() << what;
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "not a FormatError: " << e.what();
  }
  return ::testing::AssertionFailure() << "no exception";
}

/// `text` with its first `from` replaced by `to` (a test failure when there is none): a
/// known-good file made malformed in one place.
inline std::string ReplacedOnce(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

/// A malformed input and what its FormatError must name: the line, the field and a part of
/// the message ("" for any).
struct MalformedInput {
  std::string text;
  int line = 0;
  std::string field;
  std::string expected_text;
};

/// For each input: parse(input.text, source) fails with a FormatError as FailsWith checks.
template <typename Parse>
void ExpectEachFailsWith(Parse&& parse, const std::string& source,
                         const std::vector<MalformedInput>& inputs) {
  for (const MalformedInput& input : inputs) {
    EXPECT_TRUE(FailsWith([&] { parse(input.text, source); }, source, input.line, input.field,
                          input.expected_text))
        << "input:\n"
        << input.text;
  }
}

/// A path in the temporary directory unique to this process and test.
inline std::string TempPath(const std::string& file_name) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / fmt::format("h4_formats_{}", ::getpid());
  std::filesystem::create_directories(dir);
  return (dir / (std::string(info->test_suite_name()) + "_" + info->name() + "_" + file_name))
      .string();
}

}  // namespace h4
