// `h4cam make-board`; see make_board_command.h.
#include "firmware/cli/make_board_command.h"

#include <map>
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
  options.paper = args.paper;
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
  const std::map<std::string, PaperSize> papers = {{"auto", PaperSize::kSmallestIso},
                                                   {"a4", PaperSize::kA4},
                                                   {"a3", PaperSize::kA3},
                                                   {"fit", PaperSize::kFit}};
  command
      ->add_option("--paper", args->paper,
                   "Page: auto (the smallest of A4 and A3 that holds the board, centred, portrait "
                   "when it fits; the board's own size beyond A3), a4, a3, or fit (the board and "
                   "its margins)")
      ->transform(CLI::CheckedTransformer(papers, CLI::ignore_case))
      ->default_str("auto");
  h4::cli::RunWhenParsed(command, args,
                         [](const MakeBoardArgs& parsed) { RunMakeBoard(parsed, std::cout); });
}

}  // namespace h4::cam
