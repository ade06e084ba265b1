#include "talus/report/report.hpp"

#include <utility>

#include "talus/core/error.hpp"
#include "talus/report/plot.hpp"

namespace talus {

Table::Table(std::vector<std::string> columns) : columns_(std::move(columns)) {}

Table& Table::row(std::vector<std::string> cells) {
  if (cells.size() != columns_.size()) {
    throw Error("report table: a row of " + std::to_string(cells.size()) + " cells under " +
                std::to_string(columns_.size()) + " columns");
  }
  rows_.push_back(std::move(cells));
  return *this;
}

std::string Table::markdown(std::string_view indent) const {
  const auto line = [&](const std::vector<std::string>& cells) {
    std::string text = std::string(indent) + "|";
    for (const std::string& cell : cells) text += " " + cell + " |";
    return text + "\n";
  };
  std::string text = line(columns_) + std::string(indent) + "|";
  for (std::size_t k = 0; k < columns_.size(); ++k) text += "---|";
  text += "\n";
  for (const auto& cells : rows_) text += line(cells);
  return text;
}

Report::Report(std::string_view title) : text_("# " + std::string(title) + "\n") {}

void Report::begin_block(bool bullet) {
  if (!(bullet && in_list_)) text_ += "\n";
  in_list_ = bullet;
}

Report& Report::heading(std::string_view text, int level) {
  begin_block(false);
  text_ += std::string(static_cast<std::size_t>(level), '#') + " " + std::string(text) + "\n";
  return *this;
}

Report& Report::paragraph(std::string_view text) {
  begin_block(false);
  text_ += std::string(text) + "\n";
  return *this;
}

Report& Report::bullet(std::string_view text, int depth) {
  begin_block(true);
  text_ += std::string(2 * static_cast<std::size_t>(depth), ' ') + "- " + std::string(text) + "\n";
  return *this;
}

Report& Report::table(const Table& table) {
  begin_block(false);
  text_ += table.markdown();
  return *this;
}

Report& Report::figure(std::string_view caption, std::string_view file) {
  begin_block(false);
  text_ += "![" + std::string(caption) + "](" + std::string(file) + ")\n";
  return *this;
}

Report& Report::figures(std::string_view heading, const std::vector<FigureLink>& links) {
  this->heading(heading, 3);
  for (const FigureLink& link : links) figure(link.caption, link.file);
  return *this;
}

void Report::write(const std::filesystem::path& dir) const {
  write_text_file(dir / "report.md", text_);
}

void Report::write(const std::filesystem::path& dir, std::string_view files,
                   const std::vector<FigureLink>& figures) {
  paragraph("Files: " + std::string(files));
  for (const FigureLink& link : figures) figure(link.caption, link.file);
  write(dir);
}

}  // namespace talus
