#include "jobs.h"

#include <kdray/error.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

namespace kdrender {

std::vector<std::string> split_job_words(const std::string& line) {
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  for (size_t i = 0; i < line.size(); ++i) {
    char c = line[i];
    if (c == ' ' || c == '\t' || c == '\r') {
      if (in_word) words.push_back(std::move(word));
      word.clear();
      in_word = false;
    } else if (c == '#' && !in_word) {
      break;
    } else if (c == '\'' || c == '"') {
      size_t end = line.find(c, i + 1);
      if (end == std::string::npos) throw UsageError(std::string("unterminated ") + c + " quote");
      word += line.substr(i + 1, end - i - 1);
      in_word = true;
      i = end;
    } else if (c == '\\') {
      if (i + 1 == line.size()) throw UsageError("a backslash ends the line");
      word += line[++i];
      in_word = true;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (in_word) words.push_back(std::move(word));
  return words;
}

std::vector<JobLine> read_jobs(const std::string& path, const FrameOptions& defaults) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw kdray::Error(path, std::filesystem::exists(path, error) ? "not a regular file" : "no such file");
  }
  std::ifstream in(path);
  if (!in) throw kdray::Error(path, std::string("cannot open: ") + std::strerror(errno));
  std::vector<JobLine> jobs;
  std::map<std::string, int> outputs;  // output -> line writing it
  std::string text;
  for (int number = 1; std::getline(in, text); ++number) {
    const std::string where = path + ":" + std::to_string(number) + ": ";
    std::vector<std::string> words;
    try {
      words = split_job_words(text);
    } catch (const UsageError& e) {
      throw UsageError(where + e.what());
    }
    if (words.empty()) continue;
    JobLine job{number, defaults};
    CLI::App app{"a jobs line"};
    app.name(path + ":" + std::to_string(number));
    app.set_help_flag("");
    add_frame_options(app, job.options);
    std::reverse(words.begin(), words.end());  // CLI11 takes the words last first
    try {
      app.parse(words);
    } catch (const CLI::ParseError& e) {
      throw UsageError(where + e.what());
    }
    if (job.options.output.empty()) throw UsageError(where + "no -o OUTPUT on this line or the command line");
    auto [previous, inserted] = outputs.emplace(job.options.output, number);
    if (!inserted) {
      throw UsageError(where + job.options.output + " is also written by line " + std::to_string(previous->second));
    }
    jobs.push_back(std::move(job));
  }
  if (in.bad()) throw kdray::Error(path, "read error");
  if (jobs.empty()) throw UsageError(path + ": no frames (every line is blank or a comment)");
  return jobs;
}

}  // namespace kdrender
