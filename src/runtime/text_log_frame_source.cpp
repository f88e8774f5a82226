#include "vmass/runtime/text_log_frame_source.hpp"

namespace vmass::runtime {

TextLogFrameSource::TextLogFrameSource(std::unique_ptr<std::istream> in, const std::string& path,
                                       can::LogFormat format,
                                       std::unique_ptr<can::LogLineParser> parser)
    : LogFrameSource(path, format),
      in_(std::move(in)),
      lines_(*in_, can::CandumpReader::kMaxLineBytes),
      parser_(std::move(parser)) {}

TextLogFrameSource::TextLogFrameSource(std::unique_ptr<std::istream> in, io::LineReader lines,
                                       const std::string& path, can::LogFormat format,
                                       std::unique_ptr<can::LogLineParser> parser)
    : LogFrameSource(path, format),
      in_(std::move(in)),
      lines_(std::move(lines)),
      parser_(std::move(parser)) {}

void TextLogFrameSource::set_read_error(const std::string& why) {
  if (problem().empty()) set_problem(path() + ": read error: " + why);
}

std::unique_ptr<TextLogFrameSource> TextLogFrameSource::from_stream(
    std::unique_ptr<std::istream> in, const std::string& name, bool require_time,
    std::string* error) {
  std::string first;
  std::int64_t blank_lines = 0;
  io::LineReader lines(*in, can::CandumpReader::kMaxLineBytes);
  while (lines.next(&first) && first.find_first_not_of(" \t\r") == std::string::npos) {
    first.clear();  // blank lines tell nothing
    ++blank_lines;
  }
  const bool first_overlong = lines.overlong();
  const can::LogFormat format =
      first.empty() ? can::LogFormat::kCandump : can::detect_log_format(first + "\n");
  std::unique_ptr<can::LogLineParser> parser = can::make_log_line_parser(format, require_time);
  if (!parser) {
    if (error) *error = name + ": not a text CAN log (candump -l or screen output, ASC, TRC)";
    return nullptr;
  }
  const std::string read_error = lines.error();
  std::unique_ptr<TextLogFrameSource> source(
      new TextLogFrameSource(std::move(in), std::move(lines), name, format, std::move(parser)));
  source->first_line_ = std::move(first);
  source->line_ = source->first_line_;
  source->have_line_ = !source->line_.empty();
  source->overlong_ = first_overlong;
  if (!read_error.empty()) source->set_read_error(read_error);
  source->line_no_ = blank_lines;
  source->mutable_stats().lines = static_cast<std::uint64_t>(blank_lines);
  source->mutable_stats().comments = static_cast<std::uint64_t>(blank_lines);
  return source;
}

bool TextLogFrameSource::next_line() {
  if (have_line_) {
    have_line_ = false;
    return true;
  }
  if (!problem().empty()) return false;  // a read error ended the log
  const bool got = lines_.next(&line_);
  overlong_ = lines_.overlong();
  if (!got && !lines_.error().empty()) set_read_error(lines_.error());
  return got;
}

FrameSource::Read TextLogFrameSource::next_frame(can::CanFrame* frame, std::int64_t* position) {
  can::CandumpRecord record;
  while (next_line()) {
    ++line_no_;
    ++mutable_stats().lines;
    if (overlong_) {
      report_corrupt(line_no_, "line longer than " +
                                   std::to_string(can::CandumpReader::kMaxLineBytes) + " bytes");
      continue;
    }
    switch (parser_->parse(line_, &record, &why_)) {
      case can::CandumpLine::kFrame:
        if (record.interface != interface_) interface_.assign(record.interface);
        *position = line_no_;
        *frame = record.frame;
        return Read::kFrame;
      case can::CandumpLine::kComment:
        ++mutable_stats().comments;
        break;
      case can::CandumpLine::kCorrupt:
        report_corrupt(line_no_, why_);
        break;
    }
  }
  return Read::kEnd;
}

}  // namespace vmass::runtime
