#include "program/program_load.hpp"

#include "program/program_parser.hpp"

namespace armctl::program {

Result<LoadedProgram> load_program(const std::filesystem::path& file, const std::filesystem::path& points) {
  LoadedProgram l;
  auto program = read_program_file(file);
  if (!program) return program.error();
  l.program = std::move(program).value();
  std::filesystem::path used = points;
  if (used.empty()) {
    std::filesystem::path guess = file;
    guess.replace_extension(".points");
    std::error_code ec;
    if (std::filesystem::exists(guess, ec)) used = guess;
  }
  if (!used.empty()) {
    auto read = files::read_points_file(used);
    if (!read) return read.error();
    l.points = std::move(read).value();
  }
  auto flow = run_flow(l.program, l.points);
  if (!flow) return flow.error();
  l.flow = std::move(flow).value();
  return l;
}

}  // namespace armctl::program
