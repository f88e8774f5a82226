// ConvertedLogFrameSource: the frames of an ASAM MDF4 bus logging file, read by
// vmass-log-convert (asammdf) and handed over a pipe as candump -l lines. (Vector BLF is read
// natively, BlfLogFrameSource; vmass-log-convert still prints it by hand, with python-can.)
//
// The converter is the `vmass-log-convert` beside the running executable (else on PATH; the
// environment variable VMASS_LOG_CONVERT names another), run by its own interpreter line, or by
// $VMASS_PYTHON when set (a venv with asammdf). Besides frames it writes
//   #!error N WHY     record N of the log could not be read (counted as corrupt, reported)
//   #!fatal WHY       the log cannot be read at all (a missing module, not an MDF4 file):
//                     open() fails with WHY
// A converter that ends with a non-zero status without a fatal line is reported as a problem.
//
// Thread-safety: one reading thread. The child is reaped when the source is destroyed.
#pragma once

#include <sys/types.h>

#include <cstdio>
#include <memory>
#include <string>

#include "vmass/runtime/log_frame_source.hpp"

namespace vmass::runtime {

class ConvertedLogFrameSource final : public LogFrameSource {
 public:
  static std::unique_ptr<ConvertedLogFrameSource> open(const std::string& path,
                                                       can::LogFormat format, std::string* error);
  ~ConvertedLogFrameSource() override;
  ConvertedLogFrameSource(const ConvertedLogFrameSource&) = delete;
  ConvertedLogFrameSource& operator=(const ConvertedLogFrameSource&) = delete;

  std::string_view interface_name() const override { return interface_; }

  /// The converter program this process would run.
  static std::string converter_path();

 protected:
  Read next_frame(can::CanFrame* frame, std::int64_t* position) override;

 private:
  ConvertedLogFrameSource(const std::string& path, can::LogFormat format, FILE* out, pid_t child);
  bool next_line();
  void finish();

  FILE* out_ = nullptr;  ///< the converter's standard output
  pid_t child_ = -1;
  std::string line_, why_, interface_;
  bool have_line_ = false;  ///< line_ holds a line not consumed yet (peeked by open())
  std::int64_t record_ = 0;
};

}  // namespace vmass::runtime
