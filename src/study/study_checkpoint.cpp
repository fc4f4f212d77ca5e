#include "cranesim/study/study_checkpoint.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "cranesim/version.hpp"

namespace cranesim {
namespace {

std::uint64_t fnv1a(const std::string& text, std::uint64_t hash = 0xcbf29ce484222325ULL) {
  for (const unsigned char c : text) hash = (hash ^ c) * 0x100000001b3ULL;
  return hash;
}

void writeAll(int fd, const std::string& text, const std::string& path) {
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error(fmt::format("cannot write the checkpoint '{}': {}", path, std::strerror(errno)));
    done += static_cast<std::size_t>(n);
  }
  if (::fdatasync(fd) != 0) throw std::runtime_error(fmt::format("cannot sync the checkpoint '{}': {}", path, std::strerror(errno)));
}

}  // namespace

StudyCheckpoint::StudyCheckpoint(std::string path, const Study& study)
    : path_(std::move(path)), figures_(study.figures.size()) {
  const std::uint64_t hash = fnv1a(std::string(kVersion), fnv1a(study.scene_text, fnv1a(study.text)));
  header_ = fmt::format("cranesim study checkpoint {:016x}", hash);
}

StudyCheckpoint::~StudyCheckpoint() {
  if (fd_ >= 0) ::close(fd_);
}

bool StudyCheckpoint::exists() const { return std::filesystem::exists(path_); }

std::vector<CaseRow> StudyCheckpoint::load() const {
  std::ifstream in(path_);
  std::string line;
  if (!std::getline(in, line) || line != header_)
    throw SceneError({"--resume", 0, 0}, fmt::format("'{}' is the checkpoint of another study, or of this one before it "
                                                      "or its scene changed; remove it to start anew", path_));
  std::vector<CaseRow> rows;
  while (std::getline(in, line))
    if (!in.eof())  // a last line without its newline was cut short
      if (auto row = decodeRow(line, figures_)) rows.push_back(std::move(*row));
  return rows;
}

void StudyCheckpoint::open(bool fresh) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | (fresh ? O_TRUNC : 0), 0644);
  if (fd_ < 0) throw std::runtime_error(fmt::format("cannot open the checkpoint '{}': {}", path_, std::strerror(errno)));
  if (fresh) writeAll(fd_, header_ + "\n", path_);
}

void StudyCheckpoint::append(const CaseRow& row) { writeAll(fd_, encodeRow(row) + "\n", path_); }

void StudyCheckpoint::remove() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

}  // namespace cranesim
