#include "harness/records/output_folder.h"

#include <filesystem>

#include "harness/util/files.h"

namespace ldm {

OutputFolder::OutputFolder(std::string records_dir, std::string images_dir,
                           std::vector<std::string>* written)
    : records_dir_(std::move(records_dir)), images_dir_(std::move(images_dir)), written_(written) {}

std::string OutputFolder::written(const std::string& file_name) const {
  const std::string path = file(file_name);
  // Logged before the write: a write that fails half-way has nothing to leave behind, but the
  // one after it must not miss an earlier file.
  if (written_) written_->push_back(path);
  return path;
}

std::string OutputFolder::file(const std::string& file_name) const {
  return (std::filesystem::path(images_dir_) / file_name).string();
}

std::string OutputFolder::record_path(const std::string& file_name) const {
  return (std::filesystem::relative(images_dir_, records_dir_) / file_name).string();
}

std::string OutputFolder::write_text(const std::string& file_name, const std::string& text) const {
  write_text_atomically(written(file_name), text);
  return record_path(file_name);
}

bool OutputFolder::contains(const std::string& file_name) const {
  return std::filesystem::exists(file(file_name));
}

std::string OutputFolder::write_exr(const std::string& file_name, const Image& image) const {
  ldm::write_exr(written(file_name), image);
  return record_path(file_name);
}

std::string OutputFolder::write_png(const std::string& file_name, const Image& image) const {
  ldm::write_png(written(file_name), image);
  return record_path(file_name);
}

}  // namespace ldm
