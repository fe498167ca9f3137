#pragma once
// Creating a stage's output folder, with the failure reported as a file error naming the folder
// (std::filesystem's own exception reached users as an "internal error", exit 1).

#include <string>

namespace aniso {

/// Creates `folder` and its parents if missing (nothing for an empty path). FileError (exit 3)
/// naming the folder if it cannot be made: a file of that name, or a file on its path, or no
/// permission.
void create_output_folder(const std::string& folder);

} // namespace aniso
