// The log's line style; see log_style.h.
#include "host/cli/log_style.h"

#include <memory>

#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "common/cli/command_line.h"

namespace h4::host::cli {
namespace {

// "%*" of the pattern: "<program>: error: " for errors, "<program>: warning: " for
// warnings, nothing for information and debug lines.
class SeverityPrefix : public spdlog::custom_flag_formatter {
 public:
  explicit SeverityPrefix(std::string program) : program_(std::move(program)) {}

  void format(const spdlog::details::log_msg& message, const std::tm&,
              spdlog::memory_buf_t& destination) override {
    const std::string prefix = Prefix(message.level);
    destination.append(prefix.data(), prefix.data() + prefix.size());
  }

  std::unique_ptr<custom_flag_formatter> clone() const override {
    return std::make_unique<SeverityPrefix>(program_);
  }

 private:
  std::string Prefix(spdlog::level::level_enum level) const {
    if (level >= spdlog::level::err) return h4::cli::ErrorLine(program_, "");
    if (level == spdlog::level::warn) return program_ + ": warning: ";
    return "";
  }

  std::string program_;
};

}  // namespace

void UseProgramLogStyle(const std::string& program) {
  auto logger = spdlog::stderr_color_mt(program);
  auto formatter = std::make_unique<spdlog::pattern_formatter>();
  formatter->add_flag<SeverityPrefix>('*', program).set_pattern("%*%v");
  logger->set_formatter(std::move(formatter));
  spdlog::set_default_logger(logger);
}

}  // namespace h4::host::cli
