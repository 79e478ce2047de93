// A program file, its points file and its flow: everything about a program that needs no
// arm. The points file is the one given, else FILE with the extension .points if it
// exists, else none (a program without points).
#pragma once

#include <filesystem>

#include "core/error.hpp"
#include "files/points_file.hpp"
#include "program/program_flow.hpp"
#include "program/program_syntax.hpp"

namespace armctl::program {

struct LoadedProgram {
  Program program;
  files::PointsFile points;
  Flow flow;
};

// `points` empty: FILE.points beside the program, if there is one.
Result<LoadedProgram> load_program(const std::filesystem::path& file, const std::filesystem::path& points = {});

}  // namespace armctl::program
