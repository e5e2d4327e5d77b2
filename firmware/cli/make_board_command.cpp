// `h4cam make-board`; see make_board_command.h.
#include "firmware/cli/make_board_command.h"

#include <memory>
#include <ostream>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/formats/board_yaml.h"
#include "firmware/board_print/board_print.h"

namespace h4::cam {

void RunMakeBoard(const MakeBoardArgs& args, std::ostream& out) {
  const BoardSpec board = ReadBoardYaml(args.board_path);
  BoardPrintOptions options;
  options.margin = args.margin;
  BoardLayout layout;
  std::string error;
  if (!LayoutBoard(board, options, &layout, &error)) {
    throw std::runtime_error(args.board_path + ": " + error);
  }
  if (!WriteBoardFile(args.out_path, layout, args.dpi, &error)) throw std::runtime_error(error);
  out << "wrote " << args.out_path << ": " << DescribeBoard(board) << "; page "
      << layout.width * 1000 << " x " << layout.height * 1000 << " mm\n";
}

void DeclareMakeBoardCommand(CLI::App* command) {
  const auto args = std::make_shared<MakeBoardArgs>();
  h4::cli::AddBoardOption(command, &args->board_path)->required();
  h4::cli::AddOutOption(command, &args->out_path, "Output file: .svg, .pdf or .png");
  command->add_option("--dpi", args->dpi, "PNG resolution, dots per inch")->default_val(args->dpi);
  command->add_option("--margin", args->margin, "White border around the pattern, m")
      ->default_val(args->margin);
  h4::cli::RunWhenParsed(command, args,
                         [](const MakeBoardArgs& parsed) { RunMakeBoard(parsed, std::cout); });
}

}  // namespace h4::cam
