#pragma once

#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "biovision_common/atomic_file.hpp"  // FileError

namespace biovision_common
{
/// Command-line options of every evaluation, training and benchmark tool, parsed by CLI11 (Debian's
/// libcli11-dev): typed and strict, so `--threads x` is an error naming the option, not 0.
///
///   ToolOptions options("stereo_eval", "Evaluates BioBin against OpenCV on Middlebury scenes.");
///   int threads = 2;
///   options.app().add_option("--threads", threads, "worker threads")->check(kPositive);
///   options.parse(argc, argv);
///
/// --help shows each option's default, read from its variable: usage texts need not repeat them.
class ToolOptions
{
public:
  ToolOptions(const std::string& tool, const std::string& description);

  /// Where options are declared (add_option, add_flag; `->delimiter(',')` for comma lists).
  CLI::App& app() { return app_; }

  /// Parses argv. Prints the usage and exits 0 on --help; prints the error and exits 2 on an unknown
  /// option, a missing or ill-typed value, or a failed check. Arguments starting with "__" are skipped:
  /// roslaunch appends __name:= and __log:= when a tool runs as a <node> (the emulators do).
  void parse(int argc, char** argv);

  /// The options as given ("--threads 2 --json out.json"), to record how a result was made.
  const std::string& command() const { return command_; }

  /// Writes a tool's --json document (writeJsonFile) unless `path` is empty; on a FileError prints
  /// "<tool>: <why>" to stderr and returns false, so the tool can exit 1.
  bool writeJson(const std::string& path, const nlohmann::json& document) const;
  bool writeJson(const std::string& path, const nlohmann::ordered_json& document) const;

private:
  CLI::App app_;
  std::string command_;
};

/// `->check(kPositive)`, `->check(kNonNegative)` on numeric options: as CLI::PositiveNumber and
/// CLI::NonNegativeNumber, but the failure reads "--threads: 0 is not > 0" (CLI11 2.1's prints DBL_MAX
/// in full). A value that is not a number is left to the type check ("Could not convert").
extern const CLI::Validator kPositive;
extern const CLI::Validator kNonNegative;

/// Writes `document` to `path` atomically, pretty-printed with a trailing newline. Throws FileError.
void writeJsonFile(const std::string& path, const nlohmann::json& document);
/// The same, keys in the order they were added: scripts/bench_report.py lays out docs/benchmarks.md in
/// the order a tool wrote its figures (nlohmann::json would sort them).
void writeJsonFile(const std::string& path, const nlohmann::ordered_json& document);
}  // namespace biovision_common
