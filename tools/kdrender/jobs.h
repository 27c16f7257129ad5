// A --jobs file: one frame per line, written as kdrender's own per-frame options (the command
// line's options are the defaults of every line). Words split as a shell splits them ('...',
// "..." and backslash quoting); '#' at the start of a word begins a comment; blank lines are skipped.
#pragma once

#include "frame_options.h"

#include <string>
#include <vector>

namespace kdrender {

struct JobLine {
  int line_number = 0;  // 1-based, in the jobs file
  FrameOptions options;
};

// Splits one line into words; throws UsageError on an unterminated quote or a trailing backslash.
std::vector<std::string> split_job_words(const std::string& line);

// Parses every line of `path` onto a copy of `defaults` with add_frame_options. Throws
// kdray::Error when the file cannot be read and UsageError("PATH:LINE: what") for a bad line,
// a file with no frame, or two lines writing the same output.
std::vector<JobLine> read_jobs(const std::string& path, const FrameOptions& defaults);

}  // namespace kdrender
