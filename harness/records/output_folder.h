#pragma once
// Where a run's images go: writes each into the images folder and returns the path a record
// stores, relative to the folder holding records.csv (so a run folder can be moved whole).
#include <string>
#include <vector>

#include "harness/image/image.h"

namespace ldm {

class OutputFolder {
 public:
  // `images_dir` is absolute or relative to the working directory, like `records_dir`.
  // `written`, when given, collects the path of every file written (so that a configuration
  // that fails or is abandoned can remove what it wrote).
  OutputFolder(std::string records_dir, std::string images_dir,
               std::vector<std::string>* written = nullptr);

  // <images_dir>/<file_name> written as linear EXR or sRGB PNG; returns its record path.
  std::string write_exr(const std::string& file_name, const Image& image) const;
  std::string write_png(const std::string& file_name, const Image& image) const;
  // A text file (e.g. CSV); the folder is created when missing.
  std::string write_text(const std::string& file_name, const std::string& text) const;
  bool contains(const std::string& file_name) const;
  // The record path of <images_dir>/<file_name>.
  std::string record_path(const std::string& file_name) const;

 private:
  std::string file(const std::string& file_name) const;
  std::string written(const std::string& file_name) const;  // file(), logged
  std::string records_dir_, images_dir_;
  std::vector<std::string>* written_ = nullptr;
};

}  // namespace ldm
