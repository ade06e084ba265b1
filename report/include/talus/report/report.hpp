#pragma once
/// @file
/// The Markdown report builder of the experiments: a report.md of headings,
/// paragraphs, bullet lists, tables and figure links, with the blank lines
/// Markdown needs between blocks written in one place.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace talus {

/// A Markdown table: a header row, then rows of the same width.
class Table {
 public:
  explicit Table(std::vector<std::string> columns);
  /// Appends a row; throws talus::Error if its width differs from the header's.
  Table& row(std::vector<std::string> cells);
  /// "| a | b |\n|---|---|\n| 1 | 2 |\n", every line after `indent` (for a
  /// table inside a list item).
  std::string markdown(std::string_view indent = "") const;

 private:
  std::vector<std::string> columns_;
  std::vector<std::vector<std::string>> rows_;
};

/// An image of a report: its caption (alt text) and file name.
struct FigureLink {
  std::string caption, file;
};

/// Builds a report: a title, then blocks in order. Consecutive bullets form
/// one list; every other block is separated from its neighbours by a blank line.
class Report {
 public:
  /// Starts with "# title".
  explicit Report(std::string_view title);

  Report& heading(std::string_view text, int level = 2);
  /// A paragraph of Markdown text (may span lines).
  Report& paragraph(std::string_view text);
  /// A list item, nested `depth` levels deep.
  Report& bullet(std::string_view text, int depth = 0);
  Report& table(const Table& table);
  /// An image link ![caption](file), as a block of its own.
  Report& figure(std::string_view caption, std::string_view file);

  /// A level-3 heading and its figures, one block each.
  Report& figures(std::string_view heading, const std::vector<FigureLink>& links);

  /// Writes `dir`/report.md.
  void write(const std::filesystem::path& dir) const;
  /// Ends the report with "Files: `files`" and the figures among them, then
  /// writes it to `dir`/report.md.
  void write(const std::filesystem::path& dir, std::string_view files,
             const std::vector<FigureLink>& figures);

 private:
  /// Starts a block: a blank line after the previous one (none between bullets).
  void begin_block(bool bullet);

  std::string text_;
  bool in_list_ = false;
};

}  // namespace talus
