#include "common/output_folder.hpp"

#include "common/error.hpp"

#include <filesystem>
#include <system_error>

namespace aniso {

void create_output_folder(const std::string& folder) {
  if (folder.empty()) return;
  namespace fs = std::filesystem;
  std::error_code error;
  fs::create_directories(folder, error);
  if (!error && fs::is_directory(folder)) return;
  // Name the part of the path that is in the way, which is what the user has to move.
  fs::path blocking;
  for (fs::path prefix; const fs::path& part : fs::path(folder)) {
    prefix /= part;
    if (fs::exists(prefix) && !fs::is_directory(prefix)) {
      blocking = prefix;
      break;
    }
  }
  if (!blocking.empty())
    throw FileError("output folder '" + folder + "': cannot create it: '" + blocking.string() +
                    "' is a file, not a folder");
  throw FileError("output folder '" + folder +
                  "': cannot create it: " + (error ? error.message() : std::string("it is not a folder")));
}

} // namespace aniso
